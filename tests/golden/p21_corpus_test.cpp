// Golden tests over the real files of the shared corpus (p21/, p21-syntax/, and the P21 twins
// in p28/): each file gives exactly the diagnostics that corpus.tsv lists for it, and every file
// without errors survives write → read with an equal model.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "corpus.hpp"
#include "ncpost/p21/compare.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"

namespace ncpost::p21 {
namespace {

namespace fs = std::filesystem;

struct Expectation {
  std::string file;
  std::string diagnostics;  // "line:column:code ..." or "clean"
};

// Names the case in gtest's output instead of dumping its bytes.
void PrintTo(const Expectation& e, std::ostream* os) {
  *os << e.file;
}

std::vector<Expectation> load_expectations() {
  std::vector<Expectation> out;
  std::ifstream in(test::source_dir() / "tests/golden/p21/corpus.tsv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Expectation e;
    std::getline(fields, e.file, '\t');
    std::getline(fields, e.diagnostics, '\t');
    out.push_back(e);
  }
  return out;
}

std::string actual_diagnostics(const ReadResult& r) {
  std::string out;
  for (const auto& d : r.diagnostics) {
    if (!out.empty()) out += ' ';
    out += std::to_string(d.line) + ":" + std::to_string(d.column) + ":" + std::string(d.code_id());
  }
  return out.empty() ? "clean" : out;
}

std::string full_report(const ReadResult& r, const std::string& name) {
  std::string out;
  for (const auto& d : r.diagnostics) out += diag::format(d, name) + "\n";
  return out;
}

class P21Corpus : public ::testing::TestWithParam<Expectation> {};

TEST_P(P21Corpus, ReadsWithExactlyTheListedDiagnosticsAndRoundTrips) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Expectation& e = GetParam();
  const fs::path path = corpus / e.file;
  ASSERT_TRUE(fs::exists(path)) << path;
  const ReadResult first = read(test::read_file(path));
  EXPECT_EQ(actual_diagnostics(first), e.diagnostics) << full_report(first, e.file);
  if (!first.ok()) return;

  const std::string written = write_to_string(first.model);
  const ReadResult second = read(written);
  ASSERT_TRUE(second.ok()) << full_report(second, e.file + " (rewritten)");
  EXPECT_EQ(first_difference(first.model, second.model), std::nullopt);
  // Writing is deterministic: the second write gives the same bytes.
  EXPECT_EQ(write_to_string(second.model), written);
}

std::string test_name(const ::testing::TestParamInfo<Expectation>& info) {
  std::string name = info.param.file;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Files, P21Corpus, ::testing::ValuesIn(load_expectations()), test_name);

TEST(P21CorpusTable, ListsEveryP21FileOfTheCorpus) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::set<std::string> listed;
  for (const auto& e : load_expectations()) listed.insert(e.file);
  ASSERT_GT(listed.size(), 30u);
  const std::set<std::string> extensions = {".stp", ".stpnc", ".p21", ".ifc"};
  for (const char* folder : {"p21", "p21-syntax", "p28"}) {
    for (const auto& entry : fs::directory_iterator(corpus / folder)) {
      if (!extensions.count(entry.path().extension().string())) continue;
      const std::string rel = std::string(folder) + "/" + entry.path().filename().string();
      EXPECT_TRUE(listed.count(rel)) << rel << " is not in tests/golden/p21/corpus.tsv";
    }
  }
}

// Malformed inputs written by the project: each file states its expected diagnostics on line 1
// as `/* expect: line:column:code ... */`, the way LinuxCNC's bad-input tests do.
class P21Malformed : public ::testing::TestWithParam<std::string> {};

TEST_P(P21Malformed, GivesTheDiagnosticsItsFirstLineStates) {
  const fs::path path = test::source_dir() / "tests/golden/p21-malformed" / GetParam();
  const std::string text = test::read_file(path);
  const std::string first_line = text.substr(0, text.find('\n'));
  const std::string prefix = "/* expect: ";
  ASSERT_EQ(first_line.rfind(prefix, 0), 0u) << "line 1 must be " << prefix << "... */";
  const std::string expected =
      first_line.substr(prefix.size(), first_line.rfind(" */") - prefix.size());
  const ReadResult r = read(text);
  EXPECT_EQ(actual_diagnostics(r), expected) << full_report(r, GetParam());
  EXPECT_FALSE(expected == "clean") << "a malformed case must expect a diagnostic";
}

std::vector<std::string> malformed_cases() {
  std::vector<std::string> out;
  for (const auto& entry :
       fs::directory_iterator(test::source_dir() / "tests/golden/p21-malformed"))
    if (entry.path().extension() == ".stp") out.push_back(entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

INSTANTIATE_TEST_SUITE_P(Cases, P21Malformed, ::testing::ValuesIn(malformed_cases()),
                         [](const auto& param_info) {
                           std::string name =
                               param_info.param.substr(0, param_info.param.size() - 4);
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace ncpost::p21
