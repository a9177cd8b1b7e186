// Heidenhain Klartext (heidenhain-tnc640's dialect.json, klartext.cpp): the reading subset
// docs/gcode.md lists — L/FMAX, CC with C, CR and CP, TOOL CALL, the cycles 200/203, 7 and 9,
// Q parameters with formulas and FN functions, labels, repeats and subprograms — and what it
// refuses by name.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "gcode_support.hpp"

namespace ncpost::gcode {
namespace {

using test::read;

test::Read tnc(const std::string& body, ReadOptions options = {}) {
  options.program_name = "T.H";
  return read("0 BEGIN PGM T MM\n" + body + "99 END PGM T MM\n", "heidenhain-tnc640",
              std::move(options));
}

// The end points of the motions, "x,y,z" rounded to 0.001, space-separated.
std::string ends(const test::Read& r) {
  std::string out;
  auto add = [&](const canon::Pose& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%g,%g,%g ", std::round(p.x * 1000) / 1000 + 0.0,
                  std::round(p.y * 1000) / 1000 + 0.0, std::round(p.z * 1000) / 1000 + 0.0);
    out += buf;
  };
  for (const auto& c : r.calls) {
    if (const auto* t = std::get_if<canon::StraightTraverse>(&c)) add(t->to);
    if (const auto* f = std::get_if<canon::StraightFeed>(&c)) add(f->to);
    if (const auto* a = std::get_if<canon::ArcFeed>(&c)) add(a->end);
  }
  return out;
}

TEST(Klartext, LinesRapidsAndIncrements) {
  const auto r =
      tnc("1 L X+10 Y+5 Z+50 R0 FMAX\n"
          "2 L IX+5 IY-5 F200\n"
          "3 L Z-2.5\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(ends(r), "10,5,50 15,0,50 15,0,-2.5 ");
  bool rapid_first = false;
  for (const auto& c : r.calls) {
    if (std::holds_alternative<canon::StraightTraverse>(c)) {
      rapid_first = true;
      break;
    }
    if (std::holds_alternative<canon::StraightFeed>(c)) break;
  }
  EXPECT_TRUE(rapid_first);
}

TEST(Klartext, QParametersFormulasAndFn) {
  const auto r =
      tnc("1 Q1 = 3\n"
          "2 Q2 = (Q1 + 1) * 2 ^ 2\n"      // 16
          "3 FN 1: Q3 = +Q1 + +4\n"        // 7
          "4 FN 3: Q4 = +Q3 * +2\n"        // 14
          "5 FN 5: Q5 = SQRT +Q2\n"        // 4
          "6 FN 8: Q6 = +3 LEN +4\n"       // 5
          "7 FN 6: Q7 = SIN +30\n"         // 0.5 (degrees)
          "7 QL1 = Q6 * 2 + Q7 * 2 - 1\n"  // 10
          "8 L X+Q2 Y+Q3 Z+Q4 FMAX\n"
          "9 L X+Q5 Y+Q6 Z+QL1 FMAX\n"
          "10 L X-Q1 FMAX\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(ends(r), "16,7,14 4,5,10 -3,5,10 ");
}

TEST(Klartext, LabelsRepeatsJumpsAndSubprograms) {
  const auto r =
      tnc("1 Q1 = 0\n"
          "2 LBL 1\n"
          "3 Q1 = Q1 + 1\n"
          "4 L X+Q1 FMAX\n"
          "5 CALL LBL 1 REP 2\n"                // the section 1 + 2 times: X1 X2 X3
          "6 FN 12: IF +Q1 LT +5 GOTO LBL 1\n"  // X4 X5 (a new repeat count each pass: 2 more each)
          "7 CALL LBL 9\n"
          "8 L X+100 FMAX\n"
          "9 L M30\n"
          "10 LBL 9\n"
          "11 L Y+7 FMAX\n"
          "12 LBL 0\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  const std::string e = ends(r);
  // After the jump back, CALL LBL 1 REP 2 repeats again from its count.
  EXPECT_EQ(e.substr(0, 24), "1,0,0 2,0,0 3,0,0 4,0,0 ") << e;
  EXPECT_NE(e.find("100,7,0"), std::string::npos) << e;
  EXPECT_NE(e.find(",7,0 100,7,0 "), std::string::npos) << e;
}

TEST(Klartext, ArcsByCentreRadiusAndHelix) {
  const auto r =
      tnc("1 L X+10 Y+0 Z+0 FMAX\n"
          "2 CC X+0 Y+0\n"
          "3 C X+0 Y+10 DR+ F100\n"    // a quarter, counter-clockwise
          "4 CR X-10 Y+0 R+10 DR+\n"   // the next quarter by its radius
          "5 CP IPA+360 IZ-2 DR+\n");  // a full helical turn about CC
  ASSERT_TRUE(r.result.ok()) << r.messages();
  std::vector<canon::ArcFeed> arcs;
  for (const auto& c : r.calls)
    if (const auto* a = std::get_if<canon::ArcFeed>(&c)) arcs.push_back(*a);
  ASSERT_EQ(arcs.size(), 3u);
  EXPECT_NEAR(arcs[0].end.x, 0, 1e-9);
  EXPECT_NEAR(arcs[0].end.y, 10, 1e-9);
  EXPECT_GT(arcs[0].normal.k, 0);  // DR+: counter-clockwise seen from +Z
  EXPECT_NEAR(arcs[1].end.x, -10, 1e-9);
  EXPECT_NEAR(arcs[1].centre.x, 0, 1e-9);
  EXPECT_NEAR(arcs[1].centre.y, 0, 1e-9);
  EXPECT_NEAR(arcs[2].end.x, -10, 1e-9);
  EXPECT_NEAR(arcs[2].end.y, 0, 1e-9);
  EXPECT_NEAR(arcs[2].end.z, -2, 1e-9);
  EXPECT_GT(arcs[2].normal.k, 0);
}

TEST(Klartext, DrillingCycleWithItsOwnFeed) {
  const auto r =
      tnc("1 TOOL CALL 5 Z S2000\n"
          "2 L X+0 Y+0 Z+50 F300\n"
          "3 CYCL DEF 200 DRILLING ~\n"
          "  Q200=+2 ;SET-UP CLEARANCE ~\n"
          "  Q201=-10 ;DEPTH ~\n"
          "  Q206=+150 ;FEED RATE FOR PLNGNG ~\n"
          "  Q202=+10 ;PLUNGING DEPTH ~\n"
          "  Q210=+0 ;DWELL TIME AT TOP ~\n"
          "  Q203=+0 ;SURFACE COORDINATE ~\n"
          "  Q204=+20 ;2ND SET-UP CLEARANCE ~\n"
          "  Q211=+0 ;DWELL TIME AT DEPTH\n"
          "4 L X+10 Y+20 FMAX M99\n"
          "5 L X+30 FMAX\n"
          "6 CYCL CALL\n");
  ASSERT_TRUE(r.result.ok()) << r.messages();
  std::vector<canon::Cycle> cycles;
  for (const auto& c : r.calls)
    if (const auto* cy = std::get_if<canon::Cycle>(&c)) cycles.push_back(*cy);
  ASSERT_EQ(cycles.size(), 2u);
  EXPECT_NEAR(cycles[0].x, 10, 1e-9);
  EXPECT_NEAR(cycles[0].y, 20, 1e-9);
  EXPECT_NEAR(cycles[0].r_z, 2, 1e-9);
  EXPECT_NEAR(cycles[0].bottom_z, -10, 1e-9);
  EXPECT_NEAR(cycles[0].safe_z, 20, 1e-9);
  EXPECT_NEAR(cycles[0].feed, 150, 1e-9);
  EXPECT_NEAR(cycles[1].x, 30, 1e-9);
  // The cycle's feed does not stay: the feed in force after it is the program's 300 again.
  double last_feed = 0;
  for (const auto& c : r.calls)
    if (const auto* f = std::get_if<canon::SetFeedRate>(&c)) last_feed = f->rate;
  EXPECT_NEAR(last_feed, 300, 1e-9);
}

TEST(Klartext, DatumShiftAndDwell) {
  const auto r =
      tnc("1 CYCL DEF 7.0 DATUM SHIFT\n"
          "2 CYCL DEF 7.1 X+100\n"
          "3 CYCL DEF 7.2 Y+50\n"
          "4 L X+1 Y+2 Z+3 FMAX\n"
          "5 CYCL DEF 9.0 DWELL TIME\n"
          "6 CYCL DEF 9.1 DWELL 1.5\n");
  ASSERT_TRUE(r.result.ok()) << r.messages();
  // As every dialect's offsets: the motion in the shifted system, the shift as the origin's.
  EXPECT_EQ(ends(r), "1,2,3 ");
  std::optional<canon::Point> origin;
  for (const auto& c : r.calls)
    if (const auto* o = std::get_if<canon::SetOriginOffsets>(&c)) origin = o->offset;
  ASSERT_TRUE(origin);
  EXPECT_NEAR(origin->x, 100, 1e-9);
  EXPECT_NEAR(origin->y, 50, 1e-9);
  EXPECT_NEAR(origin->z, 0, 1e-9);
  bool dwell = false;
  for (const auto& c : r.calls)
    if (const auto* d = std::get_if<canon::Dwell>(&c)) dwell = std::abs(d->seconds - 1.5) < 1e-9;
  EXPECT_TRUE(dwell);
}

TEST(Klartext, CallPgmFromTheUploadedFiles) {
  ReadOptions o;
  o.subprograms.push_back({"SUB.H", "0 BEGIN PGM SUB MM\n1 L X+42 FMAX\n2 END PGM SUB MM\n"});
  const auto r = tnc("1 CALL PGM TNC:\\PARTS\\SUB.H\n2 L Y+1 FMAX\n", o);
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(ends(r), "42,0,0 42,1,0 ");
}

TEST(Klartext, RefusedAndWrongBlocksAreNamed) {
  EXPECT_TRUE(tnc("1 L X+10 RL F100\n").has(diag::Code::GcodeUnsupported));
  EXPECT_TRUE(tnc("1 RND R5\n").has(diag::Code::GcodeUnsupported));
  EXPECT_TRUE(tnc("1 CYCL DEF 251 RECTANGULAR POCKET\n").has(diag::Code::GcodeUnsupported));
  EXPECT_TRUE(tnc("1 C X+1 Y+0 DR+\n").has(diag::Code::GcodeMissingWord));  // no CC
  EXPECT_TRUE(tnc("1 CALL LBL 7\n").has(diag::Code::GcodeBadFlow));
  EXPECT_TRUE(tnc("1 CYCL CALL\n").has(diag::Code::GcodeBadFlow));
  EXPECT_TRUE(tnc("1 FN 14: ERROR = 1000\n").has(diag::Code::GcodeAbort));
  EXPECT_TRUE(tnc("1 L X+1 M128\n").has(diag::Code::GcodeUnsupported));
  EXPECT_TRUE(tnc("1 L XYZ\n").has(diag::Code::GcodeUnknownWord));
  EXPECT_TRUE(tnc("1 TOOL CALL \"MILL\" Z\n").has(diag::Code::GcodeUnsupported));
  // A machine value (FN 18) warns; a motion that depends on it is an error.
  const auto sys = tnc("1 FN 18: SYSREAD Q1 = ID270 NR1\n2 L X+Q1 FMAX\n");
  EXPECT_TRUE(sys.has(diag::Code::GcodeMachineValue)) << sys.messages();
  EXPECT_TRUE(sys.has(diag::Code::GcodeMachineMotion)) << sys.messages();
}

TEST(Klartext, EndlessJumpsStopAtMaxSteps) {
  ReadOptions o;
  o.max_steps = 1000;
  const auto r = tnc("1 LBL 1\n2 FN 9: IF +0 EQU +0 GOTO LBL 1\n", o);
  EXPECT_FALSE(r.result.ok());
  EXPECT_TRUE(r.has(diag::Code::GcodeStepLimit)) << r.messages();
}

}  // namespace
}  // namespace ncpost::gcode
