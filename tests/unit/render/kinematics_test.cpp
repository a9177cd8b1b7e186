// Tool axis → rotary positions (engine/render/kinematics.hpp, docs/kinematics.md): angles
// worked out by hand for each kinematics type, the pole, a wrap across ±180 degrees, a limit
// that forces the other solution, the preferences, and the linear positions without
// tool-centre-point control checked through the tests' own forward kinematics.

#include "ncpost/render/kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "forward_kinematics.hpp"
#include "ncpost/render/render.hpp"

namespace ncpost::render {
namespace {

using profile::KinematicsType;
using profile::MachineAxis;
using profile::RotaryAxis;

constexpr double kAngle = 1e-9;  // degrees

double sind(double degrees) {
  return std::sin(degrees * std::numbers::pi / 180);
}
double cosd(double degrees) {
  return std::cos(degrees * std::numbers::pi / 180);
}

RotaryAxis limited(char name, MachineAxis axis, double min, double max) {
  RotaryAxis a;
  a.name = name;
  a.axis = axis;
  a.min = min;
  a.max = max;
  return a;
}
RotaryAxis continuous(char name, MachineAxis axis) {
  RotaryAxis a;
  a.name = name;
  a.axis = axis;
  a.continuous = true;
  return a;
}

// A fork head: C about Z carrying A about X (linuxcnc-5ax).
profile::Kinematics head_head(double a_min = -110, double a_max = 110) {
  profile::Kinematics k;
  k.type = KinematicsType::HeadHead;
  k.primary = limited('C', MachineAxis::Z, -360, 360);
  k.secondary = limited('A', MachineAxis::X, a_min, a_max);
  return k;
}
// A trunnion: A about X carrying a C table (fanuc-30i-5ax).
profile::Kinematics table_table() {
  profile::Kinematics k;
  k.type = KinematicsType::TableTable;
  k.primary = limited('A', MachineAxis::X, -120, 30);
  k.secondary = continuous('C', MachineAxis::Z);
  return k;
}
// A B head about Y and a C table (siemens-840d-5ax).
profile::Kinematics head_table(double b_min = -100, double b_max = 100) {
  profile::Kinematics k;
  k.type = KinematicsType::HeadTable;
  k.primary = limited('B', MachineAxis::Y, b_min, b_max);
  k.secondary = continuous('C', MachineAxis::Z);
  return k;
}

RotaryPositions choose(const profile::Kinematics& k, canon::Direction axis,
                       RotaryPositions previous = {}) {
  const Kinematics::Choice c = Kinematics(k).choose(axis, previous);
  EXPECT_TRUE(c.positions) << c.refusal;
  return c.positions.value_or(RotaryPositions{});
}

#define EXPECT_POSITIONS(actual, primary_deg, secondary_deg)           \
  do {                                                                 \
    const RotaryPositions p_ = (actual);                               \
    EXPECT_NEAR(p_.primary, (primary_deg), kAngle) << "primary";       \
    EXPECT_NEAR(p_.secondary, (secondary_deg), kAngle) << "secondary"; \
  } while (0)

// Head-head C/A: v = Rz(C) Rx(A) Z = (sinA sinC, -sinA cosC, cosA).
TEST(KinematicsAngles, HeadHeadByHand) {
  const auto k = head_head();
  // The CLS paper's 30-degree head: K = 0.8660254. From home, A30 C0 (A-30 C180 turns more).
  EXPECT_POSITIONS(choose(k, {0, -0.5, cosd(30)}), 0, 30);
  // (0.5, 0, 0.866): C90 A30 or C-90 A-30; from C0 A30 the first turns 90, the second 150.
  EXPECT_POSITIONS(choose(k, {0.5, 0, cosd(30)}, {0, 30}), 90, 30);
  // Not normalised input: the same direction.
  EXPECT_POSITIONS(choose(k, {0, -2, 4 * cosd(30)}), 0, 30);
}

// Table-table A/C: the table turns the workpiece, so the tool, seen from the workpiece, turns
// the other way: v = Rz(-C) Rx(-A) Z = (sinA sinC, sinA cosC, cosA).
TEST(KinematicsAngles, TableTableByHand) {
  const auto k = table_table();
  EXPECT_POSITIONS(choose(k, {0, -0.5, cosd(30)}), -30, 0);
  // (0.5, 0, 0.866): A30 C90 or A-30 C-90 (costs 30 + 90 either way): the positive tilt.
  EXPECT_POSITIONS(choose(k, {0.5, 0, cosd(30)}), 30, 90);
  // (-0.5, 0, 0.866) from A-30 C0: A-30 C90 (90) beats A30 C-90 (150).
  EXPECT_POSITIONS(choose(k, {-0.5, 0, cosd(30)}, {-30, 0}), -30, 90);
}

// Head-table B/C: v = Rz(-C) Ry(B) Z = (sinB cosC, -sinB sinC, cosB).
TEST(KinematicsAngles, HeadTableByHand) {
  const auto k = head_table();
  EXPECT_POSITIONS(choose(k, {0.5, 0, cosd(30)}), 30, 0);
  // (0, 0.5, 0.866) from B30 C0: B30 C-90 (90) beats B-30 C90 (150).
  EXPECT_POSITIONS(choose(k, {0, 0.5, cosd(30)}, {30, 0}), 30, -90);
  // (0, -0.5, 0.866) from B30 C0: B30 C90.
  EXPECT_POSITIONS(choose(k, {0, -0.5, cosd(30)}, {30, 0}), 30, 90);
}

// On the pole (k = 1) the rotating axis has no angle of its own: it keeps the previous one,
// for every type; k = -1 needs a tilt of 180 degrees.
TEST(KinematicsAngles, PoleKeepsThePreviousAngle) {
  const auto hh = Kinematics(head_head()).choose({0, 0, 1}, {123.5, 30});
  ASSERT_TRUE(hh.positions);
  EXPECT_TRUE(hh.singular);
  EXPECT_POSITIONS(*hh.positions, 123.5, 0);
  EXPECT_POSITIONS(choose(table_table(), {0, 0, 1}, {-30, 190}), 0, 190);
  EXPECT_POSITIONS(choose(head_table(), {0, 0, 5}, {30, -725}), 0, -725);
  // Within the pole tolerance (1e-9) of the pole: still kept.
  EXPECT_POSITIONS(choose(head_head(), {1e-10, 0, 1}, {45, 10}), 45, 0);
  // Pointing up is a tilt of 180: beyond A's +-110 in both solutions.
  const auto up = Kinematics(head_head()).choose({0, 0, -1}, {});
  EXPECT_FALSE(up.positions);
  EXPECT_EQ(up.code, diag::Code::KinUnreachable);
}

// The rotating axis goes the short way across +-180: from C170 to the direction of C-170 is
// C190 (20 degrees), whether the axis is limited to +-360 or continuous, and a continuous axis
// runs on past 360.
TEST(KinematicsAngles, WrapAcrossPlusMinus180) {
  // Head-head, C limited to +-360: A30 with C = -170 (as atan2 gives it).
  const canon::Direction hh{sind(30) * sind(-170), -sind(30) * cosd(-170), cosd(30)};
  EXPECT_POSITIONS(choose(head_head(), hh, {170, 30}), 190, 30);
  // And back the other way from -170 towards 170: -190.
  const canon::Direction hh2{sind(30) * sind(170), -sind(30) * cosd(170), cosd(30)};
  EXPECT_POSITIONS(choose(head_head(), hh2, {-170, 30}), -190, 30);
  // At the limit of 360: from C350 the direction of C10 A30 would be C370, outside; C10 turns
  // 340 degrees, so the other solution, C190 A-30 (160 + 60), is the shorter; with the positive
  // tilt preferred it is C10.
  const canon::Direction hh3{sind(30) * sind(10), -sind(30) * cosd(10), cosd(30)};
  EXPECT_POSITIONS(choose(head_head(), hh3, {350, 30}), 190, -30);
  auto positive = head_head();
  positive.solution = profile::RotarySolution::PositiveTilt;
  EXPECT_POSITIONS(choose(positive, hh3, {350, 30}), 10, 30);
  // Table-table, C continuous: A-30 with C -170 from C170 is C190; from C350, C10 is C370.
  const canon::Direction tt{sind(-30) * sind(-170), sind(-30) * cosd(-170), cosd(30)};
  EXPECT_POSITIONS(choose(table_table(), tt, {-30, 170}), -30, 190);
  const canon::Direction tt2{sind(-30) * sind(10), sind(-30) * cosd(10), cosd(30)};
  EXPECT_POSITIONS(choose(table_table(), tt2, {-30, 350}), -30, 370);
  // Head-table, C continuous.
  const canon::Direction ht{sind(30) * cosd(-175), -sind(30) * sind(-175), cosd(30)};
  EXPECT_POSITIONS(choose(head_table(), ht, {30, 179}), 30, 185);
}

// A limit forces the other solution even where it turns more.
TEST(KinematicsAngles, LimitForcesTheOtherSolution) {
  // Table-table, A -120..30: from A20 C0 the tool axis of A40 C0 (20 degrees away) is out of
  // reach; A-40 C180 does it.
  const canon::Direction tt{0, sind(40), cosd(40)};
  EXPECT_POSITIONS(choose(table_table(), tt, {20, 0}), -40, 180);
  // Head-head with A -10..110: from C0 A5, A-20 C0 would be shortest; A20 C180 it is.
  const canon::Direction hh{0, sind(20), cosd(20)};
  EXPECT_POSITIONS(choose(head_head(-10, 110), hh, {0, 5}), 180, 20);
  // Head-table with B -10..100: B-20 C0 is out, B20 C180.
  const canon::Direction ht{-sind(20), 0, cosd(20)};
  EXPECT_POSITIONS(choose(head_table(-10, 100), ht, {5, 0}), 20, 180);
  // Neither within the limits: refused with both solutions and the limits named.
  const auto none = Kinematics(head_table()).choose({sind(110), 0, cosd(110)}, {});
  EXPECT_FALSE(none.positions);
  EXPECT_EQ(none.code, diag::Code::KinUnreachable);
  EXPECT_NE(none.refusal.find("B110"), std::string::npos) << none.refusal;
  EXPECT_NE(none.refusal.find("B-110"), std::string::npos) << none.refusal;
  EXPECT_NE(none.refusal.find("B -100..100"), std::string::npos) << none.refusal;
}

TEST(KinematicsAngles, PreferredSolution) {
  auto k = head_head();
  const canon::Direction v{0, -0.5, cosd(30)};
  k.solution = profile::RotarySolution::NegativeTilt;
  EXPECT_POSITIONS(choose(k, v), 180, -30);
  k.solution = profile::RotarySolution::PositiveTilt;
  EXPECT_POSITIONS(choose(k, v, {180, -30}), 0, 30);
  // The preferred side out of reach: the other one.
  k.secondary.min = 0;
  k.solution = profile::RotarySolution::NegativeTilt;
  EXPECT_POSITIONS(choose(k, v), 0, 30);
}

// Direction -1: the axis turns its part the other way, so the angle changes sign.
TEST(KinematicsAngles, DirectionMinusOne) {
  auto k = head_head();
  k.secondary.direction = -1;
  EXPECT_POSITIONS(choose(k, {0, -0.5, cosd(30)}), 0, -30);
  k.primary.direction = -1;
  EXPECT_POSITIONS(choose(k, {0.5, 0, cosd(30)}, {0, -30}), -90, -30);
}

TEST(KinematicsAngles, NoDirection) {
  const auto c = Kinematics(head_head()).choose({0, 0, 0}, {});
  EXPECT_FALSE(c.positions);
  EXPECT_EQ(c.code, diag::Code::KinNoDirection);
  EXPECT_FALSE(Kinematics(head_head()).choose({std::nan(""), 0, 1}, {}).positions);
}

// Machines whose two axes are both across the tool (an A/B head): the pole is where the tool
// lies along the outer axis.
TEST(KinematicsAngles, AxesAcrossTheTool) {
  profile::Kinematics k;
  k.type = KinematicsType::HeadHead;
  k.primary = limited('B', MachineAxis::Y, -120, 120);
  k.secondary = limited('A', MachineAxis::X, -120, 120);
  // v = Ry(B) Rx(A) Z = (cosA sinB, -sinA, cosA cosB).
  const canon::Direction v{cosd(20) * sind(35), -sind(20), cosd(20) * cosd(35)};
  const RotaryPositions p = choose(k, v);
  EXPECT_NEAR(p.primary, 35, kAngle);
  EXPECT_NEAR(p.secondary, 20, kAngle);
}

// Every candidate of random tool axes, for every type and sign, gives the tool axis back
// through the tests' forward kinematics (a different formulation of the same machine).
TEST(KinematicsAngles, RandomAxesRoundTrip) {
  std::mt19937 random(20);
  std::uniform_real_distribution<double> component(-1, 1);
  for (int type = 0; type < 3; ++type) {
    for (const int sign : {1, -1}) {
      profile::Kinematics k = type == 0   ? head_head(-180, 180)
                              : type == 1 ? table_table()
                                          : head_table(-180, 180);
      k.primary.direction = sign;
      if (type == 1) k.primary.min = -180, k.primary.max = 180;
      for (int n = 0; n < 200; ++n) {
        canon::Direction v{component(random), component(random), component(random)};
        const double size = std::hypot(v.i, v.j, v.k);
        if (size < 0.1) continue;
        const auto c = Kinematics(k).choose(v, {});
        ASSERT_TRUE(c.positions) << c.refusal;
        const auto pose = test::forward(k, {0, 0, 0}, Kinematics(k).rotary(*c.positions), 0);
        EXPECT_NEAR(pose.axis[0], v.i / size, 1e-12);
        EXPECT_NEAR(pose.axis[1], v.j / size, 1e-12);
        EXPECT_NEAR(pose.axis[2], v.k / size, 1e-12);
      }
    }
  }
}

// Without tool-centre-point control the linear axes carry the pivots and the tool length:
// converted poses, read back through the forward kinematics, give the tip and the axis.
TEST(KinematicsConverter, LinearAxesFollowThePivots) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-200, 200);
  std::uniform_real_distribution<double> component(-1, 1);
  for (int type = 0; type < 3; ++type) {
    profile::Kinematics k = type == 0 ? head_head() : type == 1 ? table_table() : head_table();
    // Offsets in every direction, so that no term hides behind a zero.
    k.primary.pivot = {12, -7, 150};
    k.secondary.pivot = {-3, 25, 90};
    for (const bool inch : {false, true}) {
      SCOPED_TRACE(std::to_string(type) + (inch ? " inch program" : " mm program"));
      KinematicsConverter converter(k, 1.0);  // pivots in mm
      std::vector<KinematicsConverter::Issue> warnings;
      canon::Call units =
          canon::UseLengthUnits{inch ? canon::Units::Inches : canon::Units::Millimetres};
      ASSERT_FALSE(converter.convert(units, warnings));
      canon::Call length = canon::UseToolLengthOffset{inch ? 3.0 : 76.2};
      ASSERT_FALSE(converter.convert(length, warnings));
      const double pivot_scale = inch ? 1 / 25.4 : 1.0;
      for (int n = 0; n < 100; ++n) {
        canon::Pose to{coordinate(random), coordinate(random), coordinate(random), std::nullopt,
                       canon::Direction{component(random), component(random),
                                        0.2 + std::abs(component(random))}};
        const canon::Pose tip = to;
        canon::Call call = canon::StraightFeed{to};
        const auto issue = converter.convert(call, warnings);
        ASSERT_FALSE(issue) << issue->message;
        const canon::Pose& machine = std::get<canon::StraightFeed>(call).to;
        ASSERT_TRUE(machine.rotary);
        const auto pose = test::forward(k, {machine.x, machine.y, machine.z}, *machine.rotary,
                                        inch ? 3.0 : 76.2, pivot_scale);
        EXPECT_NEAR(pose.tip[0], tip.x, 1e-9);
        EXPECT_NEAR(pose.tip[1], tip.y, 1e-9);
        EXPECT_NEAR(pose.tip[2], tip.z, 1e-9);
        const double size = std::hypot(tip.tool_axis->i, tip.tool_axis->j, tip.tool_axis->k);
        EXPECT_NEAR(pose.axis[0], tip.tool_axis->i / size, 1e-12);
        EXPECT_NEAR(pose.axis[1], tip.tool_axis->j / size, 1e-12);
        EXPECT_NEAR(pose.axis[2], tip.tool_axis->k / size, 1e-12);
      }
    }
  }
}

// A head-head machine by hand: pivot 150 above the gauge point, tool 50: A30 about X swings
// the tip by (200 sin30) along -Y... so the linear axes go the other way.
TEST(KinematicsConverter, HeadHeadPivotByHand) {
  auto k = head_head();
  k.secondary.pivot = {0, 0, 150};
  KinematicsConverter converter(k, 1.0);
  std::vector<KinematicsConverter::Issue> warnings;
  canon::Call length = canon::UseToolLengthOffset{50};
  ASSERT_FALSE(converter.convert(length, warnings));
  canon::Call call =
      canon::StraightFeed{{10, 20, 30, std::nullopt, canon::Direction{0, -0.5, cosd(30)}}};
  ASSERT_FALSE(converter.convert(call, warnings));
  const auto& to = std::get<canon::StraightFeed>(call).to;
  // Tool axis (0, -0.5, 0.866): the tip lies 200 along -axis from the pivot; the gauge-point
  // model of the control (tip = X, head at 0) misses it by 200 (v - Z).
  EXPECT_NEAR(to.x, 10, 1e-12);
  EXPECT_NEAR(to.y, 20 + 200 * -0.5, 1e-9);
  EXPECT_NEAR(to.z, 30 + 200 * (cosd(30) - 1), 1e-9);
  ASSERT_TRUE(to.rotary);
  EXPECT_NEAR(to.rotary->a, 30, kAngle);
  EXPECT_EQ(to.rotary->b, 0);
  EXPECT_NEAR(to.rotary->c, 0, kAngle);
}

TEST(KinematicsConverter, ToolCentrePointKeepsTheTip) {
  auto k = table_table();
  k.tool_centre_point = true;
  k.primary.pivot = {0, 0, -100};
  KinematicsConverter converter(k, 1.0);
  std::vector<KinematicsConverter::Issue> warnings;
  canon::Call call =
      canon::StraightFeed{{10, 20, 30, std::nullopt, canon::Direction{0, -0.5, cosd(30)}}};
  ASSERT_FALSE(converter.convert(call, warnings));
  const auto& to = std::get<canon::StraightFeed>(call).to;
  EXPECT_EQ(to.x, 10);
  EXPECT_EQ(to.y, 20);
  EXPECT_EQ(to.z, 30);
  EXPECT_NEAR(to.rotary->a, -30, kAngle);
}

TEST(KinematicsConverter, MotionsWithoutToolAxisKeepTheOrientation) {
  auto k = head_head();
  k.secondary.pivot = {0, 0, 100};
  KinematicsConverter converter(k, 1.0);
  std::vector<KinematicsConverter::Issue> warnings;
  canon::Call tilt = canon::StraightFeed{{0, 0, 0, std::nullopt, canon::Direction{0, -1, 0}}};
  ASSERT_FALSE(converter.convert(tilt, warnings));
  canon::Call plain = canon::StraightTraverse{{5, 0, 0}};
  ASSERT_FALSE(converter.convert(plain, warnings));
  const auto& to = std::get<canon::StraightTraverse>(plain).to;
  EXPECT_FALSE(to.rotary);        // no rotary words: the axes stay
  EXPECT_NEAR(to.y, -100, 1e-9);  // but the pivot still counts: A90 in force
  EXPECT_NEAR(to.z, -100, 1e-9);
}

TEST(KinematicsConverter, ArcsAndNurbsKeepTheOrientation) {
  auto k = head_table();
  KinematicsConverter converter(k, 1.0);
  std::vector<KinematicsConverter::Issue> warnings;
  canon::Call tilt =
      canon::StraightFeed{{0, 0, 0, std::nullopt, canon::Direction{0.5, 0, cosd(30)}}};
  ASSERT_FALSE(converter.convert(tilt, warnings));
  canon::ArcFeed arc;
  arc.end = {10, 0, 0, std::nullopt, canon::Direction{0.5, 0, cosd(30)}};
  arc.centre = {5, 0, 0};
  canon::Call same = arc;
  EXPECT_FALSE(converter.convert(same, warnings));
  EXPECT_FALSE(std::get<canon::ArcFeed>(same).end.rotary);
  arc.end.tool_axis = canon::Direction{0, 0, 1};
  canon::Call turning = arc;
  const auto issue = converter.convert(turning, warnings);
  ASSERT_TRUE(issue);
  EXPECT_EQ(issue->code, diag::Code::KinOrientationAlongCurve);
  canon::NurbsFeed nurbs;
  nurbs.degree = 1;
  nurbs.points = {{0, 0, 0, 1}, {10, 0, 0, 1}};
  nurbs.knots = {0, 0, 1, 1};
  nurbs.tool_axis = canon::Direction{0, 1, 0};
  canon::Call curve = nurbs;
  ASSERT_TRUE(converter.convert(curve, warnings));
  EXPECT_NEAR(converter.positions().primary, 30, kAngle);  // unchanged by the refused calls
}

TEST(KinematicsConverter, NativeCycles) {
  auto k = table_table();
  k.primary.pivot = {0, 0, -50};
  KinematicsConverter converter(k, 1.0);
  std::vector<KinematicsConverter::Issue> warnings;
  // G81 at (10, 0): safe level 50, R plane 2, bottom -10, feed 100.
  const canon::Cycle drill{canon::CycleKind::Drill, 10, 0, 50, 2, -10, 100, 0};
  // Tool along Z with the table turned by C90 (A30 C90, then the pole keeps C90): the hole
  // turns with the table to (0, 10), the levels stay.
  canon::Call turn =
      canon::StraightTraverse{{0, 0, 50, std::nullopt, canon::Direction{0.5, 0, cosd(30)}}};
  ASSERT_FALSE(converter.convert(turn, warnings));
  canon::Call up = canon::StraightTraverse{{0, 0, 50, std::nullopt, canon::Direction{0, 0, 1}}};
  ASSERT_FALSE(converter.convert(up, warnings));
  EXPECT_POSITIONS(converter.positions(), 0, 90);
  canon::Call cycle = drill;
  ASSERT_FALSE(converter.convert(cycle, warnings));
  EXPECT_NEAR(std::get<canon::Cycle>(cycle).x, 0, 1e-12);
  EXPECT_NEAR(std::get<canon::Cycle>(cycle).y, 10, 1e-12);
  EXPECT_NEAR(std::get<canon::Cycle>(cycle).safe_z, 50, 1e-12);
  EXPECT_NEAR(std::get<canon::Cycle>(cycle).bottom_z, -10, 1e-12);
  // Tilted: refused.
  canon::Call tilt =
      canon::StraightTraverse{{0, 0, 50, std::nullopt, canon::Direction{0, -0.5, cosd(30)}}};
  ASSERT_FALSE(converter.convert(tilt, warnings));
  canon::Call refused = drill;
  const auto issue = converter.convert(refused, warnings);
  ASSERT_TRUE(issue);
  EXPECT_EQ(issue->code, diag::Code::KinNativeCycleTilted);
}

TEST(KinematicsConverter, LargeRotationWarns) {
  auto k = head_head(-10, 110);
  KinematicsConverter converter(k, 1.0);
  std::vector<KinematicsConverter::Issue> warnings;
  canon::Call a = canon::StraightFeed{{0, 0, 0, std::nullopt, canon::Direction{0, -0.5, cosd(30)}}};
  ASSERT_FALSE(converter.convert(a, warnings));
  EXPECT_TRUE(warnings.empty());
  // C0 A30 -> C180 A30 within one feed motion: A-30 (the shorter way) is outside A's limits.
  canon::Call b = canon::StraightFeed{{0, 0, 0, std::nullopt, canon::Direction{0, 0.5, cosd(30)}}};
  ASSERT_FALSE(converter.convert(b, warnings));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].code, diag::Code::KinLargeRotation);
  // A rapid does not warn; 0 turns the warning off.
  warnings.clear();
  canon::Call c =
      canon::StraightTraverse{{0, 0, 0, std::nullopt, canon::Direction{0, -0.5, cosd(30)}}};
  ASSERT_FALSE(converter.convert(c, warnings));
  EXPECT_TRUE(warnings.empty());
  k.rotation_warning = 0;
  KinematicsConverter quiet(k, 1.0);
  canon::Call d = b;
  ASSERT_FALSE(quiet.convert(a, warnings));
  ASSERT_FALSE(quiet.convert(d, warnings));
  EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace ncpost::render
