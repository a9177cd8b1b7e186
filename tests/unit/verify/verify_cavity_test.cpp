// The verifier's profiled features (engine/verify/src/cavity.hpp): distances to vee, circular,
// step and woodruff-ended cavities against numbers worked out by hand, the tool shapes, and
// each check made to fail by moving the generator's own path for such a feature.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <numbers>

#include "../../../engine/verify/src/cavity.hpp"
#include "corpus.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/verify/verify.hpp"

namespace ncpost::verify {
namespace {

namespace fs = std::filesystem;
using detail::Cavity;
using detail::ToolShape;
using detail::Vec2;
using detail::Vec3;

constexpr double kDeg = std::numbers::pi / 180;

TEST(VerifyCavity, VeeSection) {
  // A 90-degree vee 5 deep with a sharp bottom along x from (0, 0) to (40, 0), radiused ends.
  Cavity c;
  c.vee(90 * kDeg, 0, 5);
  c.segment({0, 0}, {40, 0}, false, false, 0, 0);
  // On the centre line 1 above the bottom: sqrt(2)/2 from either wall.
  EXPECT_NEAR(c.signed_distance({20, 0, -4}), std::sqrt(0.5), 1e-9);
  // 0.3 below the bottom: 0.3 from the apex.
  EXPECT_NEAR(c.signed_distance({20, 0, -5.3}), -0.3, 1e-9);
  // Beside the slot just below its top: nearest is the wall's top edge (5, 0).
  EXPECT_NEAR(c.signed_distance({20, 6, -0.5}), -std::sqrt(1.25), 1e-9);
  // Beside the slot lower down: the wall (|y| = z + 5) is 1.5 / sqrt(2) away.
  EXPECT_NEAR(c.signed_distance({20, 5, -1.5}), -1.5 / std::sqrt(2.0), 1e-9);
  // The radiused end is the vee turned about the end of the spine (a cone).
  EXPECT_NEAR(c.signed_distance({43, 0, -1}), c.signed_distance({20, 3, -1}), 1e-9);
  EXPECT_NEAR(c.bottom({20, 2}), -3, 1e-9);
  EXPECT_NEAR(c.bottom({20, 6}), 0, 1e-9);  // material up to the top
  EXPECT_TRUE(c.on_floor({-2, 0}));         // in the end's cone
  EXPECT_FALSE(c.on_floor({-6, 0}));
}

TEST(VerifyCavity, VeeWithRadiusAndPartialCircle) {
  Cavity v;
  v.vee(60 * kDeg, 1, 6);  // bottom radius 1: its centre 5 deep
  v.segment({0, 0}, {40, 0}, true, true, 0, 0);
  EXPECT_NEAR(v.signed_distance({20, 0, -5.5}), 0.5, 1e-6);
  // (Heights come from the section's lower side as a polyline: within 1e-4 of the arcs.)
  EXPECT_NEAR(v.bottom({20, 0}), -6, 1e-4);
  // The tangent point of the fillet and the wall: (cos 30, 5 - sin 30) = (0.866, -5.5).
  EXPECT_NEAR(v.bottom({20, std::cos(30 * kDeg)}), -5.5, 1e-4);
  Cavity p;
  ASSERT_TRUE(p.partial_circle(6, 120 * kDeg, 3));  // centre 3 above the top
  p.segment({0, 0}, {40, 0}, true, true, 0, 0);
  EXPECT_NEAR(p.bottom({20, 0}), -3, 1e-4);
  EXPECT_NEAR(p.bottom({20, 3}), 3 - std::sqrt(36 - 9.0), 1e-4);
  EXPECT_NEAR(p.signed_distance({20, 0, -2}), 1, 1e-9);
  Cavity shallow;
  EXPECT_FALSE(shallow.partial_circle(6, 60 * kDeg, 3));  // the arc ends below the top
}

TEST(VerifyCavity, StepIsSigned) {
  // Wall foot along y at x 25 (into the wall: +x), floor 25 wide, 8 deep, fillet 1.
  Cavity c;
  c.step(90 * kDeg, 1, 8);
  c.line({25, 0}, {0, 1}, {1, 0}, 60, 25);
  EXPECT_NEAR(c.u({20, 10}), -5, 1e-9);
  EXPECT_NEAR(c.signed_distance({23, 10, -4}), 2, 1e-9);  // 2 from the wall
  EXPECT_NEAR(c.signed_distance({25.4, 10, -4}), -0.4, 1e-9);
  EXPECT_NEAR(c.signed_distance({-200, 10, -4}), 4, 1e-9);  // open side: the floor is nearest
  // In the fillet's corner: 1 - 1/sqrt(2) outside the arc (the corner (25, -8)).
  EXPECT_NEAR(c.signed_distance({24.999999, 10, -7.999999}), -(std::sqrt(2.0) - 1), 1e-5);
  EXPECT_TRUE(c.on_floor({10, 30}));
  EXPECT_FALSE(c.on_floor({-1, 30}));  // past the open boundary
  EXPECT_FALSE(c.on_floor({10, 61}));  // past the end of the step
}

TEST(VerifyCavity, WoodruffEnd) {
  // Rounded-U 8 wide, 5 deep, 30 long, woodruff ends of radius 20 (axis 15 above the bottom).
  Cavity c;
  c.rounded_u(4, 5);
  c.segment({0, 0}, {30, 0}, false, false, 20, 20);
  // Beyond the end the bottom rises along the radius-20 arc about (30, 15).
  EXPECT_NEAR(c.bottom({36, 0}), 15 - std::sqrt(400 - 36.0), 1e-4);
  EXPECT_NEAR(c.bottom({30 + std::sqrt(400 - 225.0) + 0.1, 0}), 0, 1e-9);
  // Below that arc: 20.402 from the axis, 0.402 into the material.
  EXPECT_NEAR(c.signed_distance({36, 0, -4.5}), 20 - std::sqrt(36 + 19.5 * 19.5), 1e-4);
  // A ball of radius 4 whose centre is 16 from the axis touches the end; 16.28 from it, it is
  // 0.28 into it.
  ToolShape ball{4, 4, 0};
  const auto outline = ball.outline(0.05, 10);
  EXPECT_NEAR(c.violation({33, 0, -5}, ball, outline, 0, nullptr), std::sqrt(265.0) - 16, 1e-4);
  EXPECT_LT(c.violation({30 + 16 * std::sin(0.3), 0, 15 - 16 * std::cos(0.3) - 4}, ball, outline, 0,
                        nullptr),
            1e-4);
}

TEST(VerifyCavity, GeneralSections) {
  // A symmetric vee 5 deep as a general section, along x from (0, 0) to (40, 0), open ends.
  Cavity vee;
  vee.general({{-5, 0}, {0, -5}, {5, 0}}, true);
  vee.segment({0, 0}, {40, 0}, true, true, 0, 0);
  EXPECT_FALSE(vee.signed_across());
  // 1 above the vertex: 1 / sqrt(2) from either wall; and on the other side the same.
  EXPECT_NEAR(vee.signed_distance({20, 0, -4}), std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(vee.signed_distance({20, -1, -4.5}), -0.5 / std::numbers::sqrt2, 1e-9);
  EXPECT_NEAR(vee.bottom({20, 2}), -3, 1e-9);
  // An asymmetric one (deep from -2 to 6, across to the left): u is signed.
  Cavity step;
  step.general({{-2, 0}, {-2, -3}, {6, -3}, {6, 0}}, false);
  step.segment({0, 0}, {40, 0}, true, true, 0, 0);
  EXPECT_TRUE(step.signed_across());
  EXPECT_NEAR(step.signed_distance({20, 5, -1}), 1, 1e-9);    // 1 from the left wall
  EXPECT_NEAR(step.signed_distance({20, -5, -1}), -3, 1e-9);  // 3 into the right wall
  EXPECT_NEAR(step.bottom({20, 5}), -3, 1e-9);
  EXPECT_NEAR(step.bottom({20, -5}), 0, 1e-9);
  // A part above the top is cut off there.
  Cavity high;
  high.general({{-6, 2}, {-4, 0}, {-4, -2}, {4, -2}, {4, 0}, {6, 2}}, true);
  high.segment({0, 0}, {40, 0}, true, true, 0, 0);
  EXPECT_NEAR(high.signed_distance({20, 0, -1}), 1, 1e-9);
  EXPECT_NEAR(high.signed_distance({20, 5, -1}), -1, 1e-9);
}

TEST(VerifyCavity, SphericalHoleBottom) {
  // A Ø30 hole whose bottom is a sphere of radius 20, lowest 16 deep: its centre 4 above the top,
  // meeting the wall sqrt(400 - 225) = 13.229 below it.
  Cavity c;
  c.spherical_hole(15, 20, 16);
  c.point({0, 0});
  EXPECT_NEAR(c.signed_distance({0, 0, -15.7}), 0.3, 1e-6);
  EXPECT_NEAR(c.signed_distance({0, 0, -16.2}), -0.2, 1e-6);
  EXPECT_NEAR(c.bottom({0, 0}), -16, 1e-4);
  EXPECT_NEAR(c.bottom({14, 0}), 4 - std::sqrt(400 - 196.0), 1e-4);
  EXPECT_NEAR(c.signed_distance({14, 0, -5}), 1, 1e-9);  // the wall, above the sphere
  EXPECT_NEAR(c.signed_distance({15.5, 0, -5}), -0.5, 1e-9);
}

TEST(VerifyCavity, ToolShapes) {
  const ToolShape flat{5, 0, 0};
  const ToolShape bull{5, 1, 0};
  const ToolShape ball{4, 4, 0};
  const ToolShape cone{8, 0, 45 * kDeg};
  const ToolShape rounded{5, 1, 30 * kDeg};
  EXPECT_EQ(flat.lower(4.9), 0);
  EXPECT_NEAR(bull.lower(5), 1, 1e-12);
  EXPECT_NEAR(bull.lower(4.5), 1 - std::sqrt(0.75), 1e-12);
  EXPECT_NEAR(ball.lower(4), 4, 1e-12);
  EXPECT_NEAR(cone.lower(3), 3, 1e-12);
  // A 60-degree cone with a tip radius 1: the flank touches the tip at 1 · cos 30 out.
  EXPECT_NEAR(rounded.lower(0.5), 1 - std::sqrt(0.75), 1e-12);
  EXPECT_NEAR(rounded.lower(3), 1 - 0.5 + (3 - std::cos(30 * kDeg)) / std::tan(30 * kDeg), 1e-12);
}

// ---- the generator's paths, moved ---------------------------------------------------------

struct Program {
  pipeline::LoadedModel loaded;
  std::unique_ptr<stepnc::AttributeReader> attributes;
  std::vector<canon::Call> calls;
};

Program load(const std::string& name) {
  static const express::SchemaRegistry registry;
  Program p;
  const fs::path file = test::source_dir() / "tests/golden/features/cases" / (name + ".stp");
  p.loaded = pipeline::load(test::read_file(file), registry);
  EXPECT_TRUE(p.loaded.ok()) << file;
  p.attributes = std::make_unique<stepnc::AttributeReader>(p.loaded.model, *p.loaded.schema);
  canon::ProgramBuffer buffer;
  EXPECT_TRUE(stepnc::interpret(p.loaded.model, *p.attributes, buffer).ok()) << file;
  p.calls = buffer.calls();
  return p;
}

std::size_t count(const VerifyResult& r, diag::Code code) {
  std::size_t n = 0;
  for (const auto& f : r.findings) n += f.diagnostic.code == code;
  return n;
}

std::string dump(const VerifyResult& r) {
  return format_text(r, "case");
}

// Moves every feed of one workingstep that `pick` selects by `by`.
template <typename Pick>
std::size_t move_feeds(std::vector<canon::Call>& calls, const std::string& workingstep, Pick pick,
                       canon::Pose by) {
  bool inside = false;
  std::size_t moved = 0;
  for (canon::Call& c : calls) {
    if (const auto* b = std::get_if<canon::Begin>(&c); b && b->scope == canon::Scope::Workingstep)
      inside = b->entity.name == workingstep;
    auto* f = std::get_if<canon::StraightFeed>(&c);
    if (!inside || f == nullptr || !pick(f->to)) continue;
    f->to.x += by.x;
    f->to.y += by.y;
    f->to.z += by.z;
    ++moved;
  }
  return moved;
}

// Whether each generated case passes, with every feature checked, is the features golden test's
// (tests/golden/features); here each check is made to fail. One case's feeds of one
// workingstep that `pick` selects are moved by `by`: the verifier must find `gouges` gouges
// (and `below_floor` passes below the floor), so the program is no longer ok.
struct MovedFeeds {
  const char* name;
  const char* file;
  const char* workingstep;
  bool (*pick)(const canon::Pose& to);
  canon::Pose by;
  std::size_t at_least_moved;
  std::size_t gouges = 1;
  std::size_t below_floor = 0;
};

void PrintTo(const MovedFeeds& c, std::ostream* os) {
  *os << c.name;
}

class VerifyMovedFeeds : public ::testing::TestWithParam<MovedFeeds> {};

TEST_P(VerifyMovedFeeds, AreFound) {
  const MovedFeeds& c = GetParam();
  Program p = load(c.file);
  ASSERT_GE(move_feeds(p.calls, c.workingstep, c.pick, c.by), c.at_least_moved);
  const VerifyResult r = verify_calls(p.loaded.model, *p.attributes, p.calls);
  EXPECT_EQ(count(r, diag::Code::VerifyGouge), c.gouges) << dump(r);
  EXPECT_EQ(count(r, diag::Code::VerifyBelowFloor), c.below_floor) << dump(r);
  EXPECT_FALSE(r.ok());
}

INSTANTIATE_TEST_SUITE_P(
    GeneratedPaths, VerifyMovedFeeds,
    ::testing::Values(
        // The Bezier channel's passes 0.2 mm lower: into its section, below its floor at the
        // bottom.
        MovedFeeds{"GeneralSectionPassesTooDeep",
                   "slot-general-section",
                   "BEZIER CHANNEL",
                   [](const canon::Pose& to) { return to.z < -0.5; },
                   {0, 0, -0.2},
                   11,
                   1,
                   1},
        // One ring of the B-spline groove 0.2 mm further out on its left side: into the
        // section's wall, which the ring's other passes only touch.
        MovedFeeds{"GeneralSectionRingPushedOut",
                   "slot-general-section",
                   "SPLINE GROOVE",
                   [](const canon::Pose& to) { return to.y > 6 && to.y < 9 && to.z < -1; },
                   {0, 0.2, 0},
                   2},
        // The finishing pass's feeds in the sphere (below where it meets the wall, 9.229 deep)
        // 0.2 mm lower: into the sphere, and at the axis 0.2 below its lowest point.
        MovedFeeds{"MilledSphereTooDeep",
                   "hole-milled-sphere",
                   "SPHERE FINISH",
                   [](const canon::Pose& to) { return to.z < -9.3; },
                   {0, 0, -0.2},
                   11,
                   1,
                   1},
        MovedFeeds{"VeeCutTooDeep",
                   "slot-vee",
                   "VEE 90 RADIUSED",
                   [](const canon::Pose& to) { return std::abs(to.z + 5) < 1e-9; },
                   {0, 0, -0.3},
                   2,
                   1,
                   1},
        // The last level's arc stations at the +x end moved 0.3 mm further out: into the end.
        MovedFeeds{"WoodruffArcPushedOut",
                   "slot-woodruff",
                   "KEYWAY WOODRUFF",
                   [](const canon::Pose& to) {
                     return to.x > 30.5 && to.x < 41 && to.z < -3.4 && std::abs(to.y) < 1e-9;
                   },
                   {0.3, 0, 0},
                   4},
        // One ring of the stepped partial-circular passes 0.2 mm wider: into the arc.
        MovedFeeds{"SteppedRingTooFarOut",
                   "slot-partial-circular",
                   "ROUND STEPPED",
                   [](const canon::Pose& to) {
                     return std::abs(to.y - 32.4690) < 1e-3 && std::abs(to.z + 1.7042) < 1e-3;
                   },
                   {0, 0.2, 0},
                   1},
        MovedFeeds{"StepWallPassIntoTheWall",
                   "step",
                   "STEP BIDIRECTIONAL",
                   [](const canon::Pose& to) { return std::abs(to.x - 20) < 1e-9; },
                   {0.25, 0, 0},
                   2}),
    [](const ::testing::TestParamInfo<MovedFeeds>& moved) {
      return std::string(moved.param.name);
    });

// A cancelled job (its client left, its time ran out) stops verifying: before the first
// executable when it interprets, before the first feature's coverage when it is given calls.
// Cancelled is no verdict, so not ok; unset, the same verification passes.
TEST(VerifyCavityPrograms, ACancelledVerificationIsNoVerdict) {
  const Program p = load("slot-vee");
  std::atomic<bool> cancel{true};
  VerifyOptions options;
  options.interpret.cancel = &cancel;
  const VerifyResult interpreted = verify(p.loaded.model, *p.attributes, options);
  EXPECT_TRUE(interpreted.cancelled);
  EXPECT_FALSE(interpreted.ok());
  EXPECT_EQ(interpreted.motions, 0u);
  const VerifyResult given = verify_calls(p.loaded.model, *p.attributes, p.calls, options);
  EXPECT_TRUE(given.cancelled);
  EXPECT_FALSE(given.ok());
  for (const auto& f : given.features) EXPECT_FALSE(f.coverage_checked) << f.name;
  EXPECT_NE(format_text(given, "case").find("result: cancelled"), std::string::npos);
  EXPECT_NE(format_json(given, "case").find("\"cancelled\": true"), std::string::npos);
  cancel = false;
  const VerifyResult whole = verify(p.loaded.model, *p.attributes, options);
  EXPECT_FALSE(whole.cancelled);
  EXPECT_TRUE(whole.ok()) << dump(whole);
}

TEST(VerifyCavityPrograms, ThreadHelixTooWide) {
  // The M16 helix 0.2 mm further out than the major diameter allows (lead-in moved with it).
  Program p = load("thread-drilling");
  bool moved = false;
  bool inside = false;
  for (canon::Call& c : p.calls) {
    if (const auto* b = std::get_if<canon::Begin>(&c); b && b->scope == canon::Scope::Workingstep)
      inside = b->entity.name == "THREAD M16";
    if (!inside) continue;
    if (auto* f = std::get_if<canon::StraightFeed>(&c); f && std::abs(f->to.x - 1) < 1e-9) {
      f->to.x += 0.2;
      moved = true;
    }
    if (auto* a = std::get_if<canon::ArcFeed>(&c)) a->end.x += 0.2;
  }
  ASSERT_TRUE(moved);
  const VerifyResult r = verify_calls(p.loaded.model, *p.attributes, p.calls);
  EXPECT_EQ(count(r, diag::Code::VerifyGouge), 1u) << dump(r);
}

}  // namespace
}  // namespace ncpost::verify
