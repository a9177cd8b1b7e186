// The planner of slots made by a form tool (features/slot.hpp).

#include <gtest/gtest.h>

#include <numbers>

#include "features/slot.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

class SlotPlan : public test::Planning {
 protected:
  // A keyway 40 long along +x with radiused ends, cut 5 deep by a ball of its width in two
  // levels, with no approach named.
  FormSlotSpec keyway() const {
    FormSlotSpec spec;
    spec.path.kind = SlotPath::Kind::Line;
    spec.path.length = 40;
    spec.passes = {{0, 5}};
    spec.depth = 5;
    spec.tool_radius = 3;
    spec.ball_radius = 3;
    spec.levels = {-2.5, -5};
    spec.entry.kind = Entry::Kind::Plunge;
    spec.exit.kind = Entry::Kind::Plunge;
    spec.tool = tool();
    spec.feature = feature("SLOT");
    return spec;
  }
};

// Down into the material at one radiused end, along the slot, down at the other end for the
// next level and back: the tool is always in the slot, and says it plunged.
TEST_F(SlotPlan, BackAndForthAlongAStraightSlot) {
  ASSERT_TRUE(plan_form_slot(keyway(), draft_));
  const std::vector<Vec3> expected{{0, 0, 2},   {0, 0, -2.5}, {40, 0, -2.5},
                                   {40, 0, -5}, {0, 0, -5},   {0, 0, 2}};
  ASSERT_EQ(moves().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_NEAR(moves()[k].to.x, expected[k].x, 1e-12) << k;
    EXPECT_NEAR(moves()[k].to.z, expected[k].z, 1e-12) << k;
  }
  EXPECT_EQ(findings(), (std::vector<std::string>{
                            "STEPNC-016: #112 (MILLING_CUTTING_TOOL) machines #125 (SLOT) along "
                            "its course of travel; it enters along its axis, as there is no room "
                            "for a helix"}));
}

// Named, the approach needs no note.
TEST_F(SlotPlan, ANamedPlungeNeedsNoNote) {
  FormSlotSpec spec = keyway();
  spec.entry.strategy = test::subject(strategy_, "PLUNGE_TOOLAXIS");
  ASSERT_TRUE(plan_form_slot(spec, draft_));
  EXPECT_TRUE(report_.all().empty());
}

// A ring groove of radius 20: one whole circle per level.
TEST_F(SlotPlan, RoundAClosedCircle) {
  FormSlotSpec spec = keyway();
  spec.path.kind = SlotPath::Kind::Circle;
  spec.path.radius = 20;
  spec.path.sweep = 2 * std::numbers::pi;
  spec.path.length = 2 * std::numbers::pi * 20;
  spec.passes = {{0, 3}};
  spec.levels = {-3};
  ASSERT_TRUE(plan_form_slot(spec, draft_));
  ASSERT_EQ(count(Move::Kind::Arc), 1u);
  const Move& circle = moves()[2];
  EXPECT_EQ(circle.kind, Move::Kind::Arc);
  EXPECT_EQ(circle.turns, 1);
  EXPECT_NEAR(circle.to.x, 20, 1e-12);
  EXPECT_NEAR(circle.centre.x, 0, 1e-12);
  EXPECT_NEAR(circle.to.z, -3, 1e-12);
}

// A ramp whose legs are a nanometre deep needs more of them than the motion limit allows.
TEST_F(SlotPlan, AHostileRampIsTheMotionLimit) {
  FormSlotSpec spec = keyway();
  spec.entry.kind = Entry::Kind::Ramp;
  spec.entry.angle = 1e-12;
  spec.entry.strategy = test::subject(strategy_, "PLUNGE_RAMP");
  EXPECT_FALSE(plan_form_slot(spec, draft_));
  ASSERT_EQ(report_.all().size(), 1u);
  EXPECT_EQ(report_.all()[0].code, diag::Code::StepncFeatureData);
}

}  // namespace
}  // namespace ncpost::stepnc::features
