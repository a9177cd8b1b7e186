// The planner of the round pocket with a half-ball floor (features/pocket.hpp).

#include <gtest/gtest.h>

#include "features/pocket.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

class PocketPlan : public test::Planning {};

TEST_F(PocketPlan, AHalfBallFloorIsCutStraightDownTheAxis) {
  RadiusedPocketSpec spec;
  spec.axis = {10, 5, 0};
  spec.levels = {-2, -4};
  spec.retract_plane = 10;
  ASSERT_TRUE(plan_radiused_pocket(spec, draft_));
  const std::vector<double> z{10, options_.clearance, -2, -4, 10};
  ASSERT_EQ(moves().size(), z.size());
  for (std::size_t k = 0; k < z.size(); ++k) {
    EXPECT_EQ(moves()[k].to.x, 10) << k;
    EXPECT_EQ(moves()[k].to.y, 5) << k;
    EXPECT_EQ(moves()[k].to.z, z[k]) << k;
  }
  EXPECT_EQ(count(Move::Kind::Feed), 2u);
}

}  // namespace
}  // namespace ncpost::stepnc::features
