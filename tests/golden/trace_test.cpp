// The interpreter's canonical trace: golden files for NIST's ex1E and for the project's own
// programs (tests/golden/trace/cases), plus the numbers checked by hand from the files' own
// coordinates. NCPOST_UPDATE_GOLDEN=1 rewrites the golden files; review the diff.

#include "ncpost/canon/trace.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "corpus.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::stepnc {
namespace {

namespace fs = std::filesystem;

struct Traced {
  std::string trace;
  std::vector<diag::Diagnostic> diagnostics;  // loading and interpreting
};

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

Traced trace_of(const fs::path& file, const InterpretOptions& options = {}) {
  pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry());
  Traced out;
  out.diagnostics = loaded.diagnostics;
  EXPECT_TRUE(loaded.ok()) << file;
  const AttributeReader attributes(loaded.model, *loaded.schema);
  canon::TraceWriter writer([&](std::string_view piece) { out.trace += piece; });
  auto result = interpret(loaded.model, attributes, writer, options);
  out.diagnostics.insert(out.diagnostics.end(), result.diagnostics.begin(),
                         result.diagnostics.end());
  return out;
}

// The trace, then each diagnostic as "file:line:column: severity: CODE: message".
std::string golden_text(const Traced& t, const std::string& name) {
  std::string text = t.trace;
  for (const auto& d : t.diagnostics) text += diag::format(d, name) + "\n";
  return text;
}

void expect_golden(const std::string& actual, const fs::path& golden) {
  if (const char* update = std::getenv("NCPOST_UPDATE_GOLDEN");
      update && std::string(update) == "1") {
    std::ofstream(golden, std::ios::binary) << actual;
    return;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden;
  EXPECT_EQ(actual, test::read_file(golden)) << "differs from " << golden;
}

bool has_line(const std::string& trace, const std::string& call) {
  return trace.find(" " + call + "\n") != std::string::npos;
}

// ex1E: checked by hand against the file's coordinates (the numbers below), then frozen as the
// golden trace. Placement rule: a feature's toolpath is in the feature's placement, inside the
// workpiece set-up, inside the setup (all identity here but the features' own placements).
TEST(TraceCorpus, NistExample1E) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Traced t = trace_of(corpus / "p21/nist_toolkit_ex1E.stp");
  EXPECT_TRUE(t.diagnostics.empty()) << golden_text(t, "ex1E");
  // #511 (91.9, -13.5, -2.5) on PLANAR FACE1 placed at z = 5 (#77/#104): the example.
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_FEED(91.9000, -13.5000, 2.5000)"));
  // Second pass #611 (…, -5.0) → z 0.
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_FEED(91.9000, 133.5000, 0.0000)"));
  // The rapid #710 is in workpiece coordinates: (6.4, -13.5, 2.5) is where pass 1 ended.
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_TRAVERSE(6.4000, -13.5000, 15.0000)"));
  // Pocket #18 placed at (70, 70, 0) with ref_direction (0, 1, 0) (#84): local (x, y) maps to
  // (70 - y, 70 + x). Helix #906 ends at local (-15, -7.2, -5.9) → (77.2, 55, -5.9), about the
  // axis through local (-15, 0) → (70, 55); it rises 20.9 at pitch 7.976846 = 943.2°, clockwise
  // from 133.2° to -90°: two full turns and 223.2°, so rs274 rotation -3.
  EXPECT_TRUE(has_line(t.trace, "ARC_FEED(77.2000, 55.0000, 70.0000, 55.0000, -3, -5.9000)"));
  // Hole #17 at (20, 60, 0): the drill path #303 starts at local (0, 0, 10).
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_TRAVERSE(20.0000, 60.0000, 10.0000)"));
  // Three tool changes after the first load: mill #39, drill #44, reamer #47, mill #39 again.
  std::size_t changes = 0;
  for (std::size_t at = 0; (at = t.trace.find("CHANGE_TOOL(", at)) != std::string::npos; ++at)
    ++changes;
  EXPECT_EQ(changes, 4u);
  // Technology #40: feed 0.04 m/s = 2400 mm/min; spindle -12 rev/s = 720 rpm clockwise.
  EXPECT_TRUE(has_line(t.trace, "SET_FEED_RATE(2400.0000)"));
  EXPECT_TRUE(has_line(t.trace, "SET_SPINDLE_SPEED(720.0000)"));
  expect_golden(golden_text(t, "nist_toolkit_ex1E.stp"),
                test::source_dir() / "tests/golden/trace/nist_toolkit_ex1E.trace");
}

// ex1 is feature-based (no toolpaths): its paths are generated (issue 5, docs/features.md;
// tests/golden/features compares them with ex1E).
TEST(TraceCorpus, NistExample1IsGeneratedFromFeatures) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Traced t = trace_of(corpus / "p21/nist_toolkit_ex1.stp");
  for (const auto& d : t.diagnostics)
    EXPECT_NE(d.severity, diag::Severity::Error) << diag::format(d, "ex1");
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_FEED(91.9000, 133.5000, 2.5000)"));
}

TEST(TraceCorpus, ToolTableGivesPocketsAndOffsets) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::vector<diag::Diagnostic> table_diagnostics;
  InterpretOptions options;
  options.tools = read_tool_table(test::read_file(corpus / "gcode/nist_toolkit_iso14649.tool_ex1"),
                                  table_diagnostics);
  EXPECT_TRUE(table_diagnostics.empty());
  ASSERT_EQ(options.tools->entries.size(), 3u);
  const Traced t = trace_of(corpus / "p21/nist_toolkit_ex1E.stp", options);
  EXPECT_TRUE(has_line(t.trace, "CHANGE_TOOL(3)"));                   // 'MILL 18MM'
  EXPECT_TRUE(has_line(t.trace, "USE_TOOL_LENGTH_OFFSET(70.0000)"));  // SPIRAL_DRILL_20MM
  EXPECT_TRUE(has_line(t.trace, "CHANGE_TOOL(6)"));                   // "REAMER_22MM"
}

TEST(TraceOwn, RotatedSetupByHand) {
  // Setup #30: rotated 90° about Z (ref_direction +Y) and shifted -14.7 in Z. Feature at
  // (10, 0, 0); toolpath point (5, 0, -1) → workpiece (15, 0, -1) → machine (-0, 15, -15.7);
  // (5, 20, -1) → (15, 20, -1) → (-20, 15, -15.7). Security plane z 50 → 35.3.
  const Traced t =
      trace_of(test::source_dir() / "tests/golden/trace/cases/placement-rotated-setup.stp");
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_FEED(0.0000, 15.0000, -15.7000)"));
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_FEED(-20.0000, 15.0000, -15.7000)"));
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_TRAVERSE(0.0000, 15.0000, 35.3000)"));
}

TEST(TraceOwn, CurvesByHand) {
  const Traced t = trace_of(test::source_dir() / "tests/golden/trace/cases/curves.stp");
  EXPECT_TRUE(t.diagnostics.empty()) << golden_text(t, "curves");
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_FEED(10.0000, 0.0000, 0.0000)"));  // line, t = 2 × 5
  EXPECT_TRUE(has_line(t.trace, "ARC_FEED(0.0000, 10.0000, 0.0000, 0.0000, 1, 0.0000)"));
  EXPECT_TRUE(has_line(t.trace, "ARC_FEED(10.0000, 0.0000, 0.0000, 0.0000, -1, 0.0000)"));
  EXPECT_TRUE(has_line(t.trace, "STRAIGHT_FEED(20.0000, 0.0000, 0.0000)"));  // reversed segment
  // Helix: rise 4 at pitch 2 = exactly two turns, ending at the start's angle: rotation -2.
  EXPECT_TRUE(has_line(t.trace, "ARC_FEED(20.0000, 0.0000, 25.0000, 0.0000, -2, -4.0000)"));
  EXPECT_NE(t.trace.find("NURBS_FEED(2, "), std::string::npos);
}

TEST(TraceOwn, ErrorsNameTheInstance) {
  const Traced t = trace_of(test::source_dir() / "tests/golden/trace/cases/errors.stp");
  ASSERT_EQ(t.diagnostics.size(), 2u) << golden_text(t, "errors");
  EXPECT_EQ(t.diagnostics[0].code_id(), "STEPNC-015");
  EXPECT_NE(t.diagnostics[0].message.find("#70"), std::string::npos);
  EXPECT_EQ(t.diagnostics[1].code_id(), "STEPNC-012");
  EXPECT_NE(t.diagnostics[1].message.find("#18"), std::string::npos);
  EXPECT_NE(t.diagnostics[1].message.find("#19"), std::string::npos);
}

class TraceGolden : public ::testing::TestWithParam<std::string> {};

TEST_P(TraceGolden, MatchesItsTraceFile) {
  const fs::path input = test::source_dir() / "tests/golden/trace/cases" / (GetParam() + ".stp");
  const Traced t = trace_of(input);
  expect_golden(golden_text(t, GetParam() + ".stp"),
                test::source_dir() / "tests/golden/trace/cases" / (GetParam() + ".trace"));
}

INSTANTIATE_TEST_SUITE_P(Cases, TraceGolden,
                         ::testing::Values("placement-rotated-setup", "curves", "executables",
                                           "errors", "five-axis"),
                         [](const auto& param_info) {
                           std::string n = param_info.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
}  // namespace ncpost::stepnc
