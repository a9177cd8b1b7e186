// Malformed schemas: each gives its stable code at the right line:column, recovery resumes at
// the next `;` or END_x, and hostile nesting is bounded instead of exhausting the stack.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_support.hpp"

namespace ncpost::express {
namespace {

using Strings = std::vector<std::string>;
using test::codes;
using test::positions;

TEST(express_diagnostics, MissingSemicolonIsReportedAtTheNextTokenAndParsingResumes) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "ENTITY e;\n"
      "  a : INTEGER\n"
      "  b : REAL;\n"
      "  c : STRING;\n"
      "END_ENTITY;\n"
      "ENTITY f; END_ENTITY;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-010@4:3"}));
  EXPECT_NE(result.diagnostics[0].message.find("expected ';'"), std::string::npos)
      << result.diagnostics[0].message;
  const Entity* e = result.schemas.find_entity("e");
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(test::attribute_names(*e), (Strings{"c"}));
  EXPECT_NE(result.schemas.find_entity("f"), nullptr);
  EXPECT_FALSE(result.ok());
}

TEST(express_diagnostics, MissingEndEntityCostsOneDiagnostic) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "  ENTITY e;\n"
      "    a : INTEGER;\n"
      "  ENTITY f;\n"
      "    b : REAL;\n"
      "  END_ENTITY;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-011@2:3"}));
  ASSERT_NE(result.schemas.find_entity("f"), nullptr);
  EXPECT_EQ(test::attribute_names(*result.schemas.find_entity("f")), (Strings{"b"}));
  EXPECT_EQ(test::attribute_names(*result.schemas.find_entity("e")), (Strings{"a"}));
}

TEST(express_diagnostics, MissingEndSchemaAndUnclosedFunction) {
  EXPECT_EQ(positions(parse_express("SCHEMA s;\nENTITY e; END_ENTITY;\n")),
            (Strings{"EXP-011@1:1"}));
  EXPECT_EQ(
      positions(parse_express("SCHEMA s;\n  FUNCTION f : INTEGER;\n  RETURN (1);\nEND_SCHEMA;")),
      (Strings{"EXP-011@2:3"}));
  EXPECT_EQ(
      positions(parse_express("SCHEMA s;\n  FUNCTION f : INTEGER; END_PROCEDURE;\nEND_SCHEMA;")),
      (Strings{"EXP-010@2:25"}));
}

TEST(express_diagnostics, NoSchemaAtAll) {
  EXPECT_EQ(positions(parse_express("")), (Strings{"EXP-014@1:1"}));
  EXPECT_EQ(codes(parse_express("(* only a remark *) ENTITY e; END_ENTITY;")),
            (Strings{"EXP-010", "EXP-014"}));
}

TEST(express_diagnostics, UnknownSupertypeTypeAndSelectItemAtTheirOwnPositions) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "ENTITY e SUBTYPE OF (missing_super);\n"
      "  a : missing_type;\n"
      "  b : LIST [1:?] OF SET OF missing_element;\n"
      "END_ENTITY;\n"
      "TYPE sel = SELECT (e, missing_item); END_TYPE;\n"
      "TYPE t = sel; END_TYPE;\n"
      "ENTITY g SUBTYPE OF (t); END_ENTITY;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-030@2:22", "EXP-031@3:7", "EXP-031@4:28",
                                        "EXP-031@6:23", "EXP-030@8:22"}));
}

TEST(express_diagnostics, InheritanceAndTypeCycles) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "ENTITY a SUBTYPE OF (c); x : INTEGER; END_ENTITY;\n"
      "ENTITY b SUBTYPE OF (a); END_ENTITY;\n"
      "ENTITY c SUBTYPE OF (b); END_ENTITY;\n"
      "TYPE t1 = t2; END_TYPE;\n"
      "TYPE t2 = t1; END_TYPE;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(codes(result), (Strings{"EXP-036", "EXP-037"}));
  // The link that closes the cycle (b → a) is dropped; the rest keeps its attributes.
  EXPECT_EQ(test::attribute_names(*result.schemas.find_entity("a")), (Strings{"x"}));
  EXPECT_TRUE(result.schemas.find_entity("b")->supertype_refs.empty());
  EXPECT_EQ(result.schemas.underlying_type(*result.schemas.find_type("t1")).kind, TypeKind::Named);
}

TEST(express_diagnostics, ImportsFromMissingSchemasAreReportedOnceAtTheImport) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "  USE FROM elsewhere (far_entity);\n"
      "  REFERENCE FROM present (nope);\n"
      "  ENTITY e SUBTYPE OF (far_entity); a : far_entity; END_ENTITY;\n"
      "END_SCHEMA;\n"
      "SCHEMA present; END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-032@2:12", "EXP-033@3:27"}));
}

TEST(express_diagnostics, BadRedeclarations) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "ENTITY p; x : REAL; END_ENTITY;\n"
      "ENTITY q; END_ENTITY;\n"
      "ENTITY r SUBTYPE OF (p);\n"
      "  SELF\\q.x : INTEGER;\n"
      "  SELF\\p.nope : INTEGER;\n"
      "DERIVE\n"
      "  SELF\\p.other : REAL := 1.0;\n"
      "END_ENTITY;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-034@5:3", "EXP-034@6:3", "EXP-034@8:3"}));
}

TEST(express_diagnostics, InverseForAnAttributeThatDoesNotExist) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "ENTITY owner_of; INVERSE things : SET OF thing FOR holder; END_ENTITY;\n"
      "ENTITY thing; owner : owner_of; END_ENTITY;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-038@2:26"}));
}

TEST(express_diagnostics, DuplicatesAttributeIsAnErrorDeclarationIsAWarning) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "ENTITY e; a : INTEGER; a : REAL; END_ENTITY;\n"
      "TYPE t = REAL; END_TYPE;\n"
      "TYPE t = INTEGER; END_TYPE;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-022@2:24", "EXP-020@4:1"}));
  EXPECT_EQ(result.diagnostics[1].severity, diag::Severity::Warning);
  EXPECT_NE(result.diagnostics[1].message.find("line 3"), std::string::npos);
  EXPECT_EQ(result.schemas.find_type("t")->underlying.kind, TypeKind::Real);

  const ParseResult only_warning =
      parse_express("SCHEMA s; TYPE t = REAL; END_TYPE; TYPE t = REAL; END_TYPE; END_SCHEMA;");
  EXPECT_TRUE(only_warning.ok());
  EXPECT_EQ(codes(only_warning), (Strings{"EXP-020"}));
}

TEST(express_diagnostics, UnbalancedBracketsInExpressions) {
  const ParseResult result = parse_express(
      "SCHEMA s;\n"
      "ENTITY e; a : INTEGER;\n"
      "WHERE\n"
      "  wr1 : SIZEOF(a > 0;\n"
      "  wr2 : a > 0);\n"
      "  wr3 : a > 0;\n"
      "END_ENTITY;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-015@4:21", "EXP-015@5:14"}));
  ASSERT_EQ(result.schemas.find_entity("e")->where_rules.size(), 1u);
  EXPECT_EQ(result.schemas.find_entity("e")->where_rules[0].label, "wr3");
}

std::string repeat(std::string_view text, std::size_t times) {
  std::string out;
  out.reserve(text.size() * times);
  for (std::size_t i = 0; i < times; ++i) out += text;
  return out;
}

TEST(express_diagnostics, HostileNestingIsBoundedNotRecursed) {
  const std::size_t deep = 200000;
  const std::string parens = "SCHEMA s; ENTITY e; a : INTEGER; WHERE wr1 : " + repeat("(", deep) +
                             "a" + repeat(")", deep) + "; END_ENTITY; END_SCHEMA;";
  EXPECT_EQ(codes(parse_express(parens)).at(0), "EXP-012");

  const std::string lists =
      "SCHEMA s; TYPE t = " + repeat("LIST OF ", deep) + "INTEGER; END_TYPE; END_SCHEMA;";
  EXPECT_EQ(codes(parse_express(lists)).at(0), "EXP-012");

  const std::string supertypes = "SCHEMA s; ENTITY e SUPERTYPE OF (" + repeat("ONEOF(", deep) +
                                 "x" + repeat(")", deep) + "); END_ENTITY; END_SCHEMA;";
  EXPECT_EQ(codes(parse_express(supertypes)).at(0), "EXP-012");

  const std::string functions =
      "SCHEMA s; " + repeat("FUNCTION f; ", deep) + repeat("END_FUNCTION; ", deep) + "END_SCHEMA;";
  EXPECT_EQ(codes(parse_express(functions)).at(0), "EXP-012");

  std::string chain = "SCHEMA s; ENTITY e0; a : INTEGER; END_ENTITY;";
  for (int i = 1; i <= 100; ++i)
    chain += " ENTITY e" + std::to_string(i) + " SUBTYPE OF (e" + std::to_string(i - 1) +
             "); END_ENTITY;";
  chain += " END_SCHEMA;";
  const ParseResult result = parse_express(chain);
  EXPECT_EQ(codes(result).at(0), "EXP-041");
  EXPECT_EQ(test::attribute_names(*result.schemas.find_entity("e64")), (Strings{"a"}));
}

TEST(express_diagnostics, ErrorLimitStopsTheParse) {
  ParseLimits limits;
  limits.max_errors = 10;
  const ParseResult result = parse_express(
      "SCHEMA s; ENTITY e; " + repeat("a : ; ", 1000) + " END_ENTITY; END_SCHEMA;", limits);
  EXPECT_LE(result.diagnostics.size(), 12u);
  EXPECT_EQ(codes(result).back(), "EXP-013");
}

TEST(express_diagnostics, InputLargerThanTheLimitIsRejected) {
  ParseLimits limits;
  limits.max_input_bytes = 16;
  const ParseResult result = parse_express("SCHEMA s; END_SCHEMA; -- a remark", limits);
  EXPECT_EQ(codes(result), (Strings{"EXP-040"}));
  EXPECT_TRUE(result.schemas.schemas().empty());
}

TEST(express_diagnostics, PositionsCountLinesInsideRemarks) {
  const ParseResult result = parse_express(
      "SCHEMA s; (* one\n"
      "two (* three\n"
      "four *) five *)\n"
      "  ENTITY e; x : ; END_ENTITY;\n"
      "END_SCHEMA;\n");
  EXPECT_EQ(positions(result), (Strings{"EXP-010@4:17"}));
}

}  // namespace
}  // namespace ncpost::express
