// Programs written the way other systems write them (tests/golden/tolerant/cases, one kind per
// case and one combining them; docs/interoperability.md): through the jobs every verb and route
// runs (pipeline::trace, verify, post), tolerant (the default) and strict (`--strict`).
// Per case: <case>.trace the tolerant trace and its diagnostics, <case>.strict the strict
// diagnostics, <case>.verify the tolerant verify report, <case>.nc the tolerant linuxcnc post
// (or its diagnostics when the post is refused). NCPOST_UPDATE_GOLDEN=1 rewrites them.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "golden.hpp"
#include "ncpost/pipeline/jobs.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/pipeline/post.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/xslt/xslt.hpp"

namespace ncpost::pipeline {
namespace {

namespace fs = std::filesystem;

const fs::path& cases() {
  static const fs::path dir = test::source_dir() / "tests/golden/tolerant/cases";
  return dir;
}

const Schemas& schemas() {
  static const Schemas s = load_schemas();
  return s;
}

JobContext context(bool strict) {
  JobContext c;
  c.schemas = &schemas();
  c.strict = strict;
  return c;
}

Input input(const fs::path& file) {
  Input in;
  in.name = file.filename().string();
  in.bytes = test::read_file(file);
  return in;
}

std::string lines(const std::vector<diag::FileDiagnostic>& diagnostics) {
  std::string out;
  for (const auto& d : diagnostics) out += diag::format(d) + "\n";
  return out;
}

std::string traced(const fs::path& file, bool strict) {
  std::string text;
  const JobResult r = trace(input(file), context(strict), TraceFormat::Text,
                            [&](std::string_view piece) { text += piece; });
  return text + lines(r.diagnostics);
}

std::string posted(const fs::path& file) {
  xslt::initialise();
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  std::vector<diag::FileDiagnostic> diagnostics;
  const auto linuxcnc = store.load("linuxcnc", diagnostics);
  EXPECT_TRUE(linuxcnc) << lines(diagnostics);
  if (!linuxcnc) return {};
  std::string text;
  const PostJobResult r =
      post(input(file), context(false), *linuxcnc, [&](std::string_view piece) { text += piece; });
  return text + lines(r.diagnostics());
}

std::size_t count(const std::string& text, std::string_view what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::vector<std::string> case_names() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(cases()))
    if (entry.path().extension() == ".stp") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class TolerantGolden : public ::testing::TestWithParam<std::string> {};

TEST_P(TolerantGolden, TraceVerifyAndPostMatchTheirFiles) {
  const fs::path file = cases() / (GetParam() + ".stp");
  const std::string tolerant = traced(file, false);
  const std::string strict = traced(file, true);
  test::expect_golden(tolerant, cases() / (GetParam() + ".trace"));
  // Strict reads the file as written: refused at the check (nothing traced), or read without
  // the variants table, implicit values and second readings of units; never as tolerant does.
  test::expect_golden(strict, cases() / (GetParam() + ".strict"));
  EXPECT_NE(strict, tolerant);
  if (strict.find(": error: EXP-0") != std::string::npos) {
    EXPECT_EQ(strict.find("PROJECT_START"), std::string::npos) << strict;
  }
  EXPECT_EQ(strict.find("INTEROP-"), std::string::npos) << strict;
  const VerifyOutcome verified = verify(input(file), context(false), {});
  test::expect_golden(verify_report_text(verified, GetParam() + ".stp"),
                      cases() / (GetParam() + ".verify"));
  const std::string nc = posted(file);
  test::expect_golden(nc, cases() / (GetParam() + ".nc"));
  // Every assumption is visible: each INTEROP note about the program (not the file's schema
  // name) is a comment of the trace, at its workingstep, and of the posted program.
  const std::size_t notes = count(tolerant, ": note: INTEROP-") - count(tolerant, "INTEROP-001");
  EXPECT_EQ(count(tolerant, "COMMENT(\"ASSUMED "), notes) << tolerant;
  if (nc.find(": error: ") == std::string::npos) {
    EXPECT_EQ(count(nc, "ASSUMED "), notes) << nc;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, TolerantGolden, ::testing::ValuesIn(case_names()));

// `--strict` is today's check: on every program of the golden suites, a strict job reports what
// the schema check reported before the tolerant mode existed (pipeline::load's default, whose
// diagnostics those suites freeze), word for word.
TEST(TolerantStrict, StrictIsTheCheckEveryGoldenCaseFroze) {
  static const express::SchemaRegistry registry;
  ReadOptions options;
  options.name_what_is_not_a_program = false;
  std::size_t files = 0;
  for (const char* suite : {"trace/cases", "features/cases", "verify/cases", "tolerant/cases"}) {
    for (const auto& entry : fs::directory_iterator(test::source_dir() / "tests/golden" / suite)) {
      if (entry.path().extension() != ".stp") continue;
      SCOPED_TRACE(entry.path().string());
      ++files;
      const Program program = read(input(entry.path()), context(true), options);
      const LoadedModel before = load(test::read_file(entry.path()), registry);
      EXPECT_EQ(lines(program.diagnostics),
                lines(diag::with_file(before.diagnostics, entry.path().filename().string())));
    }
  }
  EXPECT_GT(files, 40u);
}

// What a trace says without the tolerant reading's notes and comments, and without call numbers
// (a comment shifts them).
std::string without_assumptions(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    if (line.find("INTEROP-") != std::string_view::npos ||
        line.find("COMMENT(\"ASSUMED ") != std::string_view::npos)
      continue;
    const auto first = line.find_first_not_of(' ');
    if (first != std::string_view::npos && line[first] >= '0' && line[first] <= '9')
      line.remove_prefix(line.find(' ', first) + 1);
    out.append(line).push_back('\n');
  }
  return out;
}

// `--strict` is today's reading of every program of the golden suites: it never notes an
// assumption, and where the tolerant reading assumes nothing that moves the tool (only cutting
// depths the hole's own: INTEROP-004), the tolerant trace is the strict one plus its notes and
// comments. The cases where the tolerant reading changes the motion (a variant, an implicit
// depth, a closed polyline, another unit) are the tolerant suite's, frozen there in both modes.
TEST(TolerantStrict, StrictTracesAreTodaysAndTolerantOnlyAddsNotes) {
  std::size_t compared = 0;
  for (const char* suite : {"trace/cases", "features/cases", "verify/cases"}) {
    for (const auto& entry : fs::directory_iterator(test::source_dir() / "tests/golden" / suite)) {
      if (entry.path().extension() != ".stp") continue;
      SCOPED_TRACE(entry.path().string());
      const std::string strict = traced(entry.path(), true);
      const std::string tolerant = traced(entry.path(), false);
      EXPECT_EQ(strict.find("INTEROP-"), std::string::npos) << strict;
      EXPECT_EQ(strict.find("ASSUMED "), std::string::npos) << strict;
      bool moves = false;
      for (const char* code : {"INTEROP-002", "INTEROP-003", "INTEROP-005", "INTEROP-006",
                               "INTEROP-007", "INTEROP-008"})
        moves = moves || tolerant.find(code) != std::string::npos;
      if (moves || strict.find(": error: EXP-0") != std::string::npos) continue;
      ++compared;
      EXPECT_EQ(without_assumptions(tolerant), without_assumptions(strict));
    }
  }
  EXPECT_GT(compared, 40u);
}

}  // namespace
}  // namespace ncpost::pipeline
