// `inspect` (program-information extraction): golden JSON for real and own programs, and the
// program-structure cases on small programs written here.

#include <gtest/gtest.h>

#include <fstream>

#include "corpus.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/pipeline/jobs.hpp"
#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::stepnc {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// The built-in schema only, as `ncpost inspect` without --schemas.
const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry instance;
  return instance;
}

// The typed result, its JSON form (as `ncpost inspect` writes it, without diagnostics) and the
// structure diagnostics.
struct Inspected {
  ProgramInfo typed;
  ordered_json json;
  std::vector<diag::Diagnostic> diagnostics;
};

Inspected inspected(ProgramInfo info) {
  Inspected out;
  out.json = pipeline::program_info_json(info);
  out.diagnostics = info.diagnostics;
  out.typed = std::move(info);
  return out;
}

Inspected inspect_text(std::string text) {
  p21::ReadResult r = p21::read(std::move(text));
  EXPECT_TRUE(r.ok());
  return inspected(inspect(r.model, registry()));
}

std::vector<std::string> codes(const std::vector<diag::Diagnostic>& diagnostics) {
  std::vector<std::string> out;
  for (const auto& d : diagnostics) out.emplace_back(d.code_id());
  return out;
}

// Compares with tests/golden/inspect/<name>.json. NCPOST_UPDATE_GOLDEN=1 rewrites the file
// instead; review the diff before committing it.
void expect_golden(const ordered_json& actual, const std::string& name) {
  const fs::path golden = test::source_dir() / "tests/golden/inspect" / (name + ".json");
  if (const char* update = std::getenv("NCPOST_UPDATE_GOLDEN");
      update && std::string(update) == "1") {
    std::ofstream(golden) << actual.dump(2) << '\n';
    return;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden;
  const ordered_json expected = ordered_json::parse(test::read_file(golden));
  EXPECT_EQ(actual, expected) << "actual:\n" << actual.dump(2);
}

std::vector<std::uint64_t> element_ids(const ordered_json& workplan) {
  std::vector<std::uint64_t> ids;
  for (const auto& e : workplan["elements"]) ids.push_back(e["id"].get<std::uint64_t>());
  return ids;
}

TEST(InspectCorpus, NistExample1Tree) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Inspected info = inspect_text(test::read_file(corpus / "p21/nist_toolkit_ex1.stp"));
  EXPECT_TRUE(info.diagnostics.empty());
  const auto& project = info.json["project"];
  EXPECT_EQ(project["name"], "EXECUTE EXAMPLE1");
  const auto& main = project["main_workplan"];
  EXPECT_EQ(main["name"], "MAIN WORKPLAN");
  EXPECT_EQ(element_ids(main), (std::vector<std::uint64_t>{10, 11, 12, 13, 14}));
  const auto& drill = main["elements"][1];
  EXPECT_EQ(drill["name"], "WS DRILL HOLE1");
  EXPECT_EQ(drill["feature"]["type"], "ROUND_HOLE");
  EXPECT_EQ(drill["operation"]["type"], "DRILLING");
  EXPECT_EQ(drill["tool"]["name"], "SPIRAL_DRILL_20MM");
  EXPECT_EQ(info.json["tools"].size(), 3u);
  EXPECT_EQ(info.json["statistics"]["workingsteps"], 5);
  EXPECT_EQ(info.json["statistics"]["by_type"]["CARTESIAN_POINT"], 13);
  EXPECT_EQ(info.json["header"]["author"], (ordered_json{"YONG TAK HYUN", "JOCHEN WOLF"}));
  expect_golden(info.json, "nist_toolkit_ex1");
}

TEST(InspectCorpus, NistExample1ExplicitToolpaths) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Inspected info = inspect_text(test::read_file(corpus / "p21/nist_toolkit_ex1E.stp"));
  EXPECT_TRUE(info.diagnostics.empty());
  expect_golden(info.json, "nist_toolkit_ex1E");
}

TEST(InspectCorpus, Ap238AimFileIsNamedAsSuch) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  p21::ReadResult r = p21::read(test::read_file(corpus / "p21/efrainrodriguez_exp2.stpnc"));
  const Inspected info = inspected(inspect(r.model, registry()));
  // No schema for INTEGRATED_CNC_SCHEMA among the built-in ones: the built-in is used instead.
  EXPECT_EQ(codes(info.diagnostics),
            (std::vector<std::string>{"EXP-050", "EXP-052", "STEPNC-006"}));
  EXPECT_EQ(info.diagnostics[0].message,
            "no schema for FILE_SCHEMA 'INTEGRATED_CNC_SCHEMA'; known: machining_schema, "
            "milling_schema");
  EXPECT_EQ(info.diagnostics[1].severity, diag::Severity::Note);
  EXPECT_TRUE(info.json["project"].is_null());
  EXPECT_EQ(info.json["header"]["schemas"], (ordered_json{"INTEGRATED_CNC_SCHEMA"}));
}

// The attribute positions come from the schema: the corpus's combined ISO 14649 schema (NIST's,
// one SCHEMA with other entity names here and there) gives the same program information.
TEST(InspectCorpus, NistExample1WithTheCombinedSchema) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const express::ParseResult combined = express::parse_express(test::read_file(
      corpus / "express/michaloski_STEPNCpp_combined_schema_14649-10-11-12-111-121.exp"));
  ASSERT_TRUE(combined.ok());
  p21::ReadResult r = p21::read(test::read_file(corpus / "p21/nist_toolkit_ex1.stp"));
  const Inspected info = inspected(inspect(r.model, combined.schemas));
  EXPECT_TRUE(info.diagnostics.empty());
  expect_golden(info.json, "nist_toolkit_ex1");
}

TEST(InspectOwn, BracketExample) {
  const Inspected info = inspect_text(test::read_file(test::source_dir() / "examples/bracket.stp"));
  EXPECT_TRUE(info.diagnostics.empty());
  const auto& main = info.json["project"]["main_workplan"];
  EXPECT_EQ(element_ids(main), (std::vector<std::uint64_t>{20, 21, 22, 23, 24}));
  EXPECT_EQ(main["elements"][0]["text"], "Check that the blank is clamped at both ends");
  EXPECT_EQ(element_ids(main["elements"][2]), (std::vector<std::uint64_t>{25, 26}));
  expect_golden(info.json, "bracket");
}

std::string program(const std::string& data) {
  return "ISO-10303-21;HEADER;FILE_DESCRIPTION(('t'),'2;1');"
         "FILE_NAME('t','t',(''),(''),'','','');FILE_SCHEMA(('MACHINING_SCHEMA'));ENDSEC;DATA;\n" +
         data + "\nENDSEC;END-ISO-10303-21;";
}

TEST(InspectOwn, ControlStructures) {
  const Inspected info = inspect_text(
      program("#1=PROJECT('P',#2,(),$,$,$);"
              "#2=WORKPLAN('MAIN',(#3,#4,#5,#6,#7,#8),$,$,$);"
              "#3=IF_STATEMENT('IF',#20,#9,#10);"
              "#4=WHILE_STATEMENT('WHILE',#20,#11);"
              "#5=PARALLEL('PAR',(#9,#10));"
              "#6=NON_SEQUENTIAL('NONSEQ',(#9));"
              "#7=SELECTIVE('SEL',(#10));"
              "#8=LOAD_TOOL('LOAD',#30);"
              "#9=PROGRAM_STOP('STOP');#10=SET_MARK('MARK');#11=EXCHANGE_PALLET('PALLET');"
              "#20=COMPARISON_EQUAL(#21,#21);#21=NC_CONSTANT('C',1.);"
              "#30=MILLING_CUTTING_TOOL('T1',$,(),$,$,$);"));
  EXPECT_TRUE(info.diagnostics.empty());
  const auto& e = info.json["project"]["main_workplan"]["elements"];
  EXPECT_EQ(e[0]["true_branch"]["type"], "PROGRAM_STOP");
  EXPECT_EQ(e[0]["false_branch"]["type"], "SET_MARK");
  EXPECT_EQ(e[1]["body"]["type"], "EXCHANGE_PALLET");
  EXPECT_EQ(e[2]["branches"].size(), 2u);
  EXPECT_EQ(e[3]["elements"][0]["id"], 9);
  EXPECT_EQ(e[4]["elements"][0]["id"], 10);
  EXPECT_EQ(e[5]["tool"]["name"], "T1");
  EXPECT_EQ(info.json["tools"][0]["used_by"], (ordered_json{8}));
}

TEST(InspectOwn, WorkplanThatContainsItself) {
  const Inspected info =
      inspect_text(program("#1=PROJECT('P',#2,(),$,$,$);#2=WORKPLAN('MAIN',(#3),$,$,$);"
                           "#3=WORKPLAN('LOOP',(#2),$,$,$);"));
  ASSERT_EQ(info.diagnostics.size(), 1u);
  EXPECT_EQ(info.diagnostics[0].code_id(), "STEPNC-005");
  EXPECT_EQ(info.diagnostics[0].message, "#2 contains itself");
}

TEST(InspectOwn, DeepNestingIsBounded) {
  std::string data = "#1=PROJECT('P',#2,(),$,$,$);";
  const int depth = 5000;
  for (int i = 2; i < depth; ++i)
    data += "#" + std::to_string(i) + "=WORKPLAN('W',(#" + std::to_string(i + 1) + "),$,$,$);";
  data += "#" + std::to_string(depth) + "=PROGRAM_STOP('S');";
  const Inspected info = inspect_text(program(data));
  ASSERT_EQ(info.diagnostics.size(), 1u);
  EXPECT_EQ(info.diagnostics[0].code_id(), "STEPNC-008");
}

TEST(InspectOwn, MainWorkplanOfTheWrongType) {
  const Inspected info =
      inspect_text(program("#1=PROJECT('P',#2,(),$,$,$);#2=CARTESIAN_POINT('X',(0.,0.,0.));"));
  ASSERT_EQ(info.diagnostics.size(), 1u);
  EXPECT_EQ(info.diagnostics[0].code_id(), "STEPNC-003");
  EXPECT_NE(info.diagnostics[0].message.find("#1"), std::string::npos);
}

TEST(InspectOwn, UnknownExecutableIsReportedNotDropped) {
  const Inspected info = inspect_text(
      program("#1=PROJECT('P',#2,(),$,$,$);#2=WORKPLAN('MAIN',(#3),$,$,$);#3=MYSTERY('M');"));
  ASSERT_EQ(info.diagnostics.size(), 1u);
  EXPECT_EQ(info.diagnostics[0].code_id(), "STEPNC-007");
  EXPECT_EQ(info.json["project"]["main_workplan"]["elements"][0]["type"], "MYSTERY");
}

// Executables are whatever the schema makes a subtype of EXECUTABLE, not a list in the code:
// ISO 14649-10's touch probing and a schema of one's own.
TEST(InspectOwn, ExecutablesComeFromTheSchema) {
  const Inspected builtin = inspect_text(
      program("#1=PROJECT('P',#2,(),$,$,$);#2=WORKPLAN('MAIN',(#3),$,$,$);"
              "#3=TOOL_LENGTH_PROBING('PROBE',$,$,$,#4,0.,1.,#5);#4=NC_VARIABLE('V',0.);"
              "#5=MILLING_CUTTING_TOOL('T1',$,(),$,$,$);"));
  EXPECT_TRUE(builtin.diagnostics.empty());
  EXPECT_EQ(builtin.json["project"]["main_workplan"]["elements"][0]["name"], "PROBE");

  const express::ParseResult own = express::parse_express(
      "SCHEMA shop_floor;"
      "ENTITY project; its_id : STRING; main_workplan : workplan; END_ENTITY;"
      "ENTITY executable ABSTRACT SUPERTYPE; its_id : STRING; END_ENTITY;"
      "ENTITY workplan SUBTYPE OF (executable); its_elements : LIST [0:?] OF executable; "
      "END_ENTITY;"
      "ENTITY coolant_check SUBTYPE OF (executable); pressure : REAL; END_ENTITY;"
      "ENTITY note; its_id : STRING; END_ENTITY;"
      "END_SCHEMA;");
  ASSERT_TRUE(own.ok());
  p21::ReadResult r = p21::read(
      "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'2;1');FILE_NAME('','',(''),(''),'','','');"
      "FILE_SCHEMA(('SHOP_FLOOR'));ENDSEC;DATA;\n"
      "#1=PROJECT('P',#2);#2=WORKPLAN('MAIN',(#3,#4));#3=COOLANT_CHECK('CHECK',5.);\n"
      "#4=NOTE('N');\nENDSEC;END-ISO-10303-21;");
  ASSERT_TRUE(r.ok());
  const Inspected info = inspected(inspect(r.model, own.schemas));
  const auto& elements = info.json["project"]["main_workplan"]["elements"];
  EXPECT_EQ(elements[0]["name"], "CHECK");
  EXPECT_EQ(elements[1]["name"], "N");
  ASSERT_EQ(codes(info.diagnostics), std::vector<std::string>{"STEPNC-007"});
  EXPECT_EQ(info.diagnostics[0].line, 3u);
}

// A file that names a schema the registry does not have is read with the built-in schema, and
// the diagnostics say so.
TEST(InspectOwn, UnknownSchemaFallsBackToTheBuiltin) {
  std::string text = program("#1=PROJECT('P',#2,(),$,$,$);#2=WORKPLAN('MAIN',(),$,$,$);");
  text.replace(text.find("'MACHINING_SCHEMA'"), 18, "'SOMETHING_ELSE { 1 2 3 }'");
  const Inspected info = inspect_text(text);
  EXPECT_EQ(codes(info.diagnostics), (std::vector<std::string>{"EXP-050", "EXP-052"}));
  EXPECT_EQ(info.diagnostics[0].line, 1u);
  EXPECT_EQ(info.json["project"]["main_workplan"]["name"], "MAIN");
}

TEST(InspectOwn, NotAStepNcFile) {
  const Inspected info = inspect_text(program("#1=CARTESIAN_POINT('X',(0.,0.,0.));"));
  ASSERT_EQ(info.diagnostics.size(), 1u);
  EXPECT_EQ(info.diagnostics[0].code_id(), "STEPNC-001");
  EXPECT_EQ(info.json["statistics"]["instances"], 1);
}

TEST(InspectOwn, TextFormatShowsTheTree) {
  const Inspected info = inspect_text(test::read_file(test::source_dir() / "examples/bracket.stp"));
  const std::string text = format_text(info.typed);
  EXPECT_NE(text.find("project:     #1 'BRACKET'"), std::string::npos) << text;
  EXPECT_NE(text.find("      #25 MACHINING_WORKINGSTEP 'DRILL HOLE'"), std::string::npos) << text;
  EXPECT_LT(text.find("'DRILL HOLE'"), text.find("'REAM HOLE'"));
}

}  // namespace
}  // namespace ncpost::stepnc
