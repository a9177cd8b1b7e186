// The thread drilling planner (features/threads.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "features/threads.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

// M16 x 2, 10 deep, in a hole drilled 14 deep; a Ø12 thread drill-mill: its centre circles
// at 16 / 2 - 6 = 2 from the axis.
ThreadSpec m16() {
  ThreadSpec spec;
  spec.retract_z = 3;
  spec.bottom_z = -14;
  spec.length = 10;
  spec.pitch = 2;
  spec.offset = 2;
  return spec;
}

class ThreadPlan : public test::Planning {};

TEST_F(ThreadPlan, DrillsThenMillsTheThreadUpInWholeTurns) {
  ASSERT_TRUE(plan_thread_drilling(m16(), draft_));
  ASSERT_EQ(moves().size(), 7u);
  EXPECT_EQ(moves()[0].kind, Move::Kind::Rapid);
  EXPECT_EQ(moves()[1].to.z, -14);  // the drill to the bottom
  EXPECT_EQ(moves()[2].to.z, -10);  // back up to the bottom of the thread
  EXPECT_EQ(moves()[3].to.x, 2);    // out to the thread
  const Move& helix = moves()[4];
  EXPECT_EQ(helix.kind, Move::Kind::Arc);
  EXPECT_EQ(helix.turns, 5);  // 10 / 2, counter-clockwise: a right-hand thread
  EXPECT_NEAR(helix.to.x, 2, 1e-12);
  EXPECT_NEAR(helix.to.y, 0, 1e-12);
  EXPECT_EQ(helix.to.z, 0);
  EXPECT_EQ(moves()[5].to.x, 0);  // back to the axis
  EXPECT_EQ(moves()[6].to.z, 3);
}

// 10 / 1.5 = 6 2/3 turns: seven arcs' worth, clockwise for a left hand, ending 2/3 of a turn
// round (clockwise: at -240 degrees).
TEST_F(ThreadPlan, ALeftHandThreadOfPartTurns) {
  ThreadSpec spec = m16();
  spec.pitch = 1.5;
  spec.right = false;
  ASSERT_TRUE(plan_thread_drilling(spec, draft_));
  const Move& helix = moves()[4];
  EXPECT_EQ(helix.turns, -7);
  const double angle = -2 * std::numbers::pi * 2 / 3;
  EXPECT_NEAR(helix.to.x, 2 * std::cos(angle), 1e-9);
  EXPECT_NEAR(helix.to.y, 2 * std::sin(angle), 1e-9);
}

TEST_F(ThreadPlan, AHostilePitchIsTheMotionLimit) {
  ThreadSpec spec = m16();
  spec.pitch = 1e-9;
  EXPECT_FALSE(plan_thread_drilling(spec, draft_));
  ASSERT_EQ(report_.all().size(), 1u);
  EXPECT_EQ(report_.all()[0].code, diag::Code::StepncFeatureData);
}

}  // namespace
}  // namespace ncpost::stepnc::features
