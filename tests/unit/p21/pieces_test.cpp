// p21::read with ReadOptions::helpers: a large file read in pieces side by side gives what one
// parser gives, diagnostics included, whichever thread ends up reading which piece; a cut that
// lands inside a literal or a comment, or a piece with something to report, falls back to the
// reading in order; the pieces are really read apart when a helper takes them (pieces > 1), and
// read by the one parser, with nothing to join, when no helper ever starts.

#include "ncpost/parallel/pieces.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "corpus.hpp"
#include "ncpost/p21/compare.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/stream_reader.hpp"
#include "test_support.hpp"

namespace ncpost::p21 {
namespace {

namespace fs = std::filesystem;

// Three ways to lend threads: real ones, a pool that never gets to the task (the caller reads
// every piece), and one that runs each task at once, before the caller's own piece.
struct Lenders {
  parallel::ThreadGroup threads{3};
  parallel::Helpers never{[](parallel::Task) {}, 3};
  parallel::Helpers at_once{[](const parallel::Task& task) { task(); }, 3};
  [[nodiscard]] std::vector<std::pair<const char*, const parallel::Helpers*>> all() const {
    return {{"threads", &threads.helpers()}, {"never", &never}, {"at once", &at_once}};
  }
};

// Pieces of 64 bytes to 2 kB: a small file is cut many times.
ReadOptions in_pieces(const parallel::Helpers* helpers, std::size_t min_piece_bytes = 64,
                      std::size_t max_piece_bytes = 2048) {
  ReadOptions options;
  options.helpers = helpers;
  options.min_piece_bytes = min_piece_bytes;
  options.max_piece_bytes = max_piece_bytes;
  return options;
}

// Checks that reading `text` in pieces gives the same as in order; returns the pieces used.
std::size_t expect_same_in_pieces(const std::string& text, const std::string& name,
                                  const parallel::Helpers* helpers) {
  SCOPED_TRACE(name);
  const ReadResult whole = read(text);
  const ReadResult pieces = read(text, in_pieces(helpers));
  EXPECT_EQ(test::dump(pieces), test::dump(whole));
  EXPECT_EQ(pieces.model.text(), whole.model.text());
  const auto difference = first_difference(pieces.model, whole.model);
  EXPECT_FALSE(difference.has_value()) << *difference;
  EXPECT_EQ(pieces.model.instances().size(), whole.model.instances().size());
  EXPECT_EQ(pieces.model.sections().size(), whole.model.sections().size());
  EXPECT_EQ(pieces.model.header().size(), whole.model.header().size());
  EXPECT_EQ(pieces.model.max_depth(), whole.model.max_depth());
  EXPECT_EQ(pieces.model.keyword_count(), whole.model.keyword_count());
  for (std::size_t k = 0; k < whole.model.keyword_count(); ++k)
    EXPECT_EQ(pieces.model.instance_indices_of(static_cast<KeywordId>(k)).size(),
              whole.model.instance_indices_of(static_cast<KeywordId>(k)).size());
  return pieces.pieces;
}

std::string points(std::size_t first, std::size_t count) {
  std::string data;
  for (std::size_t i = first; i < first + count; ++i) {
    const std::string n = std::to_string(i);
    data += "#" + n + "=CARTESIAN_POINT('p;" + n + "',(" + n + ".,2.5,-3.E-2));\n";
    // Ids above every plain one, and apart from each other: a complex instance, nested lists.
    if (i % 7 == 0)
      data += "#" + n + "0001=(NAMED_UNIT(*)LENGTH_UNIT()SI_UNIT(.MILLI.,.METRE.));\n";
    if (i % 11 == 0) data += "#" + n + "0002=ITEM(LIST_OF((1,(2,(3)))),#" + n + ",.T.);\n";
  }
  return data;
}

std::vector<fs::path> files_in(const fs::path& directory) {
  std::vector<fs::path> out;
  if (!fs::is_directory(directory)) return out;
  for (const auto& entry : fs::recursive_directory_iterator(directory)) {
    const auto ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".stp" || ext == ".step" || ext == ".p21"))
      out.push_back(entry.path());
  }
  return out;
}

TEST(ReadInPieces, ACleanFileIsReadApartWithTheSameResult) {
  const Lenders lenders;
  const std::string text = test::wrap(points(1, 3000));
  // Every piece but the first is read apart by a helper that runs at once; none when the
  // helpers never start; with threads, however the race goes.
  EXPECT_GT(expect_same_in_pieces(text, "at once", &lenders.at_once), 50u);
  EXPECT_EQ(expect_same_in_pieces(text, "never", &lenders.never), 1u);
  EXPECT_GE(expect_same_in_pieces(text, "threads", &lenders.threads.helpers()), 1u);
}

TEST(ReadInPieces, NoHelpersOrASmallFileIsOnePiece) {
  const Lenders lenders;
  const std::string text = test::wrap(points(1, 3000));
  EXPECT_EQ(read(text, in_pieces(nullptr)).pieces, 1u);
  EXPECT_EQ(read(text, in_pieces(&lenders.at_once, text.size(), text.size())).pieces, 1u);
  // Two pieces when the file holds two of the smallest, and no more than one per thread while
  // the pieces are shorter than the longest.
  EXPECT_EQ(read(text, in_pieces(&lenders.at_once, text.size() / 2, text.size())).pieces, 2u);
  EXPECT_EQ(read(text, in_pieces(&lenders.at_once, 64, text.size())).pieces, 4u);
}

// A cut is looked for where a line that ends with ';' is followed by one that starts with '#':
// these put such lines inside a comment, a string and a resource, at every place a cut may fall.
TEST(ReadInPieces, CutsInsideLiteralsAndCommentsChangeNothing) {
  const Lenders lenders;
  const std::string fake = "\n#77=FAKE(1);\n#78=FAKE(2);\n";
  const std::string holders[] = {
      "#9990=A(1); /* commented out:" + fake + "*/\n",
      "#9991=A('a string;" + fake + "');\n",
      "#9992=A('a string;\n  #not-an-instance=;\n');\n",
  };
  for (const auto& holder : holders) {
    std::string data;
    for (int block = 0; block < 40; ++block) data += points(block * 100 + 1, 50) + holder;
    for (const auto& [name, helpers] : lenders.all())
      (void)expect_same_in_pieces(test::wrap(data), name + std::string(" ") + holder, helpers);
  }
}

TEST(ReadInPieces, DiagnosticsInAnyPieceComeOutAsInOrder) {
  const Lenders lenders;
  const std::string broken[] = {
      "#5000=A(,1);\n",             // an empty parameter
      "#5001=A(1)\n",               // a missing ';'
      "#5002=A(#99999999);\n",      // a dangling reference
      "#5003=A((1,2);\n",           // unbalanced
      "#17=A(1);\n",                // a duplicate id
      "#5004=A('never closed);\n",  // a runaway string
      "ENDSEC;\nDATA;\n",           // a second DATA section in the middle of a piece
      "#5005=A(1.E999);\n",         // a number out of range
  };
  for (std::size_t at : {std::size_t{5}, std::size_t{500}, std::size_t{1200}, std::size_t{2990}})
    for (const auto& bad : broken) {
      const std::string text = test::wrap(points(1, at) + bad + points(at + 1, 3000 - at));
      for (const auto& [name, helpers] : lenders.all())
        (void)expect_same_in_pieces(
            text, name + std::string(" at ") + std::to_string(at) + " " + bad, helpers);
    }
}

TEST(ReadInPieces, MalformedCasesAndExamples) {
  const Lenders lenders;
  std::size_t count = 0;
  for (const char* folder : {"tests/golden/p21-malformed", "examples"})
    for (const auto& file : files_in(ncpost::test::source_dir() / folder)) {
      (void)expect_same_in_pieces(ncpost::test::read_file(file), file.filename(),
                                  &lenders.threads.helpers());
      ++count;
    }
  EXPECT_GT(count, 10u);
}

TEST(ReadInPieces, CorpusFiles) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Lenders lenders;
  std::size_t count = 0;
  std::size_t apart = 0;
  for (const char* folder : {"p21", "p21-syntax"})
    for (const auto& file : files_in(corpus / folder)) {
      const std::string text = ncpost::test::read_file(file);
      for (const auto& [name, helpers] : lenders.all()) {
        const std::size_t pieces =
            expect_same_in_pieces(text, file.filename().string() + " " + name, helpers);
        if (helpers == &lenders.at_once) apart += pieces > 1;
      }
      ++count;
    }
  EXPECT_GT(count, 20u);
  EXPECT_GT(apart, count / 2) << "most corpus files have one instance per line and are cut";
}

TEST(ReadInPieces, TheRestOfAStreamedFileToo) {
  const Lenders lenders;
  const std::string text = test::wrap(points(1, 3000));
  const ReadResult whole = read(text);
  for (const auto& [name, helpers] : lenders.all()) {
    SCOPED_TRACE(name);
    StreamReader reader(text.size(), in_pieces(helpers));
    ASSERT_TRUE(reader.append(std::string_view(text).substr(0, text.size() / 5)));
    reader.read_more(reader.appended());
    ASSERT_FALSE(reader.gave_up());
    ASSERT_TRUE(reader.append(std::string_view(text).substr(text.size() / 5)));
    const ReadResult streamed = reader.finish();
    if (helpers == &lenders.at_once) {
      EXPECT_GT(streamed.pieces, 50u);
    } else if (helpers == &lenders.never) {
      EXPECT_EQ(streamed.pieces, 1u);
    }
    EXPECT_EQ(test::dump(streamed), test::dump(whole));
    EXPECT_FALSE(first_difference(streamed.model, whole.model).has_value());
  }
}

TEST(ReadInPieces, ACancelStopsEveryPiece) {
  const Lenders lenders;
  const std::string text = test::wrap(points(1, 20000));
  std::atomic<bool> cancel{true};
  ReadOptions options = in_pieces(&lenders.threads.helpers());
  options.cancel = &cancel;
  const ReadResult r = read(text, options);
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.model.instances().empty());
}

}  // namespace
}  // namespace ncpost::p21
