// engine/ap238 on small AIM programs written here: what it reads, and every way it refuses or
// reports. Each program is the same skeleton (one workingstep, one milling operation, one tool)
// with the part under test spliced in.

#include "ncpost/ap238/ap238.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "ncpost/canon/trace.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"

namespace ncpost::ap238 {
namespace {

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

// Units, contexts, the project with its main workplan, one workingstep with its operation
// (#48), tool (#56 '3'), technology (#73: 600 mm/min, 1000 rev/min counter-clockwise), then
// `rest` (toolpaths of #48 and whatever else a test needs).
std::string program(const std::string& rest, const std::string& schema = "INTEGRATED_CNC_SCHEMA") {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
         "FILE_NAME('t','',(''),(''),'','','');\nFILE_SCHEMA(('" +
         schema +
         "'));\nENDSEC;\nDATA;\n"
         "#1=REPRESENTATION_CONTEXT('','none');\n"
         "#2=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n"
         "#3=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n"
         "#5=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#2,#3))"
         "REPRESENTATION_CONTEXT('','3D'));\n"
         "#6=(NAMED_UNIT(*)SI_UNIT($,.SECOND.)TIME_UNIT());\n"
         "#7=TIME_MEASURE_WITH_UNIT(TIME_MEASURE(60.),#6);\n"
         "#8=DIMENSIONAL_EXPONENTS(0.,0.,1.,0.,0.,0.,0.);\n"
         "#9=(CONVERSION_BASED_UNIT('minute',#7)NAMED_UNIT(#8)TIME_UNIT());\n"
         "#10=DIMENSIONAL_EXPONENTS(0.,0.,0.,0.,0.,0.,0.);\n"
         "#11=CONTEXT_DEPENDENT_UNIT(#10,'revolution');\n"
         "#12=DERIVED_UNIT_ELEMENT(#11,1.);\n#13=DERIVED_UNIT_ELEMENT(#9,-1.);\n"
         "#14=DERIVED_UNIT((#12,#13));\n#15=DERIVED_UNIT_ELEMENT(#2,1.);\n"
         "#16=DERIVED_UNIT((#15,#13));\n"
         "#19=APPLICATION_CONTEXT('cnc');\n#21=PRODUCT_CONTEXT('',#19,'');\n"
         "#22=PRODUCT_DEFINITION_CONTEXT('',#19,'');\n"
         "#23=MACHINING_PROJECT('P','P',$,(#21));\n"
         "#24=PRODUCT_DEFINITION_FORMATION('','',#23);\n"
         "#25=PRODUCT_DEFINITION('','',#24,#22);\n"
         "#26=MACHINING_WORKPLAN('MAIN','','','');\n"
         "#27=PRODUCT_DEFINITION_PROCESS('machining','',#26,'');\n"
         "#28=PROCESS_PRODUCT_ASSOCIATION('','',#25,#27);\n"
         "#46=MACHINING_WORKINGSTEP('WS','machining','','');\n"
         "#47=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#26,#46,1.);\n"
         "#48=MILLING_TYPE_OPERATION('OP','','','');\n"
         "#49=MACHINING_OPERATION_RELATIONSHIP('','',#46,#48);\n"
         "#55=ACTION_RESOURCE_TYPE('cutting tool');\n"
         "#56=MACHINING_TOOL('3','',(#48),#55);\n"
         "#73=MACHINING_TECHNOLOGY('','milling','','');\n"
         "#74=MEASURE_REPRESENTATION_ITEM('rotational speed',NUMERIC_MEASURE(1000.),#14);\n"
         "#75=MACHINING_SPINDLE_SPEED_REPRESENTATION('spindle speed',(#74),#1);\n"
         "#76=ACTION_PROPERTY('spindle','',#73);\n"
         "#77=ACTION_PROPERTY_REPRESENTATION('','',#76,#75);\n"
         "#78=MEASURE_REPRESENTATION_ITEM('feed speed',NUMERIC_MEASURE(600.),#16);\n"
         "#79=MACHINING_FEED_SPEED_REPRESENTATION('feed speed',(#78),#1);\n"
         "#80=ACTION_PROPERTY('feedrate','',#73);\n"
         "#81=ACTION_PROPERTY_REPRESENTATION('','',#80,#79);\n"
         "#82=MACHINING_TECHNOLOGY_RELATIONSHIP('','',#48,#73);\n" +
         rest + "ENDSEC;\nEND-ISO-10303-21;\n";
}

// A cutter-location toolpath `id` of #48 at `position` whose basic curve is a polyline from
// `from` to `to` (both "x,y,z").
std::string polyline_path(int id, int position, const std::string& from, const std::string& to) {
  const auto n = [&](int k) { return "#" + std::to_string(id + k); };
  return n(0) + "=MACHINING_TOOLPATH('PATH " + std::to_string(id) +
         "','cutter location trajectory','','');\n" + n(1) +
         "=MACHINING_TOOLPATH_SEQUENCE_RELATIONSHIP('','',#48," + n(0) + "," +
         std::to_string(position) + ".);\n" + n(2) + "=CARTESIAN_POINT('',(" + from + "));\n" +
         n(3) + "=CARTESIAN_POINT('',(" + to + "));\n" + n(4) + "=POLYLINE('',(" + n(2) + "," +
         n(3) + "));\n" + n(5) + "=REPRESENTATION('',(" + n(4) + "),#5);\n" + n(6) +
         "=ACTION_PROPERTY('basic curve',''," + n(0) + ");\n" + n(7) +
         "=ACTION_PROPERTY_REPRESENTATION('',''," + n(6) + "," + n(5) + ");\n";
}

// A toolpath `id` of #48 with a descriptive property `name` = `value` and nothing else.
std::string described_path(int id, int position, const std::string& name,
                           const std::string& value) {
  const auto n = [&](int k) { return "#" + std::to_string(id + k); };
  return n(0) + "=MACHINING_TOOLPATH('PATH " + std::to_string(id) +
         "','cutter location trajectory','','');\n" + n(1) +
         "=MACHINING_TOOLPATH_SEQUENCE_RELATIONSHIP('','',#48," + n(0) + "," +
         std::to_string(position) + ".);\n" + n(2) + "=DESCRIPTIVE_REPRESENTATION_ITEM('" + name +
         "','" + value + "');\n" + n(3) + "=REPRESENTATION('',(" + n(2) + "),#1);\n" + n(4) +
         "=ACTION_PROPERTY('" + name + "',''," + n(0) + ");\n" + n(5) +
         "=ACTION_PROPERTY_REPRESENTATION('',''," + n(4) + "," + n(3) + ");\n";
}

struct Outcome {
  std::string trace;
  std::vector<diag::Diagnostic> diagnostics;
  std::size_t calls = 0;
  [[nodiscard]] std::vector<std::string> codes() const {
    std::vector<std::string> out;
    for (const auto& d : diagnostics) out.emplace_back(d.code_id());
    return out;
  }
  [[nodiscard]] std::string all() const {
    std::string out;
    for (const auto& d : diagnostics) out += diag::format(d, "t") + "\n";
    return out;
  }
  [[nodiscard]] bool has(const std::string& call) const {
    return trace.find(" " + call + "\n") != std::string::npos;
  }
};

Outcome run(const std::string& text, const stepnc::InterpretOptions& options = {}) {
  auto read = p21::read(text);
  EXPECT_TRUE(read.ok());
  const auto selection = registry().select_for(read.model);
  EXPECT_NE(selection.source, nullptr);
  const stepnc::AttributeReader attributes(read.model, *selection.set());
  Outcome r;
  canon::TraceWriter writer([&](std::string_view piece) { r.trace += piece; });
  const auto result = ap238::interpret(read.model, attributes, writer, options);
  r.diagnostics = result.diagnostics;
  r.calls = result.calls;
  return r;
}

// ---------------------------------------------------------------------------------------------

TEST(Ap238, IsAimByFileSchema) {
  const auto aim = [](const std::string& schema) {
    return is_aim(p21::read(program("", schema)).model);
  };
  EXPECT_TRUE(aim("INTEGRATED_CNC_SCHEMA"));
  EXPECT_TRUE(aim("integrated_cnc_schema"));
  EXPECT_TRUE(aim("INTEGRATED_CNC_SCHEMA { 1 0 10303 238 1 0 1 1 }"));
  EXPECT_TRUE(aim("OTHER','INTEGRATED_CNC_SCHEMA"));
  EXPECT_FALSE(aim("MACHINING_SCHEMA','MILLING_SCHEMA"));
  EXPECT_FALSE(aim("INTEGRATED_CNC_SCHEMA_X"));
}

TEST(Ap238, PolylinesInSequenceOrder) {
  // Written out of order: the sequence positions decide.
  const Outcome r = run(program(polyline_path(200, 2, "1.,0.,0.", "2.,0.,0.") +
                                polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.")));
  EXPECT_TRUE(r.diagnostics.empty()) << r.all();
  EXPECT_TRUE(r.has("SET_FEED_RATE(600.0000)"));
  EXPECT_TRUE(r.has("SET_SPINDLE_SPEED(1000.0000)"));
  EXPECT_TRUE(r.has("START_SPINDLE_COUNTERCLOCKWISE()"));
  EXPECT_TRUE(r.has("CHANGE_TOOL(3)"));
  const auto first = r.trace.find("STRAIGHT_FEED(1.0000, 0.0000, 0.0000)");
  const auto second = r.trace.find("STRAIGHT_FEED(2.0000, 0.0000, 0.0000)");
  ASSERT_NE(first, std::string::npos) << r.trace;
  ASSERT_NE(second, std::string::npos) << r.trace;
  EXPECT_LT(first, second);
  EXPECT_TRUE(r.has("PROGRAM_END()"));
}

TEST(Ap238, RepeatedSequencePositionsRunInFileOrder) {
  const Outcome r = run(program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.") +
                                polyline_path(200, 1, "1.,0.,0.", "2.,0.,0.")));
  EXPECT_EQ(r.codes(), (std::vector<std::string>{"AP238-012"})) << r.all();
  EXPECT_LT(r.trace.find("STRAIGHT_FEED(1.0000"), r.trace.find("STRAIGHT_FEED(2.0000"));
}

TEST(Ap238, AToolpathWithoutGeometryIsNamedNeverSkipped) {
  const std::string text = program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.") +
                                   described_path(200, 2, "trajectory type", "trajectory path") +
                                   polyline_path(300, 3, "1.,0.,0.", "2.,0.,0."));
  const Outcome trace = run(text);
  ASSERT_EQ(trace.codes(), (std::vector<std::string>{"AP238-006"})) << trace.all();
  EXPECT_NE(trace.diagnostics[0].message.find("#200 (MACHINING_TOOLPATH) 'PATH 200'"),
            std::string::npos)
      << trace.diagnostics[0].message;
  EXPECT_TRUE(trace.has("PROGRAM_END()"));  // a trace goes on, to show everything
  // A post stops at the error, without the end sequence: nothing after the gap is posted.
  stepnc::InterpretOptions post;
  post.stop_at_first_error = true;
  const Outcome posted = run(text, post);
  EXPECT_FALSE(posted.has("PROGRAM_END()"));
  EXPECT_FALSE(posted.has("STRAIGHT_FEED(2.0000, 0.0000, 0.0000)"));
}

TEST(Ap238, UnknownPropertiesAreListedOncePerKindWithACount) {
  const Outcome r = run(program(described_path(100, 1, "acme spindle warmup", "on") +
                                polyline_path(110, 2, "0.,0.,5.", "1.,0.,0.") +
                                "#120=ACTION_PROPERTY('acme spindle warmup','',#110);\n"
                                "#121=ACTION_PROPERTY_REPRESENTATION('','',#120,#103);\n" +
                                "#130=ACTION_PROPERTY('acme note','',#48);\n"
                                "#131=ACTION_PROPERTY_REPRESENTATION('','',#130,#103);\n"));
  // #100 has no geometry (AP238-006); the two unknown kinds are listed once each, at the end.
  ASSERT_EQ(r.codes(), (std::vector<std::string>{"AP238-006", "AP238-009", "AP238-009"}))
      << r.all();
  // In the order of their first appearance in the file.
  EXPECT_NE(r.diagnostics[1].message.find("'acme spindle warmup' (2 on MACHINING_TOOLPATHs)"),
            std::string::npos)
      << r.diagnostics[1].message;
  EXPECT_NE(r.diagnostics[2].message.find("'acme note' (1 on MILLING_TYPE_OPERATION)"),
            std::string::npos)
      << r.diagnostics[2].message;
  EXPECT_TRUE(r.has("STRAIGHT_FEED(1.0000, 0.0000, 0.0000)"));
}

std::string circular(int id, int position, const std::string& json) {
  return described_path(id, position, "next-nc circular motion", json);
}

TEST(Ap238, NextNcHelixWithSeveralTurns) {
  // 2.25 turns clockwise about +Z, 1 mm down: rs274 counts 3 (two full turns, then the rest).
  const Outcome r = run(program(
      circular(100, 1,
               R"({"start":[5,0,0],"end":[0,-5,-1],"center":[0,0,0],"plane":"XY","clockwise":true,)"
               R"("sweepRadians":14.137166941154069,"axialRise":-1})")));
  EXPECT_TRUE(r.diagnostics.empty()) << r.all();
  EXPECT_TRUE(r.has("ARC_FEED(0.0000, -5.0000, 0.0000, 0.0000, -3, -1.0000)")) << r.trace;
}

TEST(Ap238, NextNcGeometryThatDisagreesWithItselfIsRefused) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"not json", "is not a JSON object"},
      {R"({"start":[5,0,0],"end":[0,5,0],"center":[0,0,0],"plane":"XY","clockwise":false})",
       "exactly the seven documented keys"},
      {R"({"start":[5,0,0],"end":[0,5,0],"center":[0,0,0],"plane":"XY","clockwise":false,)"
       R"("sweepRadians":3.141592653589793,"axialRise":0})",
       "does not end at its end point"},
      {R"({"start":[5,0,0],"end":[0,6,0],"center":[0,0,0],"plane":"XY","clockwise":false,)"
       R"("sweepRadians":1.5707963267948966,"axialRise":0})",
       "from its axis"},
      {R"({"start":[5,0,0],"end":[0,5,0],"center":[0,0,0],"plane":"UV","clockwise":false,)"
       R"("sweepRadians":1.5707963267948966,"axialRise":0})",
       "names no plane"},
      {R"({"start":[5,0,0],"end":[0,5,2],"center":[0,0,0],"plane":"XY","clockwise":false,)"
       R"("sweepRadians":1.5707963267948966,"axialRise":1})",
       "axial rise"},
      {std::string(100, '[') + std::string(100, ']'), "flat JSON object"},
  };
  for (const auto& [json, why] : cases) {
    SCOPED_TRACE(json);
    const Outcome r = run(program(circular(100, 1, json)));
    ASSERT_EQ(r.codes(), (std::vector<std::string>{"AP238-013"})) << r.all();
    EXPECT_NE(r.diagnostics[0].message.find(why), std::string::npos) << r.diagnostics[0].message;
    EXPECT_NE(r.diagnostics[0].message.find("#100 (MACHINING_TOOLPATH)"), std::string::npos);
  }
}

TEST(Ap238, RapidByTrajectoryTypeAndBySpeedProfile) {
  const Outcome r = run(program(
      polyline_path(100, 1, "0.,0.,5.", "0.,0.,1.") +
      "#110=DESCRIPTIVE_REPRESENTATION_ITEM('trajectory type','non-contact');\n"
      "#111=REPRESENTATION('',(#110),#1);\n#112=ACTION_PROPERTY('trajectory type','',#100);\n"
      "#113=ACTION_PROPERTY_REPRESENTATION('','',#112,#111);\n" +
      polyline_path(200, 2, "0.,0.,1.", "0.,0.,0.") +
      polyline_path(300, 3, "0.,0.,0.", "0.,0.,2.") +
      "#310=DESCRIPTIVE_REPRESENTATION_ITEM('','rapid');\n"
      "#311=MACHINING_TOOLPATH_SPEED_PROFILE_REPRESENTATION('',(#310),#1);\n"
      "#312=ACTION_PROPERTY('speed profile','',#300);\n"
      "#313=ACTION_PROPERTY_REPRESENTATION('','',#312,#311);\n"));
  EXPECT_TRUE(r.diagnostics.empty()) << r.all();
  EXPECT_TRUE(r.has("STRAIGHT_TRAVERSE(0.0000, 0.0000, 1.0000)")) << r.trace;
  EXPECT_TRUE(r.has("STRAIGHT_FEED(0.0000, 0.0000, 0.0000)")) << r.trace;
  EXPECT_TRUE(r.has("STRAIGHT_TRAVERSE(0.0000, 0.0000, 2.0000)")) << r.trace;
}

TEST(Ap238, FeedFormsOtherThanFeedSpeedAreNamed) {
  std::string text = program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0."));
  const std::string from = "MACHINING_FEED_SPEED_REPRESENTATION('feed speed'";
  text.replace(text.find(from), from.size(),
               "MACHINING_FEED_SPEED_REPRESENTATION('feed per tooth'");
  const Outcome r = run(text);
  ASSERT_EQ(r.codes(), (std::vector<std::string>{"AP238-007"})) << r.all();
  EXPECT_NE(r.diagnostics[0].message.find("'feed per tooth'"), std::string::npos);
}

TEST(Ap238, AFeedInAnUnitThatIsNoSpeedIsABadValue) {
  std::string text = program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0."));
  const std::string from = "NUMERIC_MEASURE(600.),#16)";
  text.replace(text.find(from), from.size(), "NUMERIC_MEASURE(600.),#14)");  // rev/min
  const Outcome r = run(text);
  EXPECT_EQ(r.codes(), (std::vector<std::string>{"AP238-008"})) << r.all();
}

// The ap238 fuzz target's finding: a power of 1E300 was cast to int (undefined behaviour).
// Such a unit is no speed, whatever the sign, and so is a fractional power.
TEST(Ap238, AFeedUnitWithAHugeOrFractionalPowerIsABadValue) {
  for (const char* power : {"-1.E300", "1.E300", "-1.5", "-17."}) {
    std::string text = program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0."));
    const std::string from = "#13=DERIVED_UNIT_ELEMENT(#9,-1.);";
    text.replace(text.find(from), from.size(),
                 std::string("#13=DERIVED_UNIT_ELEMENT(#9,") + power + ");");
    const Outcome r = run(text);
    EXPECT_EQ(r.codes(), (std::vector<std::string>{"AP238-008", "AP238-008"})) << power << "\n"
                                                                               << r.all();
  }
}

// Derived units nested six deep, each raised to the 16th (16^6 seconds), then 200 elements of
// that to the 16th in one unit: 200 * 2^28 is past an int (the review found it after the fix
// above). The exponents saturate instead, and the unit is no speed.
TEST(Ap238, NestedPowersOfDerivedUnitsSaturate) {
  std::string units;
  std::string inner = "#6";
  for (int level = 0; level < 6; ++level) {
    const std::string element = "#" + std::to_string(900 + 2 * level);
    const std::string unit = "#" + std::to_string(901 + 2 * level);
    units += element + "=DERIVED_UNIT_ELEMENT(" + inner + ",16.);\n" + unit + "=DERIVED_UNIT((" +
             element + "));\n";
    inner = unit;
  }
  std::string elements;
  for (int k = 0; k < 200; ++k) {
    const std::string element = "#" + std::to_string(1000 + k);
    units += element + "=DERIVED_UNIT_ELEMENT(" + inner + ",16.);\n";
    elements += (k == 0 ? "" : ",") + element;
  }
  units += "#1300=DERIVED_UNIT((" + elements + "));\n";
  std::string text = program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.") + units);
  const std::string from = "#13=DERIVED_UNIT_ELEMENT(#9,-1.);";
  text.replace(text.find(from), from.size(), "#13=DERIVED_UNIT_ELEMENT(#1300,-1.);");
  const Outcome r = run(text);
  EXPECT_EQ(r.codes(), (std::vector<std::string>{"AP238-008", "AP238-008"})) << r.all();
}

TEST(Ap238, ConversionBasedUnitsThatLoopAreRefused) {
  // 'minute' defined through itself: the chain is cut at kMaxUnitDepth and the feed refused.
  std::string text = program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0."));
  const std::string from = "#7=TIME_MEASURE_WITH_UNIT(TIME_MEASURE(60.),#6);";
  text.replace(text.find(from), from.size(), "#7=TIME_MEASURE_WITH_UNIT(TIME_MEASURE(60.),#9);");
  const Outcome r = run(text);
  EXPECT_EQ(r.codes(), (std::vector<std::string>{"AP238-008", "AP238-008"})) << r.all();
}

TEST(Ap238, TurningTechnologyIsRefusedBeforeAnyCall) {
  std::string text = program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0."));
  const std::string from = "#73=MACHINING_TECHNOLOGY('','milling','','');";
  text.replace(text.find(from), from.size(), "#73=MACHINING_TECHNOLOGY('','turning','','');");
  const Outcome r = run(text);
  ASSERT_EQ(r.codes(), (std::vector<std::string>{"AP238-005"})) << r.all();
  EXPECT_NE(r.diagnostics[0].message.find("turning"), std::string::npos);
  EXPECT_EQ(r.calls, 0u);
}

// `text` with `from` (which must be there) replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(Ap238, NoProjectAndNoWorkplan) {
  const Outcome none = run(replaced(program(""), "MACHINING_PROJECT('P'", "PRODUCT('P'"));
  EXPECT_EQ(none.codes(), (std::vector<std::string>{"AP238-001"})) << none.all();
  // The project's process chooses a workingstep, not a workplan.
  const Outcome orphan =
      run(replaced(program(""), "PRODUCT_DEFINITION_PROCESS('machining','',#26,'')",
                   "PRODUCT_DEFINITION_PROCESS('machining','',#46,'')"));
  EXPECT_EQ(orphan.codes(), (std::vector<std::string>{"AP238-003"})) << orphan.all();
  EXPECT_EQ(orphan.calls, 0u);
}

TEST(Ap238, AWorkplanThatContainsItselfAndNestingLimits) {
  const Outcome cycle =
      run(program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.") +
                  "#90=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#26,#26,2.);\n"));
  EXPECT_EQ(cycle.codes(), (std::vector<std::string>{"STEPNC-005"})) << cycle.all();
  stepnc::InterpretOptions shallow;
  shallow.max_nesting = 1;
  const Outcome deep =
      run(program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.") +
                  "#90=MACHINING_WORKPLAN('INNER','','','');\n"
                  "#91=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#26,#90,2.);\n"
                  "#92=MACHINING_WORKPLAN('INNERMOST','','','');\n"
                  "#93=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#90,#92,1.);\n"),
          shallow);
  ASSERT_EQ(deep.codes(), (std::vector<std::string>{"STEPNC-008"})) << deep.all();
  EXPECT_NE(deep.diagnostics[0].message.find("#92"), std::string::npos);
}

TEST(Ap238, ErrorsStopAtMaxErrors) {
  std::string paths;
  for (int i = 0; i < 30; ++i)
    paths += described_path(1000 + 10 * i, i + 1, "trajectory type", "trajectory path");
  stepnc::InterpretOptions options;
  options.max_errors = 5;
  const Outcome r = run(program(paths), options);
  EXPECT_EQ(r.codes(), (std::vector<std::string>{"AP238-006", "AP238-006", "AP238-006", "AP238-006",
                                                 "AP238-006", "AP238-011"}))
      << r.all();
  EXPECT_FALSE(r.has("PROGRAM_END()"));
}

TEST(Ap238, ACancelledJobStops) {
  std::atomic<bool> cancel{true};
  stepnc::InterpretOptions options;
  options.cancel = &cancel;
  const Outcome r = run(program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.")), options);
  EXPECT_FALSE(r.has("STRAIGHT_FEED(1.0000, 0.0000, 0.0000)"));
  EXPECT_FALSE(r.has("PROGRAM_END()"));
}

TEST(Ap238, AToolTableNamesTheToolOrTheToolIsAnError) {
  stepnc::InterpretOptions options;
  std::vector<diag::Diagnostic> table_diagnostics;
  options.tools = stepnc::read_tool_table("1 '3' 55.5 10\n", table_diagnostics);
  const Outcome found = run(program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.")), options);
  EXPECT_TRUE(found.has("CHANGE_TOOL(1)")) << found.trace;
  EXPECT_TRUE(found.has("USE_TOOL_LENGTH_OFFSET(55.5000)"));
  options.tools = stepnc::read_tool_table("1 'OTHER' 55.5 10\n", table_diagnostics);
  const Outcome missing = run(program(polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.")), options);
  EXPECT_EQ(missing.codes(), (std::vector<std::string>{"STEPNC-014"})) << missing.all();
}

TEST(Ap238, InspectListsToolData) {
  const std::string text = program(
      polyline_path(100, 1, "0.,0.,5.", "1.,0.,0.") +
      "#60=RESOURCE_PROPERTY('tool body','',#56);\n"
      "#61=RESOURCE_PROPERTY_REPRESENTATION('','',#60,#62);\n"
      "#62=MACHINING_TOOL_BODY_REPRESENTATION('bullnose endmill',(#63),#1);\n"
      "#63=DESCRIPTIVE_REPRESENTATION_ITEM('hand of cut','right');\n"
      "#64=REPRESENTATION_RELATIONSHIP('','',#62,#65);\n"
      "#65=MACHINING_TOOL_DIMENSION_REPRESENTATION('milling',(#66,#67),#1);\n"
      "#66=MEASURE_REPRESENTATION_ITEM('diameter',LENGTH_MEASURE(12.),#2);\n"
      "#67=MEASURE_REPRESENTATION_ITEM('edge radius',LENGTH_MEASURE(1.5),#2);\n"
      "#68=RESOURCE_PROPERTY('overall assembly length','',#56);\n"
      "#69=RESOURCE_PROPERTY_REPRESENTATION('','',#68,#70);\n"
      "#70=REPRESENTATION('',(#71),#1);\n"
      "#71=MEASURE_REPRESENTATION_ITEM('overall assembly length',LENGTH_MEASURE(90.),#2);\n");
  const auto read = p21::read(text);
  ASSERT_TRUE(read.ok());
  const auto info = ap238::inspect(read.model, registry().builtin_aim().set());
  EXPECT_TRUE(info.diagnostics.empty());
  ASSERT_EQ(info.tools.size(), 1u);
  const auto& tool = info.tools[0];
  EXPECT_EQ(tool.number, 3);
  EXPECT_EQ(tool.body, "bullnose endmill");
  EXPECT_EQ(tool.diameter, 12.0);
  EXPECT_EQ(tool.corner_radius, 1.5);
  EXPECT_EQ(tool.length, 90.0);
  EXPECT_EQ(tool.used_by, (std::vector<std::uint64_t>{46}));
  // The trace loads the same tool with its length.
  EXPECT_TRUE(run(text).has("USE_TOOL_LENGTH_OFFSET(90.0000)"));
}

}  // namespace
}  // namespace ncpost::ap238
