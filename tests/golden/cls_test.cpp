// CL files (APT CL and NX CLSF) traced: golden traces for every file of the corpus's cls/ folder
// and for the project's own programs (tests/golden/cls/cases/*.cls, one per case; a case whose
// first line is `$$ expect: CODE` must report that code). Each golden file is the trace, then the
// diagnostics as "file:line:column: severity: CODE: message", then the options the
// checks' operation-name rules selected ("option: name=value"). NCPOST_UPDATE_GOLDEN=1 rewrites
// them; review the diff.

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "corpus.hpp"
#include "golden.hpp"
#include "ncpost/canon/trace.hpp"
#include "ncpost/cls/checks.hpp"
#include "ncpost/cls/reader.hpp"

namespace ncpost::cls {
namespace {

namespace fs = std::filesystem;

struct Traced {
  std::string text;  // trace, then diagnostics
  ReadResult result;
};

Traced trace_file(const fs::path& file, const ReadOptions& options = {}) {
  Traced t;
  canon::TraceWriter writer([&](std::string_view piece) { t.text += piece; });
  ReadOptions o = options;
  o.program_name = file.stem().string();
  t.result = read(test::read_file(file), writer, o);
  for (const auto& d : t.result.diagnostics)
    t.text += diag::format(d, file.filename().string()) + "\n";
  for (const auto& [option, value] : t.result.selected_options)
    t.text += "option: " + option + "=" + value + "\n";
  return t;
}

std::vector<fs::path> files_in(const fs::path& dir, std::string_view extension = {}) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && (extension.empty() || e.path().extension() == extension))
      out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The checks configuration the own cases run with (tests/golden/cls/checks.json); the case
// files say in their first lines what they expect.
CheckConfig case_checks() {
  std::vector<diag::Diagnostic> d;
  auto config =
      parse_checks(test::read_file(test::source_dir() / "tests/golden/cls/checks.json"), d);
  EXPECT_TRUE(config) << (d.empty() ? "" : d[0].message);
  return config ? std::move(*config) : CheckConfig{};
}

TEST(ClsGolden, CorpusFiles) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto files = files_in(corpus / "cls");
  ASSERT_EQ(files.size(), 4u) << "the corpus's cls/ folder changed: review the goldens";
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    const Traced t = trace_file(file);
    EXPECT_TRUE(t.result.ok());
    for (const auto& d : t.result.diagnostics)
      EXPECT_NE(d.severity, diag::Severity::Error) << diag::format(d, file.filename().string());
    test::expect_golden(
        t.text, test::source_dir() / "tests/golden/cls" / (file.filename().string() + ".trace"));
  }
}

TEST(ClsGolden, OwnPrograms) {
  const CheckConfig checks = case_checks();
  const auto cases = files_in(test::source_dir() / "tests/golden/cls/cases", ".cls");
  ASSERT_GE(cases.size(), 10u);
  for (const auto& file : cases) {
    SCOPED_TRACE(file.filename().string());
    const std::string text = test::read_file(file);
    ReadOptions options;
    options.checks = &checks;
    const Traced t = trace_file(file, options);
    // "$$ expect: CLS-101 CLS-102" on the first line: those codes, and errors only of them.
    std::string expected;
    if (text.rfind("$$ expect:", 0) == 0) expected = text.substr(10, text.find('\n') - 10);
    for (const auto& d : t.result.diagnostics) {
      if (d.severity == diag::Severity::Error) {
        EXPECT_NE(expected.find(std::string(d.code_id())), std::string::npos)
            << "unexpected " << diag::format(d, file.filename().string());
      }
    }
    std::istringstream codes(expected);
    for (std::string code; codes >> code;) {
      const bool found =
          std::any_of(t.result.diagnostics.begin(), t.result.diagnostics.end(),
                      [&](const diag::Diagnostic& d) { return d.code_id() == code; });
      EXPECT_TRUE(found) << "expected " << code << "\n" << t.text;
    }
    fs::path golden = file;
    golden.replace_extension(".trace");
    test::expect_golden(t.text, golden);
  }
}

}  // namespace
}  // namespace ncpost::cls
