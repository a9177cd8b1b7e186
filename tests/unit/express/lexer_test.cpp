// The EXPRESS lexer on its own: remarks (nested, tail), literals, operators, keywords and
// positions. Parser-level effects of remarks are tested at the end through parse_express.

#include "lexer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ncpost/express/parse.hpp"
#include "test_support.hpp"

namespace ncpost::express::detail {
namespace {

struct Lexed {
  std::vector<Token> tokens;
  diag::DiagnosticList diagnostics;
};

Lexed lex(std::string_view text) {
  Lexed out;
  out.tokens = tokenize(text, out.diagnostics);
  return out;
}

// The spelling of every token except the final End.
std::vector<std::string> spellings(std::string_view text) {
  std::vector<std::string> out;
  for (const Token& t : lex(text).tokens)
    if (t.kind != TokenKind::End) out.emplace_back(text.substr(t.offset, t.length));
  return out;
}

using Strings = std::vector<std::string>;

TEST(express_lexer, NestedRemarksAreSkippedAsOneRemark) {
  EXPECT_EQ(spellings("a (* x (* y *) z *) b"), (Strings{"a", "b"}));
  // The inner `*)` does not end the remark: `z` is still inside it.
  EXPECT_EQ(spellings("(* (* *) END_SCHEMA; *) c"), (Strings{"c"}));
}

TEST(express_lexer, TailRemarkRunsToTheEndOfTheLine) {
  EXPECT_EQ(spellings("a -- b (* not a remark opener here\nc"), (Strings{"a", "c"}));
  EXPECT_EQ(spellings("a - - b"), (Strings{"a", "-", "-", "b"}));
}

TEST(express_lexer, RemarkMarkersInsideStringsAreText) {
  EXPECT_EQ(spellings("'(* -- ''quoted'' *)' x"), (Strings{"'(* -- ''quoted'' *)'", "x"}));
  EXPECT_EQ(spellings("\"00000041\" %0101"), (Strings{"\"00000041\"", "%0101"}));
}

TEST(express_lexer, KeywordsAreCaseInsensitiveAndOtherWordsAreIdentifiers) {
  const Lexed lexed = lex("Entity ENTITY entity eNtItY end_Entity value");
  ASSERT_EQ(lexed.tokens.size(), 7u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(lexed.tokens[i].keyword, Keyword::Entity) << i;
  EXPECT_EQ(lexed.tokens[4].keyword, Keyword::EndEntity);
  // `value` is a reserved word of EXPRESS but not one the parser dispatches on.
  EXPECT_EQ(lexed.tokens[5].keyword, Keyword::None);
  EXPECT_EQ(lexed.tokens[5].kind, TokenKind::Identifier);
}

TEST(express_lexer, MultiCharacterOperatorsAreSingleTokens) {
  EXPECT_EQ(spellings("a:=:b :<>: := <* || ** <> <= >= | SELF\\e.x"),
            (Strings{"a", ":=:", "b", ":<>:", ":=", "<*", "||", "**", "<>", "<=", ">=", "|", "SELF",
                     "\\", "e", ".", "x"}));
}

TEST(express_lexer, NumbersAreIntegersOrReals) {
  const Lexed lexed = lex("1 2.5 3.e2 1.5E-3 42");
  std::vector<TokenKind> kinds;
  for (const Token& t : lexed.tokens) kinds.push_back(t.kind);
  EXPECT_EQ(kinds, (std::vector{TokenKind::Integer, TokenKind::Real, TokenKind::Real,
                                TokenKind::Real, TokenKind::Integer, TokenKind::End}));
}

TEST(express_lexer, TokensCarryLineAndColumnAcrossRemarks) {
  const Lexed lexed = lex("a\n(* one\n two *)  bb\n\tc");
  ASSERT_EQ(lexed.tokens.size(), 4u);
  EXPECT_EQ(lexed.tokens[1].line, 3u);
  EXPECT_EQ(lexed.tokens[1].column, 10u);
  EXPECT_EQ(lexed.tokens[2].line, 4u);
  EXPECT_EQ(lexed.tokens[2].column, 2u);
}

TEST(express_lexer, UnterminatedRemarkIsReportedWhereItStarts) {
  const Lexed lexed = lex("a\n  (* (* closed once *) but not twice");
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  const diag::Diagnostic& d = lexed.diagnostics.items()[0];
  EXPECT_EQ(d.code_id(), "EXP-002");
  EXPECT_EQ(d.line, 2u);
  EXPECT_EQ(d.column, 3u);
}

TEST(express_lexer, UnterminatedStringIsReported) {
  const Lexed lexed = lex("x := 'abc");
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "EXP-003");
  EXPECT_EQ(lexed.diagnostics.items()[0].column, 6u);
}

TEST(express_lexer, InvalidCharacterIsReportedAndSkipped) {
  const Lexed lexed = lex("a # b");
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "EXP-001");
  EXPECT_EQ(lexed.diagnostics.items()[0].column, 3u);
  EXPECT_EQ(spellings("a # b"), (Strings{"a", "b"}));
}

TEST(express_lexer, RemarksHideDeclarationsFromTheParser) {
  ASSERT_PARSES_CLEANLY(result, R"(
    SCHEMA s;
    (* ENTITY hidden; END_ENTITY;
       (* END_SCHEMA; nested *) still hidden: ENTITY hidden2; END_ENTITY; *)
    ENTITY visible; -- ENTITY hidden3; END_ENTITY;
      x : INTEGER; (* y : REAL; *)
    END_ENTITY;
    END_SCHEMA;)");
  const Schema& schema = result.schemas.schemas().at(0);
  ASSERT_EQ(schema.entities.size(), 1u);
  EXPECT_EQ(schema.entities[0].name, "visible");
  EXPECT_EQ(test::attribute_names(schema.entities[0]), (Strings{"x"}));
}

// Readers of other forms (P28) ask it before a name becomes a P21 keyword.
TEST(express_lexer, WhatCanNameADeclaration) {
  for (const char* name : {"cartesian_point", "IfcText", "length_measure2", "a", "STRINGS",
                           "end_subtype_constraints", "a_name_longer_than_any_reserved_word"})
    EXPECT_TRUE(can_name_a_declaration(name)) << name;
  for (const char* name :
       {"", "string", "STRING", "Real", "end_subtype_constraint", "self", "1length", "_x",
        "length measure", "string-wrapper", "ca@tesian", "caf\xc3\xa9"})
    EXPECT_FALSE(can_name_a_declaration(name)) << name;
}

}  // namespace
}  // namespace ncpost::express::detail
