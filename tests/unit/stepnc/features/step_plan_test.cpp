// The step planner (features/step.hpp).

#include <gtest/gtest.h>

#include <set>

#include "features/step.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

// A step open along +x for 50, its wall 20 to the left (+y); a Ø10 tool, overlap 0.5, stepover
// 5: the last pass 5 off the wall (y 15), the first with the tool's edge 5 past the open
// boundary (y 0), evenly between: 0, 5, 10, 15; each from 7 (R + clearance) before x 0 to 7
// past x 50.
StepSpec step_50_by_20() {
  StepSpec spec;
  spec.along = {1, 0, 0};
  spec.length = 50;
  spec.width = 20;
  spec.tool_radius = 5;
  spec.overlap = 0.5;
  spec.stepover = 5;
  spec.levels = {-3};
  return spec;
}

class StepPlan : public test::Planning {
 protected:
  // The y of each cutting pass along x at z, and whether all ran towards +x.
  std::set<double> passes(double z, bool& all_forward) const {
    std::set<double> ys;
    all_forward = true;
    Vec3 at = moves().front().to;
    for (const Move& m : moves()) {
      if (m.kind == Move::Kind::Feed && m.to.z == z && at.z == z && m.to.y == at.y) {
        ys.insert(m.to.y);
        all_forward = all_forward && m.to.x > at.x;
        EXPECT_NEAR(std::abs(m.to.x - at.x), 64, 1e-9);
      }
      at = m.to;
    }
    return ys;
  }
};

TEST_F(StepPlan, PassesFromTheOpenBoundaryToTheWall) {
  ASSERT_TRUE(plan_step(step_50_by_20(), draft_));
  bool forward = false;
  EXPECT_EQ(passes(-3, forward), (std::set<double>{0, 5, 10, 15}));
  EXPECT_TRUE(forward);  // one way, as asked (the spec's default)
  EXPECT_NEAR(moves().front().to.x, -7, 1e-12);
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

TEST_F(StepPlan, AWallOnTheRightMirrorsThePasses) {
  StepSpec spec = step_50_by_20();
  spec.width = -20;
  spec.one_way = false;
  ASSERT_TRUE(plan_step(spec, draft_));
  bool forward = false;
  EXPECT_EQ(passes(-3, forward), (std::set<double>{0, -5, -10, -15}));
  EXPECT_FALSE(forward);  // back and forth
}

TEST_F(StepPlan, SideMillingIsThePassAlongTheWallAlone) {
  StepSpec spec = step_50_by_20();
  spec.walls_only = true;
  ASSERT_TRUE(plan_step(spec, draft_));
  bool forward = false;
  EXPECT_EQ(passes(-3, forward), (std::set<double>{15}));
}

}  // namespace
}  // namespace ncpost::stepnc::features
