// The planner of rounded-rectangle and circular regions (features/region.hpp): rectangular and
// circular pockets, straight U slots.

#include <gtest/gtest.h>

#include <cmath>

#include "features/holes.hpp"
#include "features/region.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

class RegionPlan : public test::Planning {
 protected:
  // NIST ex1's pocket: 80 × 50, corner radius 10, a Ø18 tool with allowance 1 (inset 10),
  // rings 5 apart, one level 5 deep, the default helix (0.8 R at 10 degrees).
  RegionSpec ex1_pocket() const {
    RegionSpec spec;
    spec.shape = Shape::rectangle(40, 25, 10);
    spec.inset = 10;
    spec.stepover = 5;
    spec.finish = 5;
    spec.levels = {-5};
    spec.entry.radius = 0.8 * 9;
    spec.entry.angle = radians(10);
    spec.exit.kind = Entry::Kind::Plunge;
    spec.tool = tool();
    spec.feature = feature();
    return spec;
  }
};

// The innermost path is the centre line from (-15, 0) to (15, 0); the helix (radius 7.2, one
// turn for the 7 mm from 2 above the top) is about its start, and the rings are at insets 20,
// 15, 10 from the wall: sharp-cornered, 30, 35 and 40 mm half long.
TEST_F(RegionPlan, RingsFromTheCentreLineOutwards) {
  ASSERT_TRUE(plan_region(ex1_pocket(), draft_));
  EXPECT_TRUE(report_.all().empty());
  EXPECT_EQ(moves()[0].kind, Move::Kind::Rapid);
  EXPECT_NEAR(moves()[0].to.x, -15 + 7.2, 1e-12);
  EXPECT_NEAR(moves()[0].to.z, options_.clearance, 1e-12);
  const Move& helix = moves()[1];
  ASSERT_EQ(helix.kind, Move::Kind::Arc);
  EXPECT_EQ(helix.turns, 1);
  EXPECT_NEAR(helix.centre.x, -15, 1e-12);
  EXPECT_NEAR(helix.to.z, -5, 1e-12);
  EXPECT_NEAR(moves()[2].to.x, -15, 1e-12);  // into the centre
  EXPECT_NEAR(moves()[3].to.x, 15, 1e-12);   // along the centre line
  EXPECT_EQ(count(Move::Kind::Arc), 1u);     // the rings' corners are sharp
  double x_max = 0, y_max = 0;
  for (const Move& m : moves()) {
    if (m.kind != Move::Kind::Feed) continue;
    x_max = std::max(x_max, std::abs(m.to.x));
    y_max = std::max(y_max, std::abs(m.to.y));
  }
  EXPECT_NEAR(x_max, 30, 1e-12);  // 40 less the inset
  EXPECT_NEAR(y_max, 15, 1e-12);
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

TEST_F(RegionPlan, ATooWideHelixThatTheOperationNamesIsRefused) {
  RegionSpec spec = ex1_pocket();
  spec.entry.explicit_entry = true;
  spec.entry.radius = 30;
  spec.entry.strategy = test::subject(strategy_, "PLUNGE_HELIX");
  EXPECT_FALSE(plan_region(spec, draft_));
  EXPECT_EQ(findings(), (std::vector<std::string>{
                            "STEPNC-102: #128 (PLUNGE_HELIX) radius 30 leaves no room for #112 "
                            "(MILLING_CUTTING_TOOL) in #125 (CLOSED_POCKET) (at most 15)"}));
  EXPECT_EQ(report_.all()[0].at.instance, &strategy_);
}

// A Ø10 tool in a Ø10 hole-like pocket: no room for the default helix, so it goes straight down
// the axis and says so.
TEST_F(RegionPlan, AToolThatFillsTheRegionPlunges) {
  RegionSpec spec = ex1_pocket();
  spec.shape = Shape::circle(5);
  spec.inset = 5;
  ASSERT_TRUE(plan_region(spec, draft_));
  ASSERT_EQ(report_.all().size(), 1u);
  EXPECT_EQ(report_.all()[0].code, diag::Code::StepncNote);
  EXPECT_EQ(count(Move::Kind::Arc), 0u);
  EXPECT_EQ(moves()[1].kind, Move::Kind::Feed);
  EXPECT_NEAR(moves()[1].to.z, -5, 1e-12);
}

// Sharp corners and lines back and forth: 30 mm across in steps of at most 5, seven lines
// along x, each joined to the next at its end.
TEST_F(RegionPlan, BackAndForthLines) {
  RegionSpec spec = ex1_pocket();
  spec.shape = Shape::rectangle(40, 25, 0);
  spec.pattern = RegionSpec::Pattern::Lines;
  ASSERT_TRUE(plan_region(spec, draft_));
  int lines = 0;
  double last_direction = 0;
  Vec3 at = moves().front().to;
  for (const Move& m : moves()) {
    if (m.kind == Move::Kind::Feed && m.to.z == -5 && at.z == -5 && m.to.y == at.y &&
        std::abs(m.to.x - at.x) > 50) {
      ++lines;
      const double direction = m.to.x - at.x;
      EXPECT_LT(direction * last_direction, 1e-9) << "line " << lines;
      last_direction = direction;
    }
    at = m.to;
  }
  EXPECT_EQ(lines, 7);
}

// Roughing into corners tighter than the tool (issue 17, STEPNC-120 in the reader): the rings
// of a 60 × 40 pocket with corner radius 3 at inset 5.5 (R5 + allowance 0.5) have sharp corners
// at (±24.5, ±14.5): the tool never comes nearer than the inset to a wall, and the corner keeps
// the stock the finishing pass removes.
TEST_F(RegionPlan, RoughingRingsInCornersTighterThanTheToolStayOffTheWalls) {
  RegionSpec spec = ex1_pocket();
  spec.shape = Shape::rectangle(30, 20, 3);
  spec.inset = 5.5;
  spec.entry.radius = 4;
  ASSERT_TRUE(plan_region(spec, draft_));
  double x_max = 0, y_max = 0;
  for (const Move& m : moves()) {
    if (m.kind != Move::Kind::Feed) continue;
    x_max = std::max(x_max, std::abs(m.to.x));
    y_max = std::max(y_max, std::abs(m.to.y));
  }
  EXPECT_NEAR(x_max, 24.5, 1e-12);
  EXPECT_NEAR(y_max, 14.5, 1e-12);
  EXPECT_EQ(count(Move::Kind::Arc), 1u);  // the helix; the corners are sharp
}

// A milled round hole is a circle region (milled_hole_read.cpp): Ø30, R5 tool, allowance 0.5
// (inset 5.5), two levels. The tool goes down by a helix about the centre and cuts full circles
// about it (ARC_FEED), the outermost of radius 15 - 5.5 = 9.5, never beyond it.
TEST_F(RegionPlan, AMilledHoleIsAHelixThenCircles) {
  RegionSpec spec = ex1_pocket();
  spec.shape = Shape::circle(15);
  spec.inset = 5.5;
  spec.stepover = 4;
  spec.levels = {-4, -8};
  spec.entry.radius = 4;
  ASSERT_TRUE(plan_region(spec, draft_));
  EXPECT_TRUE(report_.all().empty());
  std::size_t circles = 0;
  double outer = 0;
  for (const Move& m : moves()) {
    if (m.kind == Move::Kind::Feed) {
      EXPECT_LE(std::hypot(m.to.x, m.to.y), 9.5 + 1e-9);
    }
    if (m.kind != Move::Kind::Arc) continue;
    const double radius = std::hypot(m.to.x - m.centre.x, m.to.y - m.centre.y);
    EXPECT_LE(std::hypot(m.centre.x, m.centre.y) + radius, 9.5 + 1e-9);
    if (std::abs(m.centre.x) < 1e-12 && std::abs(m.centre.y) < 1e-12) {
      ++circles;
      outer = std::max(outer, radius);
    }
  }
  EXPECT_NEAR(outer, 9.5, 1e-9);
  EXPECT_GE(circles, 4u);  // at least two rings on each of the two levels
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

// Draft::place_from carries moves drawn in a placement of their own (a slot's placed course
// of travel) into the feature's frame: points and arc centres moved and turned, the arcs' sense
// kept, moves drawn before `first` and non-motions untouched.
TEST_F(RegionPlan, PlaceFromCarriesMovesIntoTheFeaturesFrame) {
  draft_.rapid({1, 0, 5});
  const std::size_t first = draft_.moves().size();
  draft_.feed({10, 0, -2});
  draft_.arc({10, 0, -2}, {5, 0, -2}, -1);
  draft_.add({Move::Kind::FeedRate, {}, {}, 1, 300});
  detail::Frame frame;
  frame.origin = {20, 10, 0};
  frame.x = {0, 1, 0};
  frame.y = {-1, 0, 0};
  draft_.place_from(first, frame);
  EXPECT_NEAR(moves()[0].to.x, 1, 1e-12);  // before `first`
  EXPECT_NEAR(moves()[1].to.x, 20, 1e-12);
  EXPECT_NEAR(moves()[1].to.y, 20, 1e-12);
  EXPECT_NEAR(moves()[1].to.z, -2, 1e-12);
  EXPECT_NEAR(moves()[2].centre.x, 20, 1e-12);
  EXPECT_NEAR(moves()[2].centre.y, 15, 1e-12);
  EXPECT_EQ(moves()[2].turns, -1);
  EXPECT_EQ(moves()[3].value, 300);
  EXPECT_NEAR(moves()[3].to.x, 0, 1e-12);
}

// A milled taper (holes.hpp) from radius 10 at the top to 8 at its depth 8, an R4 tool: the
// core cylinder of radius 8, then a circle at each level at the cone's radius there less the
// inset, 10 - z/4 - 4: 5.5, 5, 4.5, 4. No circle reaches past the cone at its own height, and
// the wall above a level is wider still.
TEST_F(RegionPlan, AMilledTaperFollowsTheConeLevelByLevel) {
  MilledTaperSpec spec;
  spec.core = ex1_pocket();
  spec.core.shape = Shape::circle(8);
  spec.core.inset = 4;
  spec.core.stepover = 3;
  spec.core.levels = {-4, -8};
  spec.core.entry.radius = 2;
  spec.top = 10;
  spec.bottom = 8;
  spec.depth = 8;
  spec.levels = {-2, -4, -6, -8};
  ASSERT_TRUE(plan_milled_taper(spec, draft_));
  std::vector<double> radii;
  bool core_done = false;
  for (const Move& m : moves()) {
    if (m.kind == Move::Kind::Rapid && std::abs(m.to.x) < 1e-12 && std::abs(m.to.y) < 1e-12)
      core_done = true;
    if (m.kind == Move::Kind::Feed || m.kind == Move::Kind::Arc) {
      EXPECT_LE(std::hypot(m.to.x, m.to.y), 10 + 0.25 * m.to.z - 4 + 1e-9) << m.to.z;
    }
    if (core_done && m.kind == Move::Kind::Arc) radii.push_back(std::hypot(m.to.x, m.to.y));
  }
  ASSERT_EQ(radii.size(), 4u);
  EXPECT_NEAR(radii[0], 5.5, 1e-12);
  EXPECT_NEAR(radii[1], 5.0, 1e-12);
  EXPECT_NEAR(radii[2], 4.5, 1e-12);
  EXPECT_NEAR(radii[3], 4.0, 1e-12);
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

// A milled spherical bottom (holes.hpp) with no cylinder above it, written by hand: one
// clearing level at -3 whose disc reaches 6 from the axis (rings 3 apart: 3, 6), entered by a
// helix no wider than the disc; then three circles down the sphere (radii 5, 3, 0). Each circle
// after the first is reached by a feed in at the height above and a helix down to its own
// height; the last, on the axis, by a feed along the sphere.
TEST_F(RegionPlan, AMilledSphereClearsDiscsThenCirclesDown) {
  MilledSphereSpec spec;
  spec.core = ex1_pocket();
  spec.core.shape = Shape::circle(10);
  spec.core.stepover = 3;
  spec.core.entry.radius = 8;  // wider than the disc: clamped to 6
  spec.has_core = false;
  spec.levels = {{6, -3}};
  spec.rings = {{5, -2}, {3, -3.5}, {0, -4}};
  ASSERT_TRUE(plan_milled_sphere(spec, draft_));
  std::vector<std::pair<double, double>> arcs;  // (radius, z) where each arc ends
  for (const Move& m : moves()) {
    EXPECT_LE(std::hypot(m.to.x, m.to.y), 6 + 1e-9);
    if (m.kind == Move::Kind::Arc) arcs.emplace_back(std::hypot(m.to.x, m.to.y), m.to.z);
  }
  // The helix down to -3 (radius 6), the disc's rings 3 and 6, circle 5 at -2, the helix to
  // -3.5 at radius 3, circle 3 at -3.5.
  ASSERT_EQ(arcs.size(), 6u);
  EXPECT_NEAR(arcs[0].first, 6, 1e-12);
  EXPECT_NEAR(arcs[0].second, -3, 1e-12);
  EXPECT_NEAR(arcs[1].first, 3, 1e-12);
  EXPECT_NEAR(arcs[2].first, 6, 1e-12);
  EXPECT_NEAR(arcs[3].first, 5, 1e-12);
  EXPECT_NEAR(arcs[3].second, -2, 1e-12);
  EXPECT_NEAR(arcs[4].first, 3, 1e-12);
  EXPECT_NEAR(arcs[4].second, -3.5, 1e-12);
  EXPECT_NEAR(arcs[5].second, -3.5, 1e-12);
  double deepest = 0;
  for (const Move& m : moves()) deepest = std::min(deepest, m.to.z);
  EXPECT_NEAR(deepest, -4, 1e-12);
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

}  // namespace
}  // namespace ncpost::stepnc::features
