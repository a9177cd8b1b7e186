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

// ---- general sections (slot_section_read.cpp, slot_section_plan.cpp) -----------------------

// A 90-degree vee 5 deep, as a polyline: every tip worked out by hand.
const std::vector<SectionPoint> kVee{{-5, 0}, {0, -5}, {5, 0}};

TEST(SlotSection, TipOfABallInAVeeTouchesBothWalls) {
  // A ball of radius 1 on the axis: its centre sqrt(2) above the vertex.
  EXPECT_NEAR(section_tip(kVee, {1, 1, 0}, 0), -5 + std::numbers::sqrt2 - 1, 1e-12);
  // 2 to the side: the ball on the right wall alone, its centre sqrt(2) off it.
  EXPECT_NEAR(section_tip(kVee, {1, 1, 0}, 2), -3 + std::numbers::sqrt2 - 1, 1e-12);
  // Grown by an allowance of 0.5: the centre sqrt(2) * 1.5 above the vertex.
  EXPECT_NEAR(section_tip(kVee, {1, 1, 0.5}, 0), -5 + 1.5 * std::numbers::sqrt2 - 1, 1e-12);
}

TEST(SlotSection, TipOfAFlatEndMillRestsOnItsEdges) {
  // Radius 2: its corners on the walls 2 from the axis, 3 below the top.
  EXPECT_NEAR(section_tip(kVee, {2, 0, 0}, 0), -3, 1e-12);
  // Wider than the vee at the top: it never gets below the top (the part's top beside it).
  EXPECT_GE(section_tip(kVee, {6, 0, 0}, 0), 0);
  // Radius 1 over 1: its flat spans 0 to 2, its right corner on the right wall 3 below the top.
  EXPECT_NEAR(section_tip(kVee, {1, 0, 0}, 1), -3, 1e-12);
}

TEST(SlotSection, GapIsTheDistanceToTheToolGrownByTheAllowance) {
  // A ball of radius 1 with its tip at -4 over 0 (centre (0, -3)): the vertex is 2 - 1 away.
  EXPECT_NEAR(section_gap({0, -5}, {1, 1, 0}, 0, -4), 1, 1e-12);
  // A point the tool covers (above its lower surface) is left nothing.
  EXPECT_EQ(section_gap({0, -2}, {1, 1, 0}, 0, -4), 0);
  // A bull nose (radius 2, corner 0.5) at tip -3 over 0: its corner's centre is (1.5, -2.5), so
  // (3, -3) is hypot(1.5, 0.5) from it, less the corner radius.
  EXPECT_NEAR(section_gap({3, -3}, {2, 0.5, 0}, 0, -3), std::hypot(1.5, 0.5) - 0.5, 1e-12);
}

class SectionSlotPlan : public test::Planning {
 protected:
  // Straight passes across a section between two open ends: a slot 30 long along +x, passes at
  // -1 and 1, 2 deep, crossing at -0.5 between them.
  SectionSlotSpec channel() const {
    SectionSlotSpec spec;
    spec.tool = tool();
    spec.feature = feature("SLOT");
    spec.path = {SlotPath::Kind::Line, {1, 0, 0}, 30, 0, 0};
    for (SlotEnd& e : spec.end) e.kind = SlotEnd::Kind::Open;
    spec.passes = {{-1, 2}, {1, 2}};
    spec.cross = {-2, -0.5};
    spec.rough = {0, 1};
    spec.tool_radius = 3;
    spec.levels = {-2};
    spec.entry.kind = Entry::Kind::Plunge;
    return spec;
  }
  // The same slot with radiused ends and a symmetric section: the course of travel 3 deep and a
  // ring at offset 2, 2 deep, in one level.
  SectionSlotSpec rings() const {
    SectionSlotSpec spec = channel();
    for (SlotEnd& e : spec.end) e.kind = SlotEnd::Kind::Radiused;
    spec.rings = true;
    spec.passes = {{0, 3}, {2, 2}};
    spec.cross = {-3, -2};
    spec.levels = {-3};
    return spec;
  }
};

TEST_F(SectionSlotPlan, StraightPassesCrossOverTheSectionBeyondTheEnds) {
  ASSERT_TRUE(plan_section_slot(channel(), draft_));
  // Down in the air 5 before the slot (radius 3 + clearance 2), along, up to the crossing
  // height, across, down, back, up.
  const std::vector<Vec3> expected{{-5, -1, 2},   {-5, -1, -2}, {35, -1, -2}, {35, -1, -0.5},
                                   {35, 1, -0.5}, {35, 1, -2},  {-5, 1, -2},  {-5, 1, 2}};
  ASSERT_EQ(moves().size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(moves()[i].to.x, expected[i].x, 1e-12) << i;
    EXPECT_NEAR(moves()[i].to.y, expected[i].y, 1e-12) << i;
    EXPECT_NEAR(moves()[i].to.z, expected[i].z, 1e-12) << i;
  }
  EXPECT_TRUE(findings().empty());
}

TEST_F(SectionSlotPlan, RingsTurnAboutRadiusedEnds) {
  // A symmetric section with radiused ends: the course of travel (plunged into at the end) and
  // a ring at offset 2 whose half circles are arcs about the ends of the course of travel.
  SectionSlotSpec spec = rings();
  ASSERT_TRUE(plan_section_slot(spec, draft_));
  EXPECT_EQ(count(Move::Kind::Arc), 2u);
  for (const Move& m : moves()) {
    if (m.kind != Move::Kind::Arc) continue;
    EXPECT_NEAR(m.centre.y, 0, 1e-12);
    EXPECT_TRUE(std::abs(m.centre.x) < 1e-12 || std::abs(m.centre.x - 30) < 1e-12);
    EXPECT_EQ(m.turns, 1);
  }
  // The plunge into the material at the end is noted.
  ASSERT_EQ(findings().size(), 1u);
  EXPECT_NE(findings()[0].find("enters along its axis"), std::string::npos);
  // Nothing deeper than a pass's depth.
  for (const Move& m : moves()) EXPECT_GE(m.to.z, -3 - 1e-12);
}

TEST_F(SectionSlotPlan, RampsDownAlongTheCourseOfTravel) {
  // Both ends radiused and a 10-degree ramp asked for: the tool goes down along the course of
  // travel (z changes only while x does), never below the first ring, and says nothing.
  SectionSlotSpec spec = rings();
  spec.entry.kind = Entry::Kind::Ramp;
  spec.entry.angle = 10 * std::numbers::pi / 180;
  ASSERT_TRUE(plan_section_slot(spec, draft_));
  EXPECT_TRUE(findings().empty());
  Vec3 at = moves().front().to;
  for (std::size_t i = 1; i < moves().size(); ++i) {
    const Move& m = moves()[i];
    if (m.kind == Move::Kind::Feed && m.to.z < at.z - 1e-9 && m.to.z < 0) {
      EXPECT_GT(std::abs(m.to.x - at.x), 1e-6) << "a plunge at move " << i;
    }
    EXPECT_GE(m.to.z, -3 - 1e-12);
    at = m.to;
  }
}

}  // namespace
}  // namespace ncpost::stepnc::features
