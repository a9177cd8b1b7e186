// Cycle expansion: the exact motions of every kind, as traces.

#include "ncpost/canon/cycle.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "ncpost/canon/trace.hpp"

namespace ncpost::canon {
namespace {

Cycle base(CycleKind kind) {
  return Cycle{
      .kind = kind, .x = 10, .y = 20, .safe_z = 50, .r_z = 2, .bottom_z = -10, .feed = 100};
}

std::string expand(const Cycle& cycle) {
  ProgramBuffer out;
  const CycleError error = expand_cycle(cycle, out);
  EXPECT_EQ(error, CycleError::None) << describe(error);
  return trace(out.calls());
}

TEST(CanonCycle, DrillG81) {
  EXPECT_EQ(expand(base(CycleKind::Drill)),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -10.0000)\n"
            "    5 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n");
}

TEST(CanonCycle, DrillWithDwellG82) {
  Cycle c = base(CycleKind::Drill);
  c.dwell = 0.5;
  EXPECT_EQ(expand(c),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -10.0000)\n"
            "    5 DWELL(0.5000)\n"
            "    6 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n");
}

TEST(CanonCycle, PeckDrillG83ThreePecks) {
  // r_z 2 to bottom -6 by 3: pecks end at -1, -4 and -6 (the last one shorter).
  Cycle c = base(CycleKind::PeckDrill);
  c.bottom_z = -6, c.peck = 3, c.peck_clearance = 0.5, c.dwell = 0.2;
  EXPECT_EQ(expand(c),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -1.0000)\n"
            "    5 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    6 STRAIGHT_TRAVERSE(10.0000, 20.0000, -0.5000)\n"
            "    7 STRAIGHT_FEED(10.0000, 20.0000, -4.0000)\n"
            "    8 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    9 STRAIGHT_TRAVERSE(10.0000, 20.0000, -3.5000)\n"
            "   10 STRAIGHT_FEED(10.0000, 20.0000, -6.0000)\n"
            "   11 DWELL(0.2000)\n"
            "   12 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n");
}

TEST(CanonCycle, PeckDrillMatchesLinuxCncG83) {
  // `G0 X0 Y0 Z10 / G98 G83 X1 Y1 Z-6 R2 Q2` in mm: rs274 prints the motions below
  // (LinuxCNC's re-entry clearance is 0.010 in = 0.254 mm).
  Cycle c{.kind = CycleKind::PeckDrill,
          .x = 1,
          .y = 1,
          .safe_z = 10,
          .r_z = 2,
          .bottom_z = -6,
          .feed = 100,
          .peck = 2,
          .peck_clearance = 0.254};
  ProgramBuffer out;
  ASSERT_EQ(expand_cycle(c, out), CycleError::None);
  std::vector<Call> motions(out.calls().begin() + 1, out.calls().end());  // after SET_FEED_RATE
  EXPECT_EQ(trace(motions),
            "    1 STRAIGHT_TRAVERSE(1.0000, 1.0000, 10.0000)\n"
            "    2 STRAIGHT_TRAVERSE(1.0000, 1.0000, 2.0000)\n"
            "    3 STRAIGHT_FEED(1.0000, 1.0000, 0.0000)\n"
            "    4 STRAIGHT_TRAVERSE(1.0000, 1.0000, 2.0000)\n"
            "    5 STRAIGHT_TRAVERSE(1.0000, 1.0000, 0.2540)\n"
            "    6 STRAIGHT_FEED(1.0000, 1.0000, -2.0000)\n"
            "    7 STRAIGHT_TRAVERSE(1.0000, 1.0000, 2.0000)\n"
            "    8 STRAIGHT_TRAVERSE(1.0000, 1.0000, -1.7460)\n"
            "    9 STRAIGHT_FEED(1.0000, 1.0000, -4.0000)\n"
            "   10 STRAIGHT_TRAVERSE(1.0000, 1.0000, 2.0000)\n"
            "   11 STRAIGHT_TRAVERSE(1.0000, 1.0000, -3.7460)\n"
            "   12 STRAIGHT_FEED(1.0000, 1.0000, -6.0000)\n"
            "   13 STRAIGHT_TRAVERSE(1.0000, 1.0000, 10.0000)\n");
}

TEST(CanonCycle, ChipBreakingG73) {
  Cycle c = base(CycleKind::PeckDrill);
  c.bottom_z = -6, c.peck = 3, c.peck_retract = 0.25;
  EXPECT_EQ(expand(c),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -1.0000)\n"
            "    5 STRAIGHT_TRAVERSE(10.0000, 20.0000, -0.7500)\n"
            "    6 STRAIGHT_FEED(10.0000, 20.0000, -4.0000)\n"
            "    7 STRAIGHT_TRAVERSE(10.0000, 20.0000, -3.7500)\n"
            "    8 STRAIGHT_FEED(10.0000, 20.0000, -6.0000)\n"
            "    9 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n");
}

TEST(CanonCycle, PeckCountDoesNotDriftWithRounding) {
  // 0 - 3 × 0.1 is -0.30000000000000004 in binary: still three pecks, the last at -0.3.
  Cycle c{.kind = CycleKind::PeckDrill,
          .x = 0,
          .y = 0,
          .safe_z = 1,
          .r_z = 0,
          .bottom_z = -0.3,
          .feed = 10,
          .peck = 0.1,
          .peck_retract = 0.05};
  ProgramBuffer out;
  ASSERT_EQ(expand_cycle(c, out), CycleError::None);
  int feeds = 0;
  double last = 0;
  for (const auto& call : out.calls()) {
    if (const auto* f = std::get_if<StraightFeed>(&call)) ++feeds, last = f->to.z;
  }
  EXPECT_EQ(feeds, 3);
  EXPECT_EQ(last, -0.3);
}

TEST(CanonCycle, TapG84) {
  Cycle c = base(CycleKind::Tap);
  c.pitch = 1.25, c.spindle_speed = 400, c.feed = 500, c.dwell = 0.5;
  EXPECT_EQ(expand(c),
            "    1 SET_FEED_RATE(500.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -10.0000)\n"
            "    5 STOP_SPINDLE_TURNING()\n"
            "    6 START_SPINDLE_COUNTERCLOCKWISE()\n"
            "    7 DWELL(0.5000)\n"
            "    8 STRAIGHT_FEED(10.0000, 20.0000, 2.0000)\n"
            "    9 STOP_SPINDLE_TURNING()\n"
            "   10 START_SPINDLE_CLOCKWISE()\n"
            "   11 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n");
}

TEST(CanonCycle, LeftHandTapReversesTheSpindleTheOtherWay) {
  Cycle c = base(CycleKind::Tap);
  c.pitch = 1.25, c.spindle_speed = 400, c.feed = 500, c.left_hand = true;
  EXPECT_EQ(expand(c),
            "    1 SET_FEED_RATE(500.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -10.0000)\n"
            "    5 STOP_SPINDLE_TURNING()\n"
            "    6 START_SPINDLE_CLOCKWISE()\n"
            "    7 STRAIGHT_FEED(10.0000, 20.0000, 2.0000)\n"
            "    8 STOP_SPINDLE_TURNING()\n"
            "    9 START_SPINDLE_COUNTERCLOCKWISE()\n"
            "   10 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n");
}

TEST(CanonCycle, BoreFeedOutG85) {
  EXPECT_EQ(expand(base(CycleKind::Bore)),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -10.0000)\n"
            "    5 STRAIGHT_FEED(10.0000, 20.0000, 2.0000)\n"
            "    6 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n");
}

TEST(CanonCycle, BoreSpindleStopG86) {
  Cycle c = base(CycleKind::Bore);
  c.spindle_stop = true, c.dwell = 0.5;
  EXPECT_EQ(expand(c),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -10.0000)\n"
            "    5 DWELL(0.5000)\n"
            "    6 STOP_SPINDLE_TURNING()\n"
            "    7 STRAIGHT_TRAVERSE(10.0000, 20.0000, 50.0000)\n"
            "    8 START_SPINDLE_CLOCKWISE()\n");
}

TEST(CanonCycle, ReamWithDwellG89) {
  Cycle c = base(CycleKind::Ream);
  c.dwell = 1;
  c.safe_z = c.r_z;  // return to the R plane (G99)
  EXPECT_EQ(expand(c),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    3 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n"
            "    4 STRAIGHT_FEED(10.0000, 20.0000, -10.0000)\n"
            "    5 DWELL(1.0000)\n"
            "    6 STRAIGHT_FEED(10.0000, 20.0000, 2.0000)\n"
            "    7 STRAIGHT_TRAVERSE(10.0000, 20.0000, 2.0000)\n");
}

TEST(CanonCycle, MotionsCarryTheCyclesAxes) {
  Cycle c = base(CycleKind::Drill);
  c.rotary = Rotary{0, 90, 0};
  c.tool_axis = Direction{1, 0, 0};
  ProgramBuffer out;
  ASSERT_EQ(expand_cycle(c, out), CycleError::None);
  int motions = 0;
  for (const auto& call : out.calls()) {
    const Pose* p = nullptr;
    if (const auto* t = std::get_if<StraightTraverse>(&call)) p = &t->to;
    if (const auto* f = std::get_if<StraightFeed>(&call)) p = &f->to;
    if (p == nullptr) continue;
    ++motions;
    EXPECT_EQ(p->rotary, c.rotary);
    EXPECT_EQ(p->tool_axis, c.tool_axis);
  }
  EXPECT_EQ(motions, 4);
}

TEST(CanonCycle, BadCyclesEmitNothing) {
  const auto rejected = [](const Cycle& c, CycleError expected, ExpandOptions options = {}) {
    ProgramBuffer out;
    EXPECT_EQ(expand_cycle(c, out, options), expected) << describe(expected);
    EXPECT_TRUE(out.calls().empty());
  };
  Cycle c = base(CycleKind::Drill);
  c.r_z = -20;
  rejected(c, CycleError::BadHeights);
  c = base(CycleKind::Drill);
  c.safe_z = 1;
  rejected(c, CycleError::BadHeights);
  c = base(CycleKind::Drill);
  c.feed = 0;
  rejected(c, CycleError::BadFeed);
  c = base(CycleKind::Drill);
  c.dwell = -1;
  rejected(c, CycleError::NegativeDwell);
  c = base(CycleKind::Drill);
  c.x = std::numeric_limits<double>::quiet_NaN();
  rejected(c, CycleError::NotFinite);
  c = base(CycleKind::Drill);
  c.tool_axis = Direction{0, 0, std::numeric_limits<double>::infinity()};
  rejected(c, CycleError::NotFinite);
  c = base(CycleKind::PeckDrill);
  rejected(c, CycleError::BadPeck);  // peck 0
  c.peck = 1, c.peck_clearance = -1;
  rejected(c, CycleError::BadPeck);
  // 12 mm in pecks of 1e-9 would be 1.2e10 motions.
  c = base(CycleKind::PeckDrill);
  c.peck = 1e-9;
  rejected(c, CycleError::TooManyPecks);
  c.peck = 1;  // 12 pecks
  rejected(c, CycleError::TooManyPecks, ExpandOptions{11});
  ProgramBuffer out;
  EXPECT_EQ(expand_cycle(c, out, ExpandOptions{12}), CycleError::None);
  EXPECT_EQ(check(c, ExpandOptions{12}), CycleError::None);
}

}  // namespace
}  // namespace ncpost::canon
