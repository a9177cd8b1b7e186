// AP238 AIM programs: the corpus's milling programs traced against their golden traces, its
// turning programs refused by name, the truncated AIM stub still refused by the reader. The
// goldens were checked by hand against the files' own numbers (the tests below say which) and
// then frozen; NCPOST_UPDATE_GOLDEN=1 rewrites them (review the diff).

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>

#include "corpus.hpp"
#include "ncpost/ap238/ap238.hpp"
#include "ncpost/canon/trace.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/jobs.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/verify/verify.hpp"

namespace ncpost::ap238 {
namespace {

namespace fs = std::filesystem;

struct Traced {
  std::string trace;
  std::vector<diag::Diagnostic> diagnostics;  // loading and interpreting
  bool loaded = false;
};

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

Traced trace_of(const fs::path& file, const stepnc::InterpretOptions& options = {}) {
  pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry());
  Traced out;
  out.diagnostics = loaded.diagnostics;
  out.loaded = loaded.ok();
  if (!loaded.ok()) return out;
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  canon::TraceWriter writer([&](std::string_view piece) { out.trace += piece; });
  auto result = ap238::interpret(loaded.model, attributes, writer, options);
  out.diagnostics.insert(out.diagnostics.end(), result.diagnostics.begin(),
                         result.diagnostics.end());
  return out;
}

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

std::size_t errors(const Traced& t) {
  return static_cast<std::size_t>(
      std::count_if(t.diagnostics.begin(), t.diagnostics.end(),
                    [](const diag::Diagnostic& d) { return d.severity == diag::Severity::Error; }));
}

// The milling programs of p21-aim/ (every file but the two turning ones).
std::vector<std::string> milling_files(const fs::path& corpus) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(corpus / "p21-aim"))
    if (e.path().extension() == ".stpnc") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  std::erase_if(names, [](const std::string& n) {
    return n == "nextnc_autodesk-face" || n == "nextnc_autodesk-profile";
  });
  return names;
}

TEST(Ap238Corpus, EveryMillingProgramMatchesItsGoldenTrace) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto names = milling_files(corpus);
  EXPECT_EQ(names.size(), 17u);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Traced t = trace_of(corpus / "p21-aim" / (name + ".stpnc"));
    ASSERT_TRUE(t.loaded);
    EXPECT_EQ(errors(t), 0u) << golden_text(t, name);
    EXPECT_TRUE(has_line(t.trace, "PROGRAM_END()")) << t.trace;
    expect_golden(golden_text(t, name + ".stpnc"),
                  test::source_dir() / "tests/golden/ap238/corpus" / (name + ".trace"));
  }
}

// The two turning programs are refused before any canonical call, by an error that names turning
// and the instance that makes the program a turning one.
TEST(Ap238Corpus, TurningProgramsAreRefusedNamingTurning) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  for (const char* name : {"nextnc_autodesk-face", "nextnc_autodesk-profile"}) {
    SCOPED_TRACE(name);
    const Traced t = trace_of(corpus / "p21-aim" / (std::string(name) + ".stpnc"));
    ASSERT_TRUE(t.loaded);  // the schema check passes: the refusal is the interpreter's
    EXPECT_TRUE(t.trace.empty()) << t.trace;
    ASSERT_EQ(errors(t), 1u) << golden_text(t, name);
    const auto refusal =
        std::find_if(t.diagnostics.begin(), t.diagnostics.end(),
                     [](const auto& d) { return d.severity == diag::Severity::Error; });
    EXPECT_EQ(refusal->code_id(), "AP238-005");
    EXPECT_NE(refusal->message.find("turning programs are not supported"), std::string::npos)
        << refusal->message;
    EXPECT_NE(refusal->message.find("#48 (TURNING_TYPE_OPERATION)"), std::string::npos)
        << refusal->message;
  }
}

// The truncated STEP-NC Maker file keeps being refused by the reader, which names each
// reference to an instance that was cut out; nothing is interpreted.
TEST(Ap238Corpus, TruncatedStubIsRefusedWithItsDanglingReferences) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Traced t = trace_of(corpus / "p21/efrainrodriguez_exp2.stpnc");
  EXPECT_FALSE(t.loaded);
  EXPECT_TRUE(t.trace.empty());
  std::string all;
  for (const auto& d : t.diagnostics) all += diag::format(d, "exp2") + "\n";
  EXPECT_NE(all.find("P21-040: #20 used by #11 attribute 5 is not defined"), std::string::npos)
      << all;
  EXPECT_NE(all.find("P21-040: #18 used by #13 attribute 3 is not defined"), std::string::npos)
      << all;
}

// inspect: the tree of an AIM program in the ARM's JSON shape (docs/inspect.md).
TEST(Ap238Corpus, InspectGivesTheArmShape) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto file = corpus / "p21-aim/nextnc_autodesk-mill-toolchange.stpnc";
  pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry());
  ASSERT_TRUE(loaded.ok());
  const stepnc::ProgramInfo info = ap238::inspect(loaded.model, *loaded.schema);
  EXPECT_TRUE(info.diagnostics.empty());
  const nlohmann::ordered_json json = pipeline::program_info_json(info);
  const auto& main = json["project"]["main_workplan"];
  EXPECT_EQ(main["type"], "MACHINING_WORKPLAN");
  ASSERT_EQ(main["elements"].size(), 2u);
  EXPECT_EQ(main["elements"][1]["name"], "2D-Contour");
  EXPECT_EQ(main["elements"][1]["operation"]["type"], "MILLING_TYPE_OPERATION");
  EXPECT_EQ(main["elements"][1]["tool"]["name"], "2");
  EXPECT_EQ(json["tools"].size(), 2u);
  EXPECT_EQ(json["tools"][1]["number"], 2);
  EXPECT_EQ(json["statistics"]["workingsteps"], 2);
  expect_golden(
      json.dump(2) + "\n",
      test::source_dir() / "tests/golden/ap238/corpus/nextnc_autodesk-mill-toolchange.json");
}

// ---------------------------------------------------------------------------------------------
// The project's own programs, each written in the ARM (cases/<name>.arm.stp) and converted by
// hand to the AIM (cases/<name>.aim.stp, following docs/ap238.md). The AIM file keeps the ARM
// ids of the instances that stand for ARM objects, so the two canonical programs must be
// identical call for call; only the entity names in the structure markers differ (PROJECT /
// MACHINING_PROJECT, WORKPLAN / MACHINING_WORKPLAN, SETUP / MACHINING_SETUP, RAPID_MOVEMENT /
// MACHINING_RAPID_MOVEMENT), as each names its own file's entity.

Traced arm_trace_of(const fs::path& file) {
  pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry());
  Traced out;
  out.diagnostics = loaded.diagnostics;
  out.loaded = loaded.ok();
  if (!loaded.ok()) return out;
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  canon::TraceWriter writer([&](std::string_view piece) { out.trace += piece; });
  auto result = stepnc::interpret(loaded.model, attributes, writer, {});
  out.diagnostics.insert(out.diagnostics.end(), result.diagnostics.begin(),
                         result.diagnostics.end());
  return out;
}

// The trace with the entity name of each structure marker left out.
std::string without_marker_entities(const std::string& trace) {
  static const std::regex marker(
      R"(((?:PROJECT|WORKPLAN|SETUP|WORKINGSTEP)_(?:BEGIN|END)\(#\d+), [A-Z_0-9]+,)");
  return std::regex_replace(trace, marker, "$1,");
}

class ArmEqualsAim : public ::testing::TestWithParam<std::string> {};

TEST_P(ArmEqualsAim, SameCanonicalProgram) {
  const fs::path cases = test::source_dir() / "tests/golden/ap238/cases";
  const Traced arm = arm_trace_of(cases / (GetParam() + ".arm.stp"));
  const Traced aim = trace_of(cases / (GetParam() + ".aim.stp"));
  ASSERT_TRUE(arm.loaded) << golden_text(arm, GetParam() + ".arm.stp");
  ASSERT_TRUE(aim.loaded) << golden_text(aim, GetParam() + ".aim.stp");
  EXPECT_TRUE(arm.diagnostics.empty()) << golden_text(arm, GetParam() + ".arm.stp");
  EXPECT_TRUE(aim.diagnostics.empty()) << golden_text(aim, GetParam() + ".aim.stp");
  EXPECT_GT(std::count(aim.trace.begin(), aim.trace.end(), '\n'), 25);
  EXPECT_EQ(without_marker_entities(arm.trace), without_marker_entities(aim.trace));
  expect_golden(golden_text(aim, GetParam() + ".aim.stp"), cases / (GetParam() + ".trace"));
}

// The numbers, checked by hand. own-mill-mm: set-up rotated 90 degrees about Z (x → y) and
// shifted -14.7 in Z, workpiece at (5, 0, 0) in it, feature at (10, 0, 0) in the workpiece: the
// line's end (10, 0, 0) is (25, 0, 0) in the set-up, (0, 25, -14.7) on the machine; the
// security plane z 50 is 35.3; 0.02 m/s is 1200 mm/min, -3000 rev/min is 3000 rpm clockwise;
// the tool-axis direction (0, 0.1, 1) turns with the set-up to (-0.0995, 0, 0.9950).
// own-mill-inch: 1 in = 25.4 mm, 10 in/min = 254 mm/min, 20 rev/s = 1200 rpm, 0.025 min =
// 1.5 s, the arc's -90 .. 0 degrees about (1, 1) in ends at (2, 1) in = (50.8, 25.4) mm.
TEST(Ap238Own, NumbersCheckedByHand) {
  const fs::path cases = test::source_dir() / "tests/golden/ap238/cases";
  const Traced mm = trace_of(cases / "own-mill-mm.aim.stp");
  EXPECT_TRUE(has_line(mm.trace, "STRAIGHT_FEED(0.0000, 25.0000, -14.7000)"));
  EXPECT_TRUE(has_line(mm.trace, "STRAIGHT_TRAVERSE(0.0000, 15.0000, 35.3000)"));
  EXPECT_TRUE(has_line(mm.trace, "SET_FEED_RATE(1200.0000)"));
  EXPECT_TRUE(has_line(mm.trace, "SET_SPINDLE_SPEED(3000.0000)"));
  EXPECT_TRUE(has_line(mm.trace, "START_SPINDLE_CLOCKWISE()"));
  EXPECT_TRUE(
      has_line(mm.trace, "STRAIGHT_FEED(-10.0000, 40.0000, -13.7000, -0.0995, 0.0000, 0.9950)"));
  EXPECT_TRUE(has_line(mm.trace, "CHANGE_TOOL(7)"));    // its name is a number
  EXPECT_TRUE(has_line(mm.trace, "CHANGE_TOOL(901)"));  // its name is not: its P21 id
  EXPECT_TRUE(has_line(mm.trace, "USE_TOOL_LENGTH_OFFSET(80.0000)"));
  const Traced inch = trace_of(cases / "own-mill-inch.aim.stp");
  EXPECT_TRUE(has_line(inch.trace, "STRAIGHT_TRAVERSE(0.0000, 0.0000, 50.8000)"));
  EXPECT_TRUE(has_line(inch.trace, "SET_FEED_RATE(254.0000)"));
  EXPECT_TRUE(has_line(inch.trace, "SET_SPINDLE_SPEED(1200.0000)"));
  EXPECT_TRUE(has_line(inch.trace, "DWELL(1.5000)"));
  EXPECT_TRUE(has_line(inch.trace, "ARC_FEED(50.8000, 25.4000, 25.4000, 25.4000, 1, 0.0000)"));
  EXPECT_TRUE(has_line(inch.trace, "USE_TOOL_LENGTH_OFFSET(76.2000)"));
}

// What `ncpost verify` can do with an AIM program once the pipeline interprets it with
// engine/ap238 and hands the calls to verify::verify_calls: the verifier reads features and
// operations through ISO 14649 attributes (its_feature, its_operation), which AIM workingsteps
// do not have, and builds its stock from WORKPIECE instances, which AIM programs do not have.
// So it finds no feature and no stock: every workingstep and motion is counted, nothing is
// checked, and the result is ok. Both the AIM program and its ARM twin are run, to show what
// is lost: the ARM twin's planar face is read as a feature, the AIM's INSTANCED_FEATURE is not.
TEST(Ap238Own, VerifyFindsNoFeaturesInAnAimProgram) {
  const fs::path cases = test::source_dir() / "tests/golden/ap238/cases";
  const auto verified = [&](const fs::path& file, bool aim) {
    pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry());
    EXPECT_TRUE(loaded.ok());
    const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
    canon::ProgramBuffer buffer;
    const auto interpreted = aim ? ap238::interpret(loaded.model, attributes, buffer)
                                 : stepnc::interpret(loaded.model, attributes, buffer);
    EXPECT_TRUE(interpreted.ok());
    return verify::verify_calls(loaded.model, attributes, buffer.calls());
  };
  const verify::VerifyResult aim = verified(cases / "own-mill-mm.aim.stp", true);
  EXPECT_TRUE(aim.ok());
  EXPECT_EQ(aim.workingsteps, 3u);  // ROUGH, FINISH and the rapid movement
  EXPECT_EQ(aim.motions, 18u);
  EXPECT_TRUE(aim.features.empty());
  EXPECT_TRUE(aim.findings.empty());
  const verify::VerifyResult arm = verified(cases / "own-mill-mm.arm.stp", false);
  EXPECT_EQ(arm.motions, aim.motions);
  EXPECT_EQ(arm.features.size(), 1u);
}

INSTANTIATE_TEST_SUITE_P(Cases, ArmEqualsAim, ::testing::Values("own-mill-mm", "own-mill-inch"),
                         [](const auto& param_info) {
                           std::string n = param_info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
}  // namespace ncpost::ap238
