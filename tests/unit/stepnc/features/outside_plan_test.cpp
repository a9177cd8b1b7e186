// The outside profile planners (features/outside.hpp).

#include <gtest/gtest.h>

#include <cmath>

#include "features/outside.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

class OutsidePlan : public test::Planning {};

// A 40 × 20 block, a Ø10 tool: the ring is the block grown by 5, its corners arcs of radius 5;
// each level starts and ends at the lead-in point R + clearance beyond the ring's +x side.
TEST_F(OutsidePlan, ARectangleGrownByTheToolRadius) {
  OutsideSpec spec;
  spec.shape = Shape::rectangle(20, 10, 0);
  spec.offset = 5;
  spec.tool_radius = 5;
  spec.levels = {-4};
  ASSERT_TRUE(plan_outside(spec, draft_));
  EXPECT_NEAR(moves().front().to.x, 25 + 5 + options_.clearance, 1e-12);
  EXPECT_EQ(moves()[1].kind, Move::Kind::Feed);  // down in the air
  EXPECT_NEAR(moves()[1].to.z, -4, 1e-12);
  EXPECT_NEAR(moves()[2].to.x, 25, 1e-12);  // onto the ring
  std::size_t arcs = 0;
  for (const Move& m : moves()) {
    if (m.kind != Move::Kind::Arc) continue;
    ++arcs;
    EXPECT_EQ(m.turns, 1);  // counter-clockwise
    EXPECT_NEAR(std::hypot(m.to.x - m.centre.x, m.to.y - m.centre.y), 5, 1e-12);
  }
  EXPECT_EQ(arcs, 4u);
  EXPECT_NEAR(moves()[moves().size() - 2].to.x, 32, 1e-12);  // back out to the lead-in point
}

TEST_F(OutsidePlan, AGeneralRingIsEnteredAtItsRightmostPoint) {
  GeneralOutsideSpec spec;
  spec.ring = {{-10, -10}, {10, -10}, {10, 10}, {-10, 10}};
  spec.tool_radius = 5;
  spec.ccw = false;
  spec.levels = {-2, -4};
  ASSERT_TRUE(plan_general_outside(spec, draft_));
  EXPECT_NEAR(moves().front().to.x, 10 + 5 + options_.clearance, 1e-12);
  EXPECT_NEAR(moves().front().to.y, -10, 1e-12);
  // Each level: down at the lead-in point, onto the ring, round its four corners (clockwise:
  // (10, -10), (-10, -10), (-10, 10), (10, 10)), back to the start and out.
  std::vector<std::pair<double, double>> corners;
  for (const Move& m : moves())
    if (m.kind == Move::Kind::Feed && m.to.z == -2) corners.push_back({m.to.x, m.to.y});
  const std::vector<std::pair<double, double>> expected{{17, -10}, {10, -10}, {-10, -10}, {-10, 10},
                                                        {10, 10},  {10, -10}, {17, -10}};
  EXPECT_EQ(corners, expected);
}

TEST_F(OutsidePlan, TooManyPointsForItsLevelsIsTheMotionLimit) {
  GeneralOutsideSpec spec;
  spec.ring = {{-10, -10}, {10, -10}, {10, 10}, {-10, 10}};
  spec.tool_radius = 5;
  spec.levels = {-1, -2, -3};
  options_.max_moves = 20;  // (4 + 4) × 3 = 24 motions are more
  EXPECT_FALSE(plan_general_outside(spec, draft_));
  EXPECT_EQ(report_.all().size(), 1u);
}

}  // namespace
}  // namespace ncpost::stepnc::features
