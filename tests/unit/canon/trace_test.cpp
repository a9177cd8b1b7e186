// The text trace: exact strings for every call, numbers, strings, line numbers.

#include "ncpost/canon/trace.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "canon_support.hpp"

namespace ncpost::canon {
namespace {

using test::entity;

std::string number(double v) {
  std::string s;
  append_number(s, v);
  return s;
}

std::string quoted(std::string_view text) {
  std::string s;
  append_quoted(s, text);
  return s;
}

TEST(CanonTrace, SetUpCalls) {
  EXPECT_EQ(format_call(UseLengthUnits{Units::Millimetres}), "USE_LENGTH_UNITS(CANON_UNITS_MM)");
  EXPECT_EQ(format_call(UseLengthUnits{Units::Inches}), "USE_LENGTH_UNITS(CANON_UNITS_INCHES)");
  EXPECT_EQ(format_call(UseLengthUnits{Units::Centimetres}), "USE_LENGTH_UNITS(CANON_UNITS_CM)");
  EXPECT_EQ(format_call(SetOriginOffsets{{1, 2, -14.7}, {}}),
            "SET_ORIGIN_OFFSETS(1.0000, 2.0000, -14.7000)");
  EXPECT_EQ(format_call(SetOriginOffsets{{1, 2, 3}, Rotary{90, 0, -45}}),
            "SET_ORIGIN_OFFSETS(1.0000, 2.0000, 3.0000, 90.0000, 0.0000, -45.0000)");
  EXPECT_EQ(format_call(SetFeedReference{FeedReference::Workpiece}),
            "SET_FEED_REFERENCE(CANON_WORKPIECE)");
  EXPECT_EQ(format_call(SetFeedReference{FeedReference::Xyz}), "SET_FEED_REFERENCE(CANON_XYZ)");
  EXPECT_EQ(format_call(SelectPlane{Plane::Xy}), "SELECT_PLANE(CANON_PLANE_XY)");
  EXPECT_EQ(format_call(SelectPlane{Plane::Yz}), "SELECT_PLANE(CANON_PLANE_YZ)");
  EXPECT_EQ(format_call(SelectPlane{Plane::Xz}), "SELECT_PLANE(CANON_PLANE_XZ)");
}

TEST(CanonTrace, StraightMotions) {
  EXPECT_EQ(format_call(StraightTraverse{{1, 2, 3, {}, {}}}),
            "STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000)");
  EXPECT_EQ(format_call(StraightFeed{{91.9, -13.5, 2.5, {}, {}}}),
            "STRAIGHT_FEED(91.9000, -13.5000, 2.5000)");
  // Rotary axes follow x, y, z; a tool axis follows them (or x, y, z when there are none).
  EXPECT_EQ(format_call(StraightFeed{{1, 2, 3, Rotary{10, 20, 30}, {}}}),
            "STRAIGHT_FEED(1.0000, 2.0000, 3.0000, 10.0000, 20.0000, 30.0000)");
  EXPECT_EQ(format_call(StraightFeed{{1, 2, 3, {}, Direction{0, 0, 1}}}),
            "STRAIGHT_FEED(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 1.0000)");
  EXPECT_EQ(format_call(StraightTraverse{{1, 2, 3, Rotary{0, 45, 90}, Direction{0.5, 0, 0.5}}}),
            "STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 45.0000, 90.0000, 0.5000, "
            "0.0000, 0.5000)");
}

TEST(CanonTrace, ArcsPrintRs274Arguments) {
  EXPECT_EQ(format_call(ArcFeed{{20, 2, 3, {}, {}}, {15, 2, 3}, {0, 0, 1}, -1}),
            "ARC_FEED(20.0000, 2.0000, 15.0000, 2.0000, -1, 3.0000)");
  EXPECT_EQ(format_call(ArcFeed{{20, 2, 3, Rotary{0, 0, 90}, {}}, {15, 2, 3}, {0, 0, 1}, 2}),
            "ARC_FEED(20.0000, 2.0000, 15.0000, 2.0000, 2, 3.0000, 0.0000, 0.0000, 90.0000)");
  // A tilted plane has no rs274 form.
  EXPECT_EQ(format_call(ArcFeed{{1, 1, 1, {}, {}}, {0, 0, 0}, {0, -1, 1}, 1}),
            "ARC_FEED_3D(1.0000, 1.0000, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000, -1.0000, "
            "1.0000, 1)");
}

TEST(CanonTrace, Nurbs) {
  NurbsFeed n{.degree = 2,
              .points = {{0, 0, 0, 1}, {1, 2, 0, 0.5}, {3, 0, 0, 1}},
              .knots = {0, 0, 0, 1, 1, 1}};
  EXPECT_EQ(format_call(n),
            "NURBS_FEED(2, [(0.0000, 0.0000, 0.0000, 1.0000), (1.0000, 2.0000, 0.0000, 0.5000), "
            "(3.0000, 0.0000, 0.0000, 1.0000)], [0.0000, 0.0000, 0.0000, 1.0000, 1.0000, 1.0000])");
  EXPECT_EQ(
      format_call(NurbsFeed{.degree = 1, .points = {}, .knots = {}, .rotary = Rotary{1, 2, 3}}),
      "NURBS_FEED(1, [], [], 1.0000, 2.0000, 3.0000)");
}

TEST(CanonTrace, FeedSpindleToolsCoolantOther) {
  EXPECT_EQ(format_call(SetFeedRate{250}), "SET_FEED_RATE(250.0000)");
  EXPECT_EQ(format_call(SetSpindleSpeed{1200.5}), "SET_SPINDLE_SPEED(1200.5000)");
  EXPECT_EQ(format_call(StartSpindleClockwise{}), "START_SPINDLE_CLOCKWISE()");
  EXPECT_EQ(format_call(StartSpindleCounterclockwise{}), "START_SPINDLE_COUNTERCLOCKWISE()");
  EXPECT_EQ(format_call(StopSpindleTurning{}), "STOP_SPINDLE_TURNING()");
  EXPECT_EQ(format_call(SpindleRetract{}), "SPINDLE_RETRACT()");
  EXPECT_EQ(format_call(SelectTool{7}), "SELECT_TOOL(7)");
  EXPECT_EQ(format_call(ChangeTool{7}), "CHANGE_TOOL(7)");
  EXPECT_EQ(format_call(UseToolLengthOffset{12.9794}), "USE_TOOL_LENGTH_OFFSET(12.9794)");
  EXPECT_EQ(format_call(FloodOn{}), "FLOOD_ON()");
  EXPECT_EQ(format_call(FloodOff{}), "FLOOD_OFF()");
  EXPECT_EQ(format_call(MistOn{}), "MIST_ON()");
  EXPECT_EQ(format_call(MistOff{}), "MIST_OFF()");
  EXPECT_EQ(format_call(Dwell{1.5}), "DWELL(1.5000)");
  EXPECT_EQ(format_call(Comment{"comment here"}), "COMMENT(\"comment here\")");
  EXPECT_EQ(format_call(Message{"hello"}), "MESSAGE(\"hello\")");
  EXPECT_EQ(format_call(OptionalProgramStop{}), "OPTIONAL_PROGRAM_STOP()");
  EXPECT_EQ(format_call(ProgramStop{}), "PROGRAM_STOP()");
  EXPECT_EQ(format_call(ProgramEnd{}), "PROGRAM_END()");
}

// The output options follow the name on WORKINGSTEP_BEGIN, only those set, in table order;
// the END marker does not repeat them (web/src/trace.js reads both forms).
TEST(CanonTrace, WorkingstepOutputOptions) {
  OutputOptions options;
  EXPECT_EQ(set_output_option(options, "subprogram", "on"), "");
  EXPECT_EQ(format_call(Begin{Scope::Workingstep, entity(4, "CL_OPERATION", "A_SUB"), options}),
            "WORKINGSTEP_BEGIN(#4, CL_OPERATION, \"A_SUB\", subprogram=on)");
  EXPECT_EQ(set_output_option(options, "block_numbers", "off"), "");
  EXPECT_EQ(format_call(Begin{Scope::Workingstep, entity(0, "", "x"), options}),
            "WORKINGSTEP_BEGIN($, $, \"x\", block_numbers=off, subprogram=on)");
  EXPECT_EQ(format_call(End{Scope::Workingstep, entity(0, "", "x")}),
            "WORKINGSTEP_END($, $, \"x\")");
  // Unknown names and values are refused with a message that names them.
  EXPECT_NE(set_output_option(options, "numbering", "off").find("'numbering'"), std::string::npos);
  EXPECT_NE(set_output_option(options, "block_numbers", "yes").find("'yes'"), std::string::npos);
  EXPECT_EQ(options.block_numbers, Switch::Off);  // unchanged by the refused ones
  // The first rule that sets an option decides it.
  OutputOptions first;
  EXPECT_EQ(set_output_option(first, "block_numbers", "on"), "");
  add_unset(first, options);
  EXPECT_EQ(first.block_numbers, Switch::On);
  EXPECT_EQ(first.subprogram, Switch::On);
}

TEST(CanonTrace, StructureMarkers) {
  EXPECT_EQ(format_call(Begin{Scope::Workingstep,
                              entity(10, "MACHINING_WORKINGSTEP", "WS FINISH PLANAR FACE1")}),
            "WORKINGSTEP_BEGIN(#10, MACHINING_WORKINGSTEP, \"WS FINISH PLANAR FACE1\")");
  EXPECT_EQ(format_call(End{Scope::Workingstep,
                            entity(10, "MACHINING_WORKINGSTEP", "WS FINISH PLANAR FACE1")}),
            "WORKINGSTEP_END(#10, MACHINING_WORKINGSTEP, \"WS FINISH PLANAR FACE1\")");
  EXPECT_EQ(format_call(Begin{Scope::Project, entity(1, "PROJECT", "p")}),
            "PROJECT_BEGIN(#1, PROJECT, \"p\")");
  EXPECT_EQ(format_call(End{Scope::Project, entity(1, "PROJECT", "p")}),
            "PROJECT_END(#1, PROJECT, \"p\")");
  EXPECT_EQ(format_call(Begin{Scope::Setup, entity(18446744073709551615ULL, "SETUP", "")}),
            "SETUP_BEGIN(#18446744073709551615, SETUP, \"\")");
  EXPECT_EQ(format_call(End{Scope::Setup, entity(5, "SETUP", "s")}), "SETUP_END(#5, SETUP, \"s\")");
  // No entity: `$`. A type that is not an identifier is quoted.
  EXPECT_EQ(format_call(Begin{Scope::Workplan, entity(0, "", "synthesised")}),
            "WORKPLAN_BEGIN($, $, \"synthesised\")");
  EXPECT_EQ(format_call(End{Scope::Workplan, entity(3, "bad type)", "x")}),
            "WORKPLAN_END(#3, \"bad type)\", \"x\")");
}

TEST(CanonTrace, Cycles) {
  const Cycle drill{.kind = CycleKind::Drill,
                    .x = 10,
                    .y = 20,
                    .safe_z = 50,
                    .r_z = 2,
                    .bottom_z = -10,
                    .feed = 100,
                    .dwell = 0.5};
  EXPECT_EQ(format_call(drill),
            "DRILL_CYCLE(10.0000, 20.0000, 50.0000, 2.0000, -10.0000, 100.0000, 0.5000)");
  Cycle c = drill;
  c.kind = CycleKind::PeckDrill, c.peck = 3, c.peck_retract = 0.25, c.peck_clearance = 0.5;
  EXPECT_EQ(format_call(c),
            "PECK_DRILL_CYCLE(10.0000, 20.0000, 50.0000, 2.0000, -10.0000, 100.0000, 0.5000, "
            "3.0000, 0.2500, 0.5000)");
  c = drill;
  c.kind = CycleKind::Tap, c.pitch = 1.25, c.spindle_speed = 400;
  EXPECT_EQ(format_call(c),
            "TAP_CYCLE(10.0000, 20.0000, 50.0000, 2.0000, -10.0000, 100.0000, 0.5000, 1.2500, "
            "400.0000, RIGHT_HAND)");
  c.left_hand = true;
  EXPECT_EQ(format_call(c),
            "TAP_CYCLE(10.0000, 20.0000, 50.0000, 2.0000, -10.0000, 100.0000, 0.5000, 1.2500, "
            "400.0000, LEFT_HAND)");
  c = drill;
  c.kind = CycleKind::Bore;
  EXPECT_EQ(format_call(c),
            "BORE_CYCLE(10.0000, 20.0000, 50.0000, 2.0000, -10.0000, 100.0000, 0.5000, FEED_OUT)");
  c.spindle_stop = true;
  EXPECT_EQ(format_call(c),
            "BORE_CYCLE(10.0000, 20.0000, 50.0000, 2.0000, -10.0000, 100.0000, 0.5000, "
            "SPINDLE_STOP)");
  c = drill;
  c.kind = CycleKind::Ream, c.tool_axis = Direction{0, 0, 1};
  EXPECT_EQ(format_call(c),
            "REAM_CYCLE(10.0000, 20.0000, 50.0000, 2.0000, -10.0000, 100.0000, 0.5000, 0.0000, "
            "0.0000, 1.0000)");
}

TEST(CanonTrace, Numbers) {
  EXPECT_EQ(number(0), "0.0000");
  EXPECT_EQ(number(-0.0), "0.0000");
  EXPECT_EQ(number(-0.00004), "0.0000");   // rounds to zero: no sign
  EXPECT_EQ(number(-0.00005), "-0.0001");  // -0.00005 is slightly beyond -0.00005 in binary
  EXPECT_EQ(number(0.00005), "0.0001");
  // Rounding is of the exact binary value, as printf rounds: 2.00025 is 2.0002499999... and
  // 0.00015 is 0.000149999..., while 1.00005 is 1.0000500000001...
  EXPECT_EQ(number(2.00025), "2.0002");
  EXPECT_EQ(number(0.00015), "0.0001");
  EXPECT_EQ(number(1.00005), "1.0001");
  EXPECT_EQ(number(2.5), "2.5000");
  EXPECT_EQ(number(-13.5), "-13.5000");
  EXPECT_EQ(number(123456789.123456), "123456789.1235");
  EXPECT_EQ(number(0.99999), "1.0000");
  EXPECT_EQ(number(0.99995), "1.0000");
  EXPECT_EQ(number(1e20), "100000000000000000000.0000");
  EXPECT_EQ(number(std::numeric_limits<double>::max()).size(), 309u + 5u);
  char expected[64];
  for (const double v : {3.14159265, -2.71828, 1234.56785, 0.1, -999.99995}) {
    std::snprintf(expected, sizeof expected, "%.4f", v);
    EXPECT_EQ(number(v), expected) << v;
  }
}

TEST(CanonTrace, Strings) {
  EXPECT_EQ(quoted("plain"), "\"plain\"");
  EXPECT_EQ(quoted(""), "\"\"");
  EXPECT_EQ(quoted("say \"hi\" \\ now"), "\"say \\\"hi\\\" \\\\ now\"");
  EXPECT_EQ(quoted("a\nb\rc\td"), "\"a\\nb\\rc\\td\"");
  EXPECT_EQ(quoted(std::string_view("nul\0bell\x07"
                                    "del\x7f",
                                    13)),
            "\"nul\\x00bell\\x07del\\x7F\"");
  EXPECT_EQ(quoted("Fr\xC3\xA4sen \xE2\x8C\x80"), "\"Fr\xC3\xA4sen \xE2\x8C\x80\"");  // UTF-8 kept
  EXPECT_EQ(quoted("bad \xC3 \xFF \xED\xA0\x80"), "\"bad \\xC3 \\xFF \\xED\\xA0\\x80\"");
  EXPECT_EQ(format_call(Comment{"line1\nline2 \"x\""}), "COMMENT(\"line1\\nline2 \\\"x\\\"\")");
}

TEST(CanonTrace, LinesAreNumberedLikeRs274) {
  const std::vector<Call> calls = {SetFeedRate{100}, StraightFeed{{91.9, -13.5, 2.5, {}, {}}}};
  EXPECT_EQ(trace(calls),
            "    1 SET_FEED_RATE(100.0000)\n"
            "    2 STRAIGHT_FEED(91.9000, -13.5000, 2.5000)\n");
  std::string out;
  TraceWriter writer([&out](std::string_view line) { out += line; }, 99999);
  writer.write(calls);
  EXPECT_EQ(out,
            "99999 SET_FEED_RATE(100.0000)\n"
            "100000 STRAIGHT_FEED(91.9000, -13.5000, 2.5000)\n");
  EXPECT_EQ(writer.next_line(), 100001u);
}

TEST(CanonTrace, EveryLineOfTheSampleIsOneLine) {
  const auto calls = test::sample_program();
  const std::string text = trace(calls);
  std::size_t lines = 0;
  for (const char ch : text) lines += ch == '\n';
  EXPECT_EQ(lines, calls.size());
  for (const auto& call : calls) EXPECT_EQ(format_call(call).rfind(name(call), 0), 0u);
}

}  // namespace
}  // namespace ncpost::canon
