// The converter: modal state → canonical calls, in the conventions of docs/gcode.md (program
// frame and sections, coordinates as rs274 prints them, work offsets as SET_ORIGIN_OFFSETS,
// arcs in three planes, canned cycles as canonical cycles when they map exactly).

#include <gtest/gtest.h>

#include <algorithm>

#include "gcode_support.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::gcode {
namespace {

using test::read;

TEST(Convert, ProgramFrameAndSections) {
  const auto r = read(
      "(operation one)\n"
      "G0 X1\n"
      "(FACE MILL)\n"
      "T3 M6\n"
      "S1000 M3 F200\n"
      "G1 X2\n"
      "T4 M6\n"
      "G1 X3\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(canon::trace(r.calls),
            "    1 PROJECT_BEGIN($, NC_PROGRAM, \"t.ngc\")\n"
            "    2 USE_LENGTH_UNITS(CANON_UNITS_MM)\n"
            "    3 SET_ORIGIN_OFFSETS(0.0000, 0.0000, 0.0000)\n"
            "    4 SET_FEED_REFERENCE(CANON_XYZ)\n"
            "    5 SELECT_PLANE(CANON_PLANE_XY)\n"
            "    6 COMMENT(\"operation one\")\n"
            "    7 WORKINGSTEP_BEGIN(#2, NC_SECTION, \"operation one\")\n"
            "    8 STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000)\n"
            "    9 COMMENT(\"FACE MILL\")\n"
            "   10 SELECT_TOOL(3)\n"
            "   11 WORKINGSTEP_END(#2, NC_SECTION, \"operation one\")\n"
            "   12 WORKINGSTEP_BEGIN(#4, NC_SECTION, \"FACE MILL\")\n"
            "   13 CHANGE_TOOL(3)\n"
            "   14 SET_FEED_RATE(200.0000)\n"
            "   15 SET_SPINDLE_SPEED(1000.0000)\n"
            "   16 START_SPINDLE_CLOCKWISE()\n"
            "   17 STRAIGHT_FEED(2.0000, 0.0000, 0.0000)\n"
            "   18 SELECT_TOOL(4)\n"
            "   19 WORKINGSTEP_END(#4, NC_SECTION, \"FACE MILL\")\n"
            "   20 WORKINGSTEP_BEGIN(#7, NC_SECTION, \"T4\")\n"
            "   21 CHANGE_TOOL(4)\n"
            "   22 STRAIGHT_FEED(3.0000, 0.0000, 0.0000)\n"
            "   23 WORKINGSTEP_END(#7, NC_SECTION, \"T4\")\n"
            "   24 PROGRAM_END()\n"
            "   25 PROJECT_END($, NC_PROGRAM, \"t.ngc\")\n");
}

TEST(Convert, UnitsAndDistanceModes) {
  const auto r = read("G20 G0 X1\nG91 G0 X1 Y-1\nG21 G90 G0 X25.4\nM2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.body(),
            "USE_LENGTH_UNITS(CANON_UNITS_INCHES)\n"
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(2.0000, -1.0000, 0.0000)\n"
            "USE_LENGTH_UNITS(CANON_UNITS_MM)\n"
            "STRAIGHT_TRAVERSE(25.4000, -25.4000, 0.0000)\n"
            "PROGRAM_END()\n");
}

TEST(Convert, WorkOffsetsAndAxisOffsets) {
  // As rs274 prints them: coordinates in the current system, offsets beside.
  const auto r = read(
      "G10 L2 P2 X10 Y20\n"
      "G55 G0 X1\n"  // machine X 11
      "G92 X0\n"     // the current point becomes X0
      "G0 X1\n"
      "G92.1\n"
      "G53 G0 X0\n"  // machine 0 → program -10
      "G54 G0 Y0\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.body(),
            "SET_ORIGIN_OFFSETS(10.0000, 20.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, -20.0000, 0.0000)\n"
            "SET_ORIGIN_OFFSETS(11.0000, 20.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, -20.0000, 0.0000)\n"
            "SET_ORIGIN_OFFSETS(10.0000, 20.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(-10.0000, -20.0000, 0.0000)\n"
            "SET_ORIGIN_OFFSETS(0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(0.0000, 0.0000, 0.0000)\n"
            "PROGRAM_END()\n");
}

TEST(Convert, ArcsInThreePlanes) {
  // rs274: G18 G2 X-5 Z1 I0.5 K0.5 from (-6, 0, 0) → ARC_FEED(1, -5, 0.5, -5.5, -1, 0).
  const auto r = read(
      "G0 X-6 F100\n"
      "G18 G2 X-5 Z1 I0.5 K0.5\n"
      "G17 G2 X-5 Y0 I1 J0 P2\n"
      "G19 G3 Y1 Z2 J0.5 K0.5\n"
      "G17 G0 X-5 Y0\n"
      "G2 X5 Y0 R5\n"
      "G3 X-5 Y0 R-5\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(-6.0000, 0.0000, 0.0000)\n"
            "ARC_FEED(1.0000, -5.0000, 0.5000, -5.5000, -1, 0.0000)\n"
            "ARC_FEED(-5.0000, 0.0000, -4.0000, 0.0000, -2, 1.0000)\n"
            "ARC_FEED(1.0000, 2.0000, 0.5000, 1.5000, 1, -5.0000)\n"
            "STRAIGHT_TRAVERSE(-5.0000, 0.0000, 2.0000)\n"
            "ARC_FEED(5.0000, 0.0000, 0.0000, 0.0000, -1, 2.0000)\n"
            "ARC_FEED(-5.0000, 0.0000, 0.0000, 0.0000, 1, 2.0000)\n");
}

TEST(Convert, FullCircleByCentreAlone) {
  const auto r = read("G0 X1 Y1 F30\nG2 I.5 J.5\nM2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(1.0000, 1.0000, 0.0000)\n"
            "ARC_FEED(1.0000, 1.0000, 1.5000, 1.5000, -1, 0.0000)\n");
}

TEST(Convert, CannedCyclesMapToCanonicalCycles) {
  const auto r = read(
      "G0 X0 Y0 Z10 F100 S500 M3\n"
      "G98 G81 X1 Y1 Z-2 R2\n"
      "X2\n"  // the modal cycle at a second hole
      "G99 G83 X3 Y3 Z-2 R2 Q1\n"
      "G73 X4 Q1\n"
      "G82 X5 P0.5\n"
      "G85 X6\n"
      "G86 X7 P1\n"
      "G80\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(
      r.motions(),
      "STRAIGHT_TRAVERSE(0.0000, 0.0000, 10.0000)\n"
      "DRILL_CYCLE(1.0000, 1.0000, 10.0000, 2.0000, -2.0000, 100.0000, 0.0000)\n"
      "DRILL_CYCLE(2.0000, 1.0000, 10.0000, 2.0000, -2.0000, 100.0000, 0.0000)\n"
      "STRAIGHT_TRAVERSE(3.0000, 3.0000, 10.0000)\n"
      "PECK_DRILL_CYCLE(3.0000, 3.0000, 2.0000, 2.0000, -2.0000, 100.0000, 0.0000, 1.0000, 0.0000, "
      "0.2540)\n"
      "PECK_DRILL_CYCLE(4.0000, 3.0000, 2.0000, 2.0000, -2.0000, 100.0000, 0.0000, 1.0000, 0.2540, "
      "0.0000)\n"
      "DRILL_CYCLE(5.0000, 3.0000, 2.0000, 2.0000, -2.0000, 100.0000, 0.5000)\n"
      "BORE_CYCLE(6.0000, 3.0000, 2.0000, 2.0000, -2.0000, 100.0000, 0.0000, FEED_OUT)\n"
      "BORE_CYCLE(7.0000, 3.0000, 2.0000, 2.0000, -2.0000, 100.0000, 1.0000, SPINDLE_STOP)\n");
}

TEST(Convert, CyclesOutsideXyBecomeMotions) {
  // rs274 (g81/g18/g98): over the hole at the old level, down to R, feed along -Y, back.
  const auto r = read("G18 G98 G20 F10\nG0 X0 Y2 Z0\nG81 X1 Z1 Y-1 R1\nM2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(0.0000, 2.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 2.0000, 1.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 1.0000, 1.0000)\n"
            "STRAIGHT_FEED(1.0000, -1.0000, 1.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 2.0000, 1.0000)\n");
}

TEST(Convert, HomeAndDwellAndCoolant) {
  const auto r = read("G0 X5 Y5 Z5\nG28 Z10\nG4 P1.5\nM7 M8\nM9\nM2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.body(),
            "STRAIGHT_TRAVERSE(5.0000, 5.0000, 5.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 5.0000, 10.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 5.0000, 0.0000)\n"
            "DWELL(1.5000)\n"
            "MIST_ON()\n"
            "FLOOD_ON()\n"
            "MIST_OFF()\n"
            "FLOOD_OFF()\n"
            "PROGRAM_END()\n");
}

TEST(Convert, RotaryAxesEverywhereOrNowhere) {
  const auto r = read("G0 X1\nG0 A90\nM2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 90.0000, 0.0000, 0.0000)\n");
}

// Whether a program has rotary words is decided before it is read, by a scan over its bytes
// (eight at a time where none is looked at): letters in comments, in names, in a macro call's
// arguments, or not followed by a value are not axis words; one anywhere else is.
TEST(Convert, RotaryWordsAreFoundWhereverTheyStand) {
  const std::string padding = "G0 X1 (A1 B2 C3 in a comment) ; A4 after a remark\n";
  const std::string none[] = {
      padding + "G0 Y2\nM2\n",
      padding + "#<_abc> = 1\nG0 X#<_abc>\nM2\n",
      padding + "(unclosed A5\nG0 Y2\nM2\n",
      "G0 X0\nM2\n",
  };
  for (const auto& text : none) {
    const auto r = read(text);
    const auto first = r.motions().substr(0, r.motions().find('\n'));
    EXPECT_EQ(std::count(first.begin(), first.end(), ','), 2) << text << "\n" << r.motions();
  }
  // At every offset within eight bytes, and in lower case.
  for (int shift = 0; shift < 9; ++shift) {
    const std::string text = padding + std::string(static_cast<std::size_t>(shift), ' ') +
                             (shift % 2 ? "G0 a90\n" : "G0 C-90\n") + "M2\n";
    const auto r = read(text);
    EXPECT_TRUE(r.result.ok()) << text << r.messages();
    const auto first = r.motions().substr(0, r.motions().find('\n'));
    EXPECT_EQ(std::count(first.begin(), first.end(), ','), 5) << text << "\n" << r.motions();
  }
}

TEST(Convert, PolarCoordinates) {
  // rs274 2.9 on the same lines.
  const auto r = read("G90 G0 @2 ^90\nG0 X3 Y4\nG91 G0 @1 ^0\nG91 G0 ^90\nG90 G0 @5\nM2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(0.0000, 2.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(3.0000, 4.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(3.6000, 4.8000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(-4.8000, 3.6000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(-4.0000, 3.0000, 0.0000)\n");
}

TEST(Convert, StreamsIntoTheSink) {
  // A sink that only counts: the read holds no calls itself.
  struct Count final : canon::Sink {
    std::size_t n = 0;
    void call(const canon::Call&) override { ++n; }
  } count;
  std::string text;
  for (int i = 0; i < 2000; ++i) text += "G1 X" + std::to_string(i) + " F100\n";
  const auto result = gcode::read(text + "M2\n", *test::dialect("linuxcnc"), count);
  EXPECT_EQ(result.calls, count.n);
  EXPECT_GT(count.n, 4000u);
}

}  // namespace
}  // namespace ncpost::gcode
