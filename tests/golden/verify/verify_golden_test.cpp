// Golden cases of the verifier: each cases/NAME.stp (written by make_cases.py) has
// cases/NAME.expected, the text report followed by the diagnostics, and the failing cases must
// fail with their own diagnostic at their own place, whatever the golden file says.
// NCPOST_UPDATE_GOLDEN=1 rewrites the golden files; review the diff.

#include <gtest/gtest.h>

#include <fstream>

#include "corpus.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/verify/verify.hpp"

namespace ncpost::verify {
namespace {

namespace fs = std::filesystem;

fs::path cases() {
  return test::source_dir() / "tests/golden/verify/cases";
}

VerifyResult run(const fs::path& file, std::string& text) {
  static const express::SchemaRegistry registry;
  const pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry);
  EXPECT_TRUE(loaded.ok()) << file;
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  VerifyResult r = verify(loaded.model, attributes);
  const std::string name = file.filename().string();
  text = format_text(r, name);
  for (const auto& d : r.interpreter) text += diag::format(d, name) + "\n";
  for (const auto& f : r.findings) text += diag::format(f.diagnostic, name) + "\n";
  return r;
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

std::vector<const Finding*> errors(const VerifyResult& r) {
  std::vector<const Finding*> out;
  for (const auto& f : r.findings)
    if (f.diagnostic.severity == diag::Severity::Error) out.push_back(&f);
  return out;
}

struct Expected {
  const char* name;
  std::vector<diag::Code> codes;  // the errors, in order
  std::optional<Position> at{};   // of the first, within 0.05 mm
};

// Test names and failure messages show the case, not the struct's bytes.
void PrintTo(const Expected& e, std::ostream* os) {
  *os << e.name;
}

class VerifyGolden : public testing::TestWithParam<Expected> {};

TEST_P(VerifyGolden, Case) {
  const Expected& e = GetParam();
  std::string text;
  const VerifyResult r = run(cases() / (std::string(e.name) + ".stp"), text);
  expect_golden(text, cases() / (std::string(e.name) + ".expected"));
  const auto found = errors(r);
  std::vector<diag::Code> codes;
  for (const Finding* f : found) codes.push_back(f->diagnostic.code);
  EXPECT_EQ(codes, e.codes) << text;
  EXPECT_EQ(r.ok(), e.codes.empty()) << text;
  if (std::string(e.name) == "kind-not-checked") {
    ASSERT_EQ(r.features.size(), 3u);
    EXPECT_FALSE(r.features[1].checked);
    EXPECT_NE(text.find("note: VERIFY-010: #21 SPHERICAL_CAP 'CAP1': feature kind SPHERICAL_CAP "
                        "is not checked"),
              std::string::npos)
        << text;
  }
  if (e.at && !found.empty()) {
    ASSERT_TRUE(found.front()->position) << text;
    EXPECT_NEAR(found.front()->position->x, e.at->x, 0.05) << text;
    EXPECT_NEAR(found.front()->position->y, e.at->y, 0.05) << text;
    EXPECT_NEAR(found.front()->position->z, e.at->z, 0.05) << text;
  }
}

using diag::Code;
INSTANTIATE_TEST_SUITE_P(
    Cases, VerifyGolden,
    testing::Values(
        Expected{"good", {}},
        // The outer ring's +x side at x 65.5: 0.5 mm into the wall at x 70 (r 5).
        Expected{"gouge-wall", {Code::VerifyGouge}, Position{65.5, 31, -10}},
        // Every level ends at z -8; the floor is at -10: depth, and then no floor swept.
        Expected{"shallow", {Code::VerifyDepth, Code::VerifyCoverage}, Position{38, 40, -8}},
        // Only the outer ring (5 mm from the walls) at the floor: the middle is never swept.
        Expected{"uncovered-strip", {Code::VerifyCoverage}},
        // RAPID ACROSS at z -5 from outside the block to (80, 10): 5 mm into the faced stock.
        Expected{"rapid-into-part", {Code::VerifyRapid}},
        // PLUNGE_HELIX asked for, straight down at the pocket's centre.
        Expected{"plunge-helix", {Code::VerifyPlunge}, Position{50, 40, -10}},
        // The drill 3 mm below the flat bottom at z -15.
        Expected{"hole-too-deep", {Code::VerifyBelowFloor}, Position{20, 20, -18}},
        // The pocket's outline and path as a SLOT with flat, 6 mm-cornered ends: passes.
        Expected{"slot-flat-ends", {}},
        // A SPHERICAL_CAP is not checked: a VERIFY-010 note, no error (the golden file holds
        // the note).
        Expected{"kind-not-checked", {}},
        // A 90-degree vee slot (at (20, 40), 40 along x, 5 deep) and a countersink of 90
        // degrees along its bottom: passes. 0.3 mm deeper: the point 0.3 below the vee's
        // bottom (the walls 0.3 sin 45 = 0.21), from the start of the pass. 1 mm short: the
        // depth, and the walls left 0.7 mm thick everywhere.
        Expected{"vee-good", {}},
        Expected{
            "vee-too-deep", {Code::VerifyGouge, Code::VerifyBelowFloor}, Position{20, 40, -5.3}},
        Expected{"vee-shallow", {Code::VerifyDepth, Code::VerifyCoverage}, Position{20, 40, -4}},
        // A keyway (rounded-U 8 wide, 5 deep, 30 long) with woodruff ends of radius 20, a ball
        // 8 rising along their arcs: passes. Running on 3 mm past the end at the bottom instead:
        // a gouge at (53, 40, -5), worst there (the ball's centre 0.28 mm outside the torus the
        // end is), and the arc it did not follow left uncut.
        Expected{"woodruff-good", {}},
        Expected{
            "woodruff-overcut", {Code::VerifyGouge, Code::VerifyCoverage}, Position{53, 40, -5}},
        // A ball of the partial circle's radius 0.5 mm off its centre, on the way back.
        Expected{"partial-circle-off-centre", {Code::VerifyGouge}, Position{60, 40.5, -3}},
        // A step, its wall's foot at x 25: the last pass at x 20.4 with a 10 mm end mill cuts
        // 0.4 into the wall (from its start, past the step's open end).
        Expected{"step-good", {}},
        Expected{"step-wall-gouge", {Code::VerifyGouge}, Position{20.4, -7, -8}},
        // Issue 17. A slot whose course of travel has its own placement ((0, 10), turned 90
        // degrees): cut along it, it passes; cut along the feature's x as if the placement were
        // not there, the tool is in the wall (worst at the far end, (60, 40)), the slot's floor
        // is never reached.
        Expected{"slot-placed-travel", {}},
        Expected{"slot-placed-travel-ignored",
                 {Code::VerifyGouge, Code::VerifyDepth, Code::VerifyCoverage},
                 Position{60, 40, -5}},
        // A hole tapering from 10 to 8, 15 deep: its wall is the cone between them. An 8 mm
        // tool down its axis passes; a 10 mm one is 1 mm (0.9978 along the cone's normal) into
        // it at the bottom.
        Expected{"taper-good", {}},
        Expected{"taper-too-wide", {Code::VerifyGouge}, Position{30, 30, -15}},
        // General outlines. An L-shaped polyline pocket with orthogonal_radius 5 = the tool
        // radius: its boundary at 5 from the walls and lines between pass.
        Expected{"l-pocket", {}},
        // The short arm's line at x 20.8 (pocket at (20, 15)): 0.8 mm into its wall at x 25
        // and the fillet about (20, 45), first at the arm's top.
        Expected{"l-pocket-gouge", {Code::VerifyGouge}, Position{40.8, 60, -6}},
        // Without the short arm's middle line a strip x 10..15 of it is never swept.
        Expected{"l-pocket-uncovered", {Code::VerifyCoverage}, Position{32.625, 43.625, -6}},
        // An open pocket whose lines run 10 mm out past the open side: passes.
        Expected{"open-pocket", {}},
        // A last feed to (53, 24) beside the open side: 2 mm into the part's face x 50, y > 20.
        Expected{"open-pocket-face", {Code::VerifyGouge}, Position{73, 39, -6}},
        // A general outside profile with the ring 5.01 outside it: passes.
        Expected{"outside-box", {}},
        // Across the (40, 30) corner from (45.01, 30) to (40, 35.01): 1.457 into it.
        Expected{"outside-box-corner", {Code::VerifyGouge}, Position{62.47, 47.54, -6}}),
    [](const testing::TestParamInfo<Expected>& param) {
      std::string n = param.param.name;
      std::replace(n.begin(), n.end(), '-', '_');
      return n;
    });

}  // namespace
}  // namespace ncpost::verify
