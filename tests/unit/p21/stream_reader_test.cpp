// p21::StreamReader gives what p21::read gives, whatever pieces the text arrives in: the same
// model and the same diagnostics (line, column, code and message), for clean files and for every
// malformed case; it reads while the text arrives (not all at the end) when the file is clean;
// and ReadOptions::cancel stops either reader.

#include "ncpost/p21/stream_reader.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "corpus.hpp"
#include "ncpost/p21/compare.hpp"
#include "test_support.hpp"

namespace ncpost::p21 {
namespace {

namespace fs = std::filesystem;

std::string report(const ReadResult& r) {
  std::string out;
  for (const auto& d : r.diagnostics) out += diag::format(d, "f") + "\n";
  return out;
}

// Appends `text` in pieces of `piece` bytes (0: pseudo-random sizes), reading after each one.
ReadResult read_in_pieces(const std::string& text, std::size_t piece, bool* gave_up = nullptr,
                          std::uint32_t seed = 1) {
  StreamReader reader(text.size());
  std::mt19937 random(seed);
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t n =
        piece != 0 ? piece : std::uniform_int_distribution<std::size_t>(1, 300)(random);
    const std::size_t take = std::min(n, text.size() - at);
    EXPECT_TRUE(reader.append(std::string_view(text).substr(at, take)));
    at += take;
    reader.read_more(reader.appended());
  }
  if (gave_up != nullptr) *gave_up = reader.gave_up();
  return reader.finish();
}

// A clean file has to be read as it arrives, not again at the end, unless `may_give_up`.
void expect_same_as_read(const std::string& text, const std::string& name,
                         bool may_give_up = false) {
  const ReadResult whole = read(text);
  const bool must_stream = whole.diagnostics.empty() && !may_give_up;
  for (const std::size_t piece : {std::size_t{1}, std::size_t{7}, std::size_t{64},
                                  std::size_t{4096}, std::size_t{0}, text.size() + 1}) {
    SCOPED_TRACE(name + " in pieces of " + std::to_string(piece));
    bool gave_up = false;
    const ReadResult streamed = read_in_pieces(text, piece, &gave_up);
    EXPECT_EQ(report(streamed), report(whole));
    if (must_stream && piece < text.size()) {
      EXPECT_FALSE(gave_up);
    }
    EXPECT_EQ(streamed.model.text(), whole.model.text());
    const auto difference = first_difference(streamed.model, whole.model);
    EXPECT_FALSE(difference.has_value()) << *difference;
    EXPECT_EQ(streamed.model.sections().size(), whole.model.sections().size());
    EXPECT_EQ(streamed.model.header().size(), whole.model.header().size());
  }
}

std::vector<fs::path> files_in(const fs::path& directory) {
  std::vector<fs::path> out;
  if (!fs::is_directory(directory)) return out;
  for (const auto& entry : fs::recursive_directory_iterator(directory)) {
    const auto ext = entry.path().extension().string();
    if (entry.is_regular_file() &&
        (ext == ".stp" || ext == ".step" || ext == ".p21" || ext == ".stpnc" || ext == ".ifc"))
      out.push_back(entry.path());
  }
  return out;
}

TEST(StreamReader, MalformedCasesGiveTheSameDiagnostics) {
  const auto files = files_in(ncpost::test::source_dir() / "tests/golden/p21-malformed");
  ASSERT_GT(files.size(), 10u);
  for (const auto& file : files)
    expect_same_as_read(ncpost::test::read_file(file), file.filename());
}

TEST(StreamReader, ExamplesGiveTheSameModel) {
  const auto files = files_in(ncpost::test::source_dir() / "examples");
  ASSERT_FALSE(files.empty());
  for (const auto& file : files)
    expect_same_as_read(ncpost::test::read_file(file), file.filename());
}

TEST(StreamReader, CorpusFilesGiveTheSameResult) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::size_t count = 0;
  for (const char* folder : {"p21", "p21-syntax", "p28"})
    for (const auto& file : files_in(corpus / folder)) {
      expect_same_as_read(ncpost::test::read_file(file), file.filename());
      ++count;
    }
  EXPECT_GT(count, 20u);
}

// Literals and comments that hold the characters the cut looks for.
TEST(StreamReader, SemicolonsInsideLiteralsAndComments) {
  const std::string cases[] = {
      test::wrap("#1=A('a;b','c'';''d');\n#2=B(#1);"),
      test::wrap("/* ; ' */ #1=A(1); /* *; */ #2=A(2);/**/#3=A(3);/*/ ; */#4=A(4);"),
      test::wrap("#1=A('line one;\nline two;');\n#2=A('x');"),
      test::wrap("#1=A('\\S\\';x');\n#2=A('y;');"),        // an escaped apostrophe
      test::wrap("#1=A('runs away;\n#2=A(2);\n#3=A(3);"),  // a string never closed
      test::wrap("#1=A(\"0F;\");\n#2=A(.E;N.);"),          // broken literals with a ';'
      test::wrap("#1=A(1) /* never closed ; "),            // comment runs to the end
      test::wrap("#1=A(1);#2=A(2)\n#3=A(3);"),             // a missing ';'
      test::wrap("#1=A(1);") + "SIGNATURE;QUJD;ENDSEC;",   // ed.3 signature after the end
      test::wrap("#1=A(1);") + "junk;",
      "garbage;" + test::wrap("#1=A(1);"),
  };
  for (const auto& text : cases) expect_same_as_read(text, text.substr(text.find("DATA")));
  // ANCHOR and REFERENCE sections (rare) are not read in pieces: a cut inside one makes the
  // stream reader give up, and the result is still the same.
  expect_same_as_read(
      "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'2;1');FILE_NAME('','',(''),(''),'','','');"
      "FILE_SCHEMA(('S'));ENDSEC;REFERENCE;#5=<http://x;y>;ENDSEC;DATA;#1=A(#5);ENDSEC;"
      "END-ISO-10303-21;",
      "reference", true);
}

std::string large_file(std::size_t instances) {
  std::string data;
  for (std::size_t i = 1; i <= instances; ++i)
    data += "#" + std::to_string(i) + "=CARTESIAN_POINT('p;" + std::to_string(i) + "',(" +
            std::to_string(i) + ".,2.5,-3.E-2));\n";
  return test::wrap(data);
}

TEST(StreamReader, ReadsWhileTheTextArrives) {
  const std::string text = large_file(20000);
  StreamReader reader(text.size());
  const std::size_t half = text.size() / 2;
  ASSERT_TRUE(reader.append(std::string_view(text).substr(0, half)));
  reader.read_more(reader.appended());
  EXPECT_FALSE(reader.gave_up());
  // Everything up to the last whole instance of the first half has been read already.
  EXPECT_GT(reader.read_through(), half - 200);
  EXPECT_LE(reader.read_through(), half);
  ASSERT_TRUE(reader.append(std::string_view(text).substr(half)));
  EXPECT_FALSE(reader.append("x")) << "more than the announced size is refused";
  const ReadResult streamed = reader.finish();
  const ReadResult whole = read(text);
  EXPECT_TRUE(streamed.ok()) << report(streamed);
  EXPECT_EQ(streamed.model.instances().size(), 20000u);
  EXPECT_FALSE(first_difference(streamed.model, whole.model).has_value());
}

TEST(StreamReader, GivesUpAtTheFirstDiagnosticAndReadsAgainAtTheEnd) {
  const std::string text = test::wrap("#1=A(1);\n#2=A(,2);\n#3=A(#9);");
  StreamReader reader(text.size());
  ASSERT_TRUE(reader.append(text.substr(0, text.find("#3"))));
  reader.read_more(reader.appended());
  EXPECT_TRUE(reader.gave_up());
  EXPECT_EQ(reader.read_through(), 0u);
  ASSERT_TRUE(reader.append(text.substr(text.find("#3"))));
  const ReadResult streamed = reader.finish();
  EXPECT_EQ(report(streamed), report(read(text)));
  EXPECT_NE(test::find_code(streamed, "P21-027"), nullptr) << report(streamed);
}

TEST(StreamReader, TakeTextGivesTheBytesBack) {
  StreamReader reader(11);
  ASSERT_TRUE(reader.append("<?xml "));
  reader.read_more(reader.appended());
  EXPECT_EQ(reader.arrived(6), "<?xml ");
  ASSERT_TRUE(reader.append("x/>\n\n"));
  EXPECT_EQ(reader.take_text(), "<?xml x/>\n\n");
}

TEST(ReadCancel, AFlagSetBeforehandStopsTheRead) {
  const std::string text = large_file(50000);
  std::atomic<bool> cancel{true};
  ReadOptions options;
  options.cancel = &cancel;
  const ReadResult r = read(text, options);
  EXPECT_TRUE(r.cancelled);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(r.diagnostics.empty());
  EXPECT_TRUE(r.model.instances().empty());
  cancel = false;
  const ReadResult again = read(text, options);
  EXPECT_FALSE(again.cancelled);
  EXPECT_TRUE(again.ok()) << report(again);
}

TEST(ReadCancel, StopsInsideOneEnormousInstance) {
  // One instance of a million values: the flag is looked at per token, not per instance.
  std::string list;
  for (int i = 0; i < 1000000; ++i) list += i == 0 ? "1" : ",1";
  const std::string text = test::wrap("#1=A((" + list + "));");
  std::atomic<bool> cancel{true};
  ReadOptions options;
  options.cancel = &cancel;
  EXPECT_TRUE(read(text, options).cancelled);
}

TEST(ReadCancel, StreamReaderStopsToo) {
  const std::string text = large_file(20000);
  std::atomic<bool> cancel{false};
  ReadOptions options;
  options.cancel = &cancel;
  StreamReader reader(text.size(), options);
  ASSERT_TRUE(reader.append(std::string_view(text).substr(0, text.size() / 2)));
  reader.read_more(reader.appended());
  EXPECT_GT(reader.read_through(), 0u);
  cancel = true;
  ASSERT_TRUE(reader.append(std::string_view(text).substr(text.size() / 2)));
  reader.read_more(reader.appended());
  const ReadResult r = reader.finish();
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.model.instances().empty());
}

}  // namespace
}  // namespace ncpost::p21
