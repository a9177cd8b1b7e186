// validate(): a Model checked against an EXPRESS schema. One small program per check against
// the project's own test schema (data/validate.exp), then the STEPcode cases of the corpus and
// the NIST ISO 14649 programs against the built-in schema.

#include "ncpost/express/validate.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "corpus.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/parallel/pieces.hpp"
#include "test_support.hpp"

namespace ncpost::express {
namespace {

namespace fs = std::filesystem;
using Strings = std::vector<std::string>;

const SchemaSet& test_schema() {
  static const ParseResult parsed = parse_express(ncpost::test::read_file(
      ncpost::test::source_dir() / "tests/unit/express/data/schemas/validate.exp"));
  EXPECT_TRUE(parsed.diagnostics.empty()) << test::describe(parsed.diagnostics);
  return parsed.schemas;
}

// The header takes line 1, so the n-th line of `data` is line n + 1 of the file.
std::string program(const std::string& data, const std::string& schema = "VALIDATE_TEST") {
  return "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'2;1');FILE_NAME('','',(''),(''),'','','');"
         "FILE_SCHEMA(('" +
         schema + "'));ENDSEC;DATA;\n" + data + "\nENDSEC;END-ISO-10303-21;\n";
}

std::string join(const Strings& items) {
  std::string out;
  for (const auto& i : items) out += i + "\n";
  return out;
}

// "CODE@line:column message" per diagnostic.
Strings described(const std::vector<diag::Diagnostic>& diagnostics) {
  Strings out;
  for (const auto& d : diagnostics)
    out.push_back(std::string(d.code_id()) + "@" + std::to_string(d.line) + ":" +
                  std::to_string(d.column) + " " + d.message);
  return out;
}

// The check as asked, then again with `plan` (every type of the set learnt in advance), which
// must not change a word of what it says.
Strings validated(const p21::Model& model, const SchemaSet& set, const ValidateOptions& options,
                  const CheckPlan& plan) {
  const Strings learning = described(validate(model, set, options));
  ValidateOptions planned = options;
  planned.plan = &plan;
  EXPECT_EQ(join(described(validate(model, set, planned))), join(learning)) << "with a plan";
  return learning;
}

Strings run(const std::string& text, const SchemaSet& set, const ValidateOptions& options = {}) {
  p21::ReadResult read = p21::read(text);
  EXPECT_TRUE(read.ok()) << test::describe(read.diagnostics);
  const CheckPlan plan(set);
  return validated(read.model, set, options, plan);
}

Strings check(const std::string& data) {
  return run(program(data), test_schema());
}

// ---------------------------------------------------------------------------------------------
// A program that fits, with every construct of the schema.

const std::string kValid =
    "#1=POINT('p',(0.,1.,2));\n"  // an integer is a valid REAL
    "#2=CIRCLE('c',#1,5.);\n"
    "#3=SQUARE('s',#1,2.5);\n"
    "#4=DRAWING('d',(#2,#3),.CYAN.,.T.,.U.,3,LENGTH_MEASURE(2.));\n"
    "#5=DRAWING('e',(#2),$,.F.,.T.,0,LABEL('x'));\n"
    "#6=GRID(((1,$),(3,4)),(),\"0F\");\n"
    "#7=ORIGIN('o',*);\n"
    "#8=CIRCLE('c2',#7,POSITIVE_LENGTH_MEASURE(1.));\n"
    "#9=(ITEM('t')POINT((1.,2.))TAGGED(7));\n"
    "#10=(ITEM('u')ORIGIN()POINT(*));\n"
    "#11=MESH(2,(5,6));\n"
    "#12=CIRCLE('c3',#9,1.);\n";

TEST(express_validate, ValidProgramHasNoDiagnostics) {
  EXPECT_EQ(check(kValid), Strings{});
}

// ---------------------------------------------------------------------------------------------
// One check at a time.

TEST(express_validate, EntityNotInSchemaIsAWarningOncePerEntity) {
  EXPECT_EQ(check("#1=FROB(1);\n#2=FROB(2);\n#3=POINT('p',(0.));"),
            (Strings{"EXP-060@2:1 #1 FROB: entity FROB is not in the schema (2 instances, the "
                     "first here); its values are not checked"}));
}

TEST(express_validate, AbstractEntity) {
  EXPECT_EQ(check("#1=ITEM('i');"),
            (Strings{"EXP-059@2:1 #1 ITEM: item is ABSTRACT; only its subtypes (or a complex "
                     "instance) can be instantiated"}));
}

TEST(express_validate, ParameterCount) {
  EXPECT_EQ(check("#1=POINT('p',(0.),3);\n#2=POINT('q');"),
            (Strings{"EXP-061@2:1 #1 POINT has 3 parameters; the schema gives point 2 (name, "
                     "coordinates)",
                     "EXP-061@3:1 #2 POINT has 1 parameter; the schema gives point 2 (name, "
                     "coordinates)"}));
}

TEST(express_validate, OmittedRequiredAttribute) {
  EXPECT_EQ(check("#1=POINT($,(0.));\n#2=DRAWING('d',(#3),$,.T.,.T.,1,$);\n"
                  "#3=CIRCLE('c',#4,1.);#4=POINT('p',(0.));"),
            (Strings{"EXP-062@2:1 #1 POINT attribute 'name': '$' but the attribute is not "
                     "OPTIONAL"}));
}

TEST(express_validate, OmittedElementOfAnAggregate) {
  EXPECT_EQ(check("#1=POINT('p',(0.,$));\n#2=GRID((($,$),(1,$)),(),$);"),
            (Strings{"EXP-062@2:1 #1 POINT attribute 'coordinates' element 2: '$' but the "
                     "elements of LIST are not OPTIONAL"}));
}

TEST(express_validate, ValueOfTheWrongKind) {
  const Strings got = check(
      "#1=POINT(5,(0.));\n"                           // integer for a label (STRING)
      "#2=POINT('p',('x'));\n"                        // string for a REAL
      "#3=MESH(2.,(1,2));\n"                          // real for an INTEGER
      "#4=POINT('p',#1);\n"                           // reference for a LIST
      "#5=GRID(((1,2),(3,4)),(#1),$);\n"              // reference for a REAL element
      "#6=DRAWING('d',(#7),$,.T.,.T.,1,2.);\n"        // untyped value for a SELECT
      "#7=CIRCLE('c',#8,(1.));#8=POINT('p',(0.));");  // list for a REAL
  EXPECT_EQ(got,
            (Strings{
                "EXP-063@2:1 #1 POINT attribute 'name': expected label (STRING), found the "
                "integer 5",
                "EXP-063@3:1 #2 POINT attribute 'coordinates' element 1: expected length_measure "
                "(REAL), found the string 'x'",
                "EXP-063@4:1 #3 MESH attribute 'index_count': expected INTEGER, found the real 2.",
                "EXP-063@5:1 #4 POINT attribute 'coordinates': expected LIST [1:3] OF "
                "length_measure, found #1 (POINT)",
                "EXP-063@6:1 #5 GRID attribute 'weights' element 1: expected REAL, found #1 "
                "(POINT)",
                "EXP-063@7:1 #6 DRAWING attribute 'value': expected measure_value (SELECT), found "
                "the real 2. (a SELECT value that is not an entity is written as "
                "TYPE_NAME(value))",
                "EXP-063@8:1 #7 CIRCLE attribute 'radius': expected positive_length_measure "
                "(REAL), found a list of 1 element",
            }))
      << join(got);
}

TEST(express_validate, ReferenceToTheWrongEntity) {
  const Strings got = check(
      "#1=POINT('p',(0.));\n"
      "#2=CIRCLE('c',#1,1.);\n"
      "#3=CIRCLE('c',#2,1.);\n"                   // a circle where a point is declared
      "#4=DRAWING('d',(#2,#1),$,.T.,.T.,1,$);\n"  // a point in SET OF shape_select
      "#5=CIRCLE('c',#6,1.);\n"                   // a subtype (origin) is fine
      "#6=ORIGIN('o',*);\n"
      "#7=CIRCLE('c',#8,1.);\n"  // complex: one record is a point
      "#8=(ITEM('t')POINT((1.))TAGGED(1));\n"
      "#9=CIRCLE('c',#10,1.);\n"  // complex without a point record
      "#10=(ITEM('t')TAGGED(1));");
  EXPECT_EQ(got, (Strings{
                     "EXP-064@4:1 #3 CIRCLE attribute 'centre': #2 (CIRCLE) is not a point (nor a "
                     "subtype of it)",
                     "EXP-064@5:1 #4 DRAWING attribute 'shapes' element 2: #1 (POINT) is not a "
                     "member of SELECT shape_select (circle, square)",
                     "EXP-064@10:1 #9 CIRCLE attribute 'centre': #10 is not a point (nor a subtype "
                     "of it)",
                 }))
      << join(got);
}

TEST(express_validate, AggregateBounds) {
  const Strings got = check(
      "#1=POINT('p',());\n"                       // LIST [1:3]: too few
      "#2=POINT('p',(1.,2.,3.,4.));\n"            // too many
      "#3=GRID(((1,2)),(),$);\n"                  // ARRAY [1:2]: exactly 2
      "#4=GRID(((1,2),(3,4,5)),(1.,2.,3.),$);\n"  // inner ARRAY, LIST [0:2]
      "#5=DRAWING('d',(),$,.T.,.T.,1,$);\n"       // SET [1:?]
      "#6=MESH(3,(1,2));");                       // ARRAY [1:SELF\mesh.index_count]
  EXPECT_EQ(got, (Strings{
                     "EXP-065@2:1 #1 POINT attribute 'coordinates': LIST [1:3] OF length_measure "
                     "needs at least 1 element, found 0",
                     "EXP-065@3:1 #2 POINT attribute 'coordinates': LIST [1:3] OF length_measure "
                     "allows at most 3 elements, found 4",
                     "EXP-065@4:1 #3 GRID attribute 'cells': ARRAY [1:2] OF ARRAY [1:2] OF "
                     "OPTIONAL INTEGER holds exactly 2 elements, found 1",
                     "EXP-065@5:1 #4 GRID attribute 'cells' element 2: ARRAY [1:2] OF OPTIONAL "
                     "INTEGER holds exactly 2 elements, found 3",
                     "EXP-065@5:1 #4 GRID attribute 'weights': LIST [0:2] OF REAL allows at most 2 "
                     "elements, found 3",
                     "EXP-065@6:1 #5 DRAWING attribute 'shapes': SET [1:?] OF shape_select needs "
                     "at least 1 element, found 0",
                     "EXP-065@7:1 #6 MESH attribute 'indices': ARRAY [1:SELF\\mesh.index_count] "
                     "OF INTEGER (here [1:3]) holds exactly 3 elements, found 2",
                 }))
      << join(got);
}

TEST(express_validate, EnumerationValues) {
  const Strings got = check(
      "#1=CIRCLE('c',#2,1.);#2=POINT('p',(0.));\n"
      "#3=DRAWING('d',(#1),.PURPLE.,.T.,.T.,1,$);\n"  // not a colour
      "#4=DRAWING('d',(#1),.red.,.U.,.X.,1,$);\n"     // case-insensitive item; BOOLEAN .U.; LOGICAL
                                                      // .X.
      "#5=DRAWING('d',(#1),'RED',.T.,.T.,1,$);");     // a string for an enumeration
  EXPECT_EQ(got, (Strings{
                     "EXP-066@3:1 #3 DRAWING attribute 'paint': the enumeration value .PURPLE. is "
                     "not an item of colour (red, green, blue, cyan)",
                     "EXP-066@4:1 #4 DRAWING attribute 'visible': the enumeration value .U. is not "
                     "a BOOLEAN (.T. or .F.)",
                     "EXP-066@4:1 #4 DRAWING attribute 'known': the enumeration value .X. is not a "
                     "LOGICAL (.T., .F. or .U.)",
                     "EXP-063@5:1 #5 DRAWING attribute 'paint': expected colour (ENUMERATION), "
                     "found the string 'RED'",
                 }))
      << join(got);
}

TEST(express_validate, DerivedValues) {
  const Strings got = check(
      "#1=POINT('p',*);\n"                    // '*' where point.coordinates is explicit: error
      "#2=ORIGIN('o',(0.,0.));\n"             // a value where origin derives it: warning
      "#3=ORIGIN('o',$);\n"                   // '$' there: also a warning
      "#4=(ITEM('u')ORIGIN()POINT((1.)));\n"  // complex: origin's DERIVE applies to point's record
      "#5=(ITEM(*)POINT((1.))TAGGED(2));");   // '*' in a record whose attribute is explicit
  EXPECT_EQ(got, (Strings{
                     "EXP-067@2:1 #1 POINT attribute 'coordinates': '*' but the attribute is not "
                     "derived in point",
                     "EXP-068@3:1 #2 ORIGIN attribute 'coordinates': found a list of 2 elements, "
                     "but origin re-declares the attribute as DERIVE: ISO 10303-21 writes '*' "
                     "there",
                     "EXP-068@4:1 #3 ORIGIN attribute 'coordinates': found '$', but origin "
                     "re-declares the attribute as DERIVE: ISO 10303-21 writes '*' there",
                     "EXP-068@5:1 #4 partial record POINT attribute 'coordinates': found a list of "
                     "1 element, but origin re-declares the attribute as DERIVE: ISO 10303-21 "
                     "writes '*' there",
                     "EXP-067@6:1 #5 partial record ITEM attribute 'name': '*' but the attribute "
                     "is not derived in item",
                 }))
      << join(got);
}

TEST(express_validate, TypedValuesInSelects) {
  const Strings got = check(
      "#1=CIRCLE('c',#2,1.);#2=POINT('p',(0.));\n"
      "#3=DRAWING('d',(#1),$,.T.,.T.,1,COUNT_MEASURE(4));\n"   // fine
      "#4=DRAWING('d',(#1),$,.T.,.T.,1,PLANE_ANGLE(4.));\n"    // not a member
      "#5=DRAWING('d',(#1),$,.T.,.T.,1,COUNT_MEASURE(4.));\n"  // member, value of the wrong kind
      "#6=DRAWING('d',(#1),$,.T.,.T.,1,#2);\n"                 // an entity; the select has none
      "#7=DRAWING('d',(#1),$,.T.,.T.,COUNT_MEASURE(1),$);\n"   // the declared type, typed: fine
      "#8=DRAWING('d',(#1),$,.T.,.T.,LABEL('x'),$);");         // another type: wrong kind
  EXPECT_EQ(got, (Strings{
                     "EXP-069@4:1 #4 DRAWING attribute 'value': the typed value PLANE_ANGLE(...) "
                     "is not a member of SELECT measure_value (length_measure, count_measure, "
                     "label)",
                     "EXP-063@5:1 #5 DRAWING attribute 'value': expected INTEGER, found the real "
                     "4.",
                     "EXP-064@6:1 #6 DRAWING attribute 'value': #2 (POINT) is not a member of "
                     "SELECT measure_value (length_measure, count_measure, label)",
                     "EXP-063@8:1 #8 DRAWING attribute 'layer': expected count_measure (INTEGER), "
                     "found the typed value LABEL(...)",
                 }))
      << join(got);
}

TEST(express_validate, ComplexInstanceRecords) {
  const Strings got = check(
      "#1=(ITEM('t')POINT((1.))TAGGED(1,2));\n"  // TAGGED declares one attribute
      "#2=(ITEM('t')POINT((1.))WIDGET(1));\n"    // unknown record: warned, the others checked
      "#3=(ITEM(1)POINT(('x')));");              // values checked per record
  EXPECT_EQ(got, (Strings{
                     "EXP-061@2:1 #1 partial record TAGGED has 2 parameters; tagged declares 1 "
                     "(tag)",
                     "EXP-060@3:1 #2 partial record WIDGET: entity WIDGET is not in the schema; "
                     "its values are not checked",
                     "EXP-063@4:1 #3 partial record ITEM attribute 'name': expected label "
                     "(STRING), found the integer 1",
                     "EXP-063@4:1 #3 partial record POINT attribute 'coordinates' element 1: "
                     "expected length_measure (REAL), found the string 'x'",
                 }))
      << join(got);
}

TEST(express_validate, DiagnosticsAreBounded) {
  std::string data;
  for (int i = 1; i <= 50; ++i) data += "#" + std::to_string(i) + "=POINT($,(0.));\n";
  ValidateOptions options;
  options.max_diagnostics = 10;
  const Strings got = run(program(data), test_schema(), options);
  ASSERT_EQ(got.size(), 11u);
  EXPECT_EQ(got.back(),
            "EXP-058@0:0 validation stopped after 10 diagnostics; the rest of the file was not "
            "checked");
}

TEST(express_validate, ACancelFlagStopsTheCheck) {
  std::string data;
  for (int i = 1; i <= 10000; ++i) data += "#" + std::to_string(i) + "=POINT($,(0.));\n";
  ValidateOptions options;
  options.max_diagnostics = 100000;
  EXPECT_EQ(run(program(data), test_schema(), options).size(), 10000u);
  std::atomic<bool> cancel{true};
  options.cancel = &cancel;
  // The flag is looked at every 4096 instances: the check stops at the first look.
  EXPECT_LT(run(program(data), test_schema(), options).size(), 4096u);
}

// Tolerant (ValidateOptions::tolerant): EXP-059, EXP-062 and EXP-064 are one warning per code,
// entity (as written) and attribute, at the first instance, with a count; what the interpreter
// cannot check again (here EXP-061, EXP-063) stays one error per instance.
TEST(express_validate, TolerantAggregatesWhatIsCheckedAgainDownstream) {
  const std::string data =
      "#1=POINT($,(0.));\n"
      "#2=POINT($,(0.,$));\n"
      "#3=POINT('p',(0.),3);\n"
      "#4=ITEM('i');\n"
      "#5=CIRCLE('c',#6,1.);\n"
      "#6=CIRCLE('c',#1,1.);\n"
      "#7=POINT($,('x'));\n"
      "#8=ITEM('j');";
  ValidateOptions tolerant;
  tolerant.tolerant = true;
  const Strings got = run(program(data), test_schema(), tolerant);
  EXPECT_EQ(got, (Strings{
                     "EXP-061@4:1 #3 POINT has 3 parameters; the schema gives point 2 (name, "
                     "coordinates)",
                     "EXP-063@8:1 #7 POINT attribute 'coordinates' element 1: expected "
                     "length_measure (REAL), found the string 'x'",
                     "EXP-062@2:1 \u00d73, first #1 POINT.name: '$' but the attribute is not "
                     "OPTIONAL (tolerated; an error follows where machining needs the value; "
                     "--strict reports each instance as an error)",
                     "EXP-062@3:1 #2 POINT.coordinates: element 2: '$' but the elements of LIST "
                     "are not OPTIONAL (tolerated; an error follows where machining needs the "
                     "value; --strict reports each instance as an error)",
                     "EXP-059@5:1 \u00d72, first #4 ITEM: item is ABSTRACT; only its subtypes (or "
                     "a complex instance) can be instantiated (tolerated; an error follows where "
                     "machining needs the value; --strict reports each instance as an error)",
                     "EXP-064@6:1 #5 CIRCLE.centre: #6 (CIRCLE) is not a point (nor a subtype of "
                     "it) (tolerated; an error follows where machining needs the value; --strict "
                     "reports each instance as an error)",
                 }))
      << join(got);
  p21::ReadResult read = p21::read(program(data));
  for (const auto& d : validate(read.model, test_schema(), tolerant)) {
    const bool aggregated = d.code == diag::Code::ExpRequiredOmitted ||
                            d.code == diag::Code::ExpAbstractInstance ||
                            d.code == diag::Code::ExpReferenceType;
    EXPECT_EQ(d.severity, aggregated ? diag::Severity::Warning : diag::Severity::Error)
        << d.message;
  }
  // Strict, the same file gives one error per instance, as before the tolerant check existed.
  const Strings strict = run(program(data), test_schema());
  EXPECT_EQ(strict.size(), 9u) << join(strict);
}

// However many instances deviate, the tolerant check says so once per entity and attribute,
// and the limit on diagnostics is left for the errors.
TEST(express_validate, TolerantWarningsDoNotGrowWithTheFile) {
  std::string data;
  for (int i = 1; i <= 5000; ++i) data += "#" + std::to_string(i) + "=POINT($,(0.));\n";
  data += "#9999=POINT('p',(0.),3);\n";
  ValidateOptions options;
  options.tolerant = true;
  options.max_diagnostics = 1;
  const Strings got = run(program(data), test_schema(), options);
  ASSERT_EQ(got.size(), 2u) << join(got);
  EXPECT_EQ(got[0].substr(0, 7), "EXP-061");
  EXPECT_NE(got[1].find("\u00d75000, first #1 POINT.name"), std::string::npos) << got[1];
}

// A check in pieces (ValidateOptions::helpers) says what one check in order says: an unknown
// entity is reported once, at its first instance, whichever piece that falls in; the limit
// counts over all pieces.
TEST(express_validate, PiecesGiveTheSameDiagnostics) {
  std::string data;
  for (int i = 1; i <= 400; ++i) {
    const std::string n = std::to_string(i);
    if (i % 50 == 0)
      data += "#" + n + "=FROB(1);\n";  // in every piece
    else if (i == 77 || i == 390)
      data += "#" + n + "=WIDGET(2);\n";  // in the first and last
    else if (i % 9 == 0)
      data += "#" + n + "=POINT($,(0.));\n";
    else if (i % 13 == 0)
      data += "#" + n + "=(ITEM('t')POINT((1.))WIDGET(1));\n";
    else
      data += "#" + n + "=POINT('p',(0.,1.));\n";
  }
  const parallel::ThreadGroup threads(3);
  std::atomic<int> offered{0};  // pieces the check offered to `never`: it did split
  const parallel::Helpers never{[&](const parallel::Task&) { ++offered; }, 3};
  for (const bool tolerant : {false, true})
    for (const std::size_t limit : {std::size_t{1000}, std::size_t{1}, std::size_t{2},
                                    std::size_t{5}, std::size_t{30}, std::size_t{47}}) {
      ValidateOptions in_order;
      in_order.max_diagnostics = limit;
      in_order.tolerant = tolerant;
      const Strings expected = run(program(data), test_schema(), in_order);
      ASSERT_FALSE(expected.empty());
      for (const auto* helpers : {&threads.helpers(), &never})
        for (const std::size_t piece : {std::size_t{1}, std::size_t{60}, std::size_t{150}}) {
          SCOPED_TRACE("limit " + std::to_string(limit) + ", pieces of " + std::to_string(piece));
          ValidateOptions in_pieces = in_order;
          in_pieces.helpers = helpers;
          in_pieces.min_piece_instances = piece;
          EXPECT_EQ(join(run(program(data), test_schema(), in_pieces)), join(expected));
        }
    }
  // Per limit: pieces of 1 and of 60 instances make 4 pieces (3 offered), of 150 two (1); each
  // check runs twice, without and with a plan (validated()).
  EXPECT_EQ(offered.load(), 2 * 2 * 6 * (3 + 3 + 1));
}

TEST(express_validate, DeepValuesAreBoundedByTheReader) {
  // LIST [1:3] OF length_measure given lists nested to the reader's limit: one diagnostic, no
  // deep recursion.
  std::string nested = "0.";
  for (int i = 0; i < 60; ++i) nested = "(" + nested + ")";
  const Strings got = check("#1=POINT('p'," + nested + ");");
  ASSERT_EQ(got.size(), 1u) << join(got);
  EXPECT_EQ(got[0].substr(0, 8), "EXP-063@");
}

TEST(express_validate, LinearInTheNumberOfInstances) {
  // 200 000 instances: a quadratic check would take minutes; this takes well under a second.
  std::string data;
  data.reserve(200000 * 40);
  data += "#1=POINT('p',(0.,1.,2.));\n";
  for (int i = 2; i <= 200000; ++i) data += "#" + std::to_string(i) + "=CIRCLE('c',#1,1.);\n";
  p21::ReadResult read = p21::read(program(data));
  ASSERT_TRUE(read.ok());
  const auto start = std::chrono::steady_clock::now();
  const auto diagnostics = validate(read.model, test_schema());
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_TRUE(diagnostics.empty());
  EXPECT_LT(elapsed, std::chrono::seconds(10));
}

// ---------------------------------------------------------------------------------------------
// The STEPcode test cases of the corpus, with their own schemas.

struct CorpusCase {
  const char* schema;
  const char* program;
};

Strings run_corpus(const fs::path& corpus, const CorpusCase& c) {
  const ParseResult parsed = parse_express(ncpost::test::read_file(corpus / c.schema));
  EXPECT_TRUE(parsed.ok()) << test::describe(parsed.diagnostics);
  // The schema is chosen through the registry, as the CLI does.
  SchemaRegistry registry;
  EXPECT_TRUE(registry.add(c.schema, std::make_shared<ParseResult>(parsed)).empty());
  p21::ReadResult read = p21::read(ncpost::test::read_file(corpus / c.program));
  EXPECT_TRUE(read.ok()) << test::describe(read.diagnostics);
  const SchemaSelection selection = registry.select_for(read.model);
  EXPECT_TRUE(selection.diagnostics.empty()) << test::describe(selection.diagnostics);
  if (selection.set() == nullptr) return {"no schema"};
  EXPECT_FALSE(selection.source->builtin);
  return validated(read.model, *selection.set(), {}, selection.source->check_plan());
}

// "attr 2 in inst 1 is wrong", says the file: #1 declares index_count 2 and gives 3 indices.
// The attribute is `vertex_counts` (stepcode_array_bounds_expr.exp), the instance #1; #2 fits.
TEST(express_validate, StepcodeArrayBoundsFromAnAttribute) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const fs::path dir = corpus / "p21-syntax";
  EXPECT_EQ(
      run_corpus(dir, {"stepcode_array_bounds_expr.exp", "stepcode_test_array_bounds_FAIL1.p21"}),
      (Strings{"EXP-065@9:1 #1 STRUCTURED_MESH attribute 'vertex_counts': ARRAY "
               "[1:SELF\\mesh.index_count] OF INTEGER (here [1:2]) holds exactly 2 "
               "elements, found 3"}));
  EXPECT_EQ(run_corpus(dir, {"stepcode_array_bounds_expr.exp", "stepcode_test_array_bounds.p21"}),
            Strings{});
}

TEST(express_validate, StepcodeInverseAttributesAreNotInTheFile) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const fs::path dir = corpus / "p21-syntax";
  EXPECT_EQ(run_corpus(dir, {"stepcode_inherit_inverse.exp", "stepcode_test_inherit_inverse.p21"}),
            Strings{});
  EXPECT_EQ(run_corpus(dir, {"stepcode_inverse_attr.exp", "stepcode_test_inverse_attr.p21"}),
            Strings{});
}

// stepcode_missing_and_required.p21 names AUTOMOTIVE_DESIGN (AP214), which the corpus does not
// have. AP238's long form declares the same cartesian_point (name : label, from
// representation_item, then coordinates), so it stands in: `$` for the name is the error that
// the file's own comment describes.
TEST(express_validate, StepcodeMissingAndRequired) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const ParseResult ap238 = parse_express(ncpost::test::read_file(
      corpus / "express/stepcode_ap238-aim-long_integrated_cnc_schema.exp"));
  ASSERT_TRUE(ap238.ok()) << test::describe(ap238.diagnostics);
  const Strings got =
      run(ncpost::test::read_file(corpus / "p21-syntax/stepcode_missing_and_required.p21"),
          ap238.schemas);
  EXPECT_EQ(got, (Strings{"EXP-062@11:1 #56 CARTESIAN_POINT attribute 'name': '$' but the "
                          "attribute is not OPTIONAL"}));
}

// ---------------------------------------------------------------------------------------------
// The NIST ISO 14649 programs against the built-in schema (schemas/iso14649.exp).

Strings run_builtin(const fs::path& file) {
  const SchemaRegistry registry;
  p21::ReadResult read = p21::read(ncpost::test::read_file(file));
  EXPECT_TRUE(read.ok()) << test::describe(read.diagnostics);
  const SchemaSelection selection = registry.select_for(read.model);
  EXPECT_TRUE(selection.diagnostics.empty()) << test::describe(selection.diagnostics);
  EXPECT_EQ(selection.source, &registry.builtin());
  if (selection.set() == nullptr) return {"no schema"};
  return validated(read.model, *selection.set(), {}, selection.source->check_plan());
}

TEST(express_validate, NistExample1AgainstTheBuiltinSchema) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Strings got = run_builtin(corpus / "p21/nist_toolkit_ex1.stp");
  EXPECT_EQ(got, Strings{}) << join(got);
}

TEST(express_validate, NistExample1ExplicitAgainstTheBuiltinSchema) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Strings got = run_builtin(corpus / "p21/nist_toolkit_ex1E.stp");
  EXPECT_EQ(got, Strings{}) << join(got);
}

TEST(express_validate, OwnBracketExampleAgainstTheBuiltinSchema) {
  const Strings got = run_builtin(ncpost::test::source_dir() / "examples/bracket.stp");
  EXPECT_EQ(got, Strings{}) << join(got);
}

}  // namespace
}  // namespace ncpost::express
