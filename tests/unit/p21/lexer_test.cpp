// The lexer on its own: token kinds, extents, positions and validation.

#include "lexer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ncpost::p21::detail {
namespace {

struct Lexed {
  std::vector<Token> tokens;
  diag::DiagnosticList diagnostics;
};

Lexed lex_all(std::string_view text) {
  Lexed out;
  Lexer lexer(text, out.diagnostics);
  for (;;) {
    Token t = lexer.next();
    out.tokens.push_back(t);
    if (t.kind == Tok::Eof) break;
  }
  return out;
}

std::vector<Tok> kinds(std::string_view text) {
  std::vector<Tok> out;
  for (const Token& t : lex_all(text).tokens) out.push_back(t.kind);
  return out;
}

TEST(Lexer, PunctuationAndKeywords) {
  EXPECT_EQ(kinds("ISO-10303-21; END-ISO-10303-21;"),
            (std::vector{Tok::Magic, Tok::Semicolon, Tok::EndMagic, Tok::Semicolon, Tok::Eof}));
  EXPECT_EQ(kinds("A_B1(!USER,$,*)={}:"),
            (std::vector{Tok::Keyword, Tok::LParen, Tok::Keyword, Tok::Comma, Tok::Dollar,
                         Tok::Comma, Tok::Star, Tok::RParen, Tok::Equals, Tok::LBrace, Tok::RBrace,
                         Tok::Colon, Tok::Eof}));
}

TEST(Lexer, NumbersKeepTheirText) {
  const std::string text = "12 -3 +4 1. -2.5E-3 0.5e10 007";
  const auto lexed = lex_all(text);
  ASSERT_EQ(lexed.tokens.size(), 8u);
  const std::vector<std::pair<Tok, std::string>> expected = {
      {Tok::Integer, "12"},   {Tok::Integer, "-3"},  {Tok::Integer, "+4"}, {Tok::Real, "1."},
      {Tok::Real, "-2.5E-3"}, {Tok::Real, "0.5e10"}, {Tok::Integer, "007"}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(lexed.tokens[i].kind, expected[i].first) << i;
    EXPECT_EQ(text.substr(lexed.tokens[i].offset, lexed.tokens[i].length), expected[i].second);
  }
  EXPECT_TRUE(lexed.diagnostics.items().empty());
}

TEST(Lexer, InstanceNamesAndConstants) {
  const std::string_view text = "#123 #0042 #CONST_1 @7 @NAME";
  const auto lexed = lex_all(text);
  ASSERT_EQ(lexed.tokens.size(), 6u);
  EXPECT_EQ(lexed.tokens[0].kind, Tok::InstanceName);
  EXPECT_EQ(instance_id(text, lexed.tokens[0]), 123u);
  EXPECT_EQ(instance_id(text, lexed.tokens[1]), 42u);
  EXPECT_EQ(lexed.tokens[2].kind, Tok::ConstantName);
  EXPECT_EQ(lexed.tokens[3].kind, Tok::ValueName);
  EXPECT_EQ(lexed.tokens[4].kind, Tok::ConstantName);
}

TEST(Lexer, StringsEnumerationsBinariesResources) {
  const std::string text = "'it''s' .T. \"3A0F\" <http://x/y#z>";
  const auto lexed = lex_all(text);
  ASSERT_EQ(lexed.tokens.size(), 5u);
  EXPECT_EQ(lexed.tokens[0].kind, Tok::String);
  EXPECT_EQ(text.substr(lexed.tokens[0].offset, lexed.tokens[0].length), "it''s");
  EXPECT_TRUE(lexed.tokens[0].needs_decoding);
  EXPECT_EQ(lexed.tokens[1].kind, Tok::Enumeration);
  EXPECT_EQ(text.substr(lexed.tokens[1].offset, lexed.tokens[1].length), "T");
  EXPECT_EQ(lexed.tokens[2].kind, Tok::Binary);
  EXPECT_EQ(lexed.tokens[3].kind, Tok::Resource);
  EXPECT_EQ(text.substr(lexed.tokens[3].offset, lexed.tokens[3].length), "http://x/y#z");
}

TEST(Lexer, PageEscapeMayTakeAnApostrophe) {
  // \S\' is the character 0xA7; the apostrophe does not close the string.
  const std::string text = "'a\\S\\'b' X";
  const auto lexed = lex_all(text);
  ASSERT_EQ(lexed.tokens[0].kind, Tok::String);
  EXPECT_EQ(text.substr(lexed.tokens[0].offset, lexed.tokens[0].length), "a\\S\\'b");
  EXPECT_EQ(lexed.tokens[1].kind, Tok::Keyword);
}

TEST(Lexer, CommentsAnywhereAndLineColumn) {
  const std::string_view text = "/* a\n comment */ A\n  /* x */ #5";
  diag::DiagnosticList diagnostics;
  Lexer lexer(text, diagnostics);
  const Token a = lexer.next();
  const Token five = lexer.next();
  EXPECT_EQ(lexer.next().kind, Tok::Eof);
  EXPECT_EQ(lexer.position(a.start).line, 2u);
  EXPECT_EQ(lexer.position(a.start).column, 13u);
  EXPECT_EQ(lexer.position(five.start).line, 3u);
  EXPECT_EQ(lexer.position(five.start).column, 11u);
}

TEST(Lexer, PlainStringNeedsNoDecoding) {
  const auto lexed = lex_all("'plain text 123'");
  EXPECT_FALSE(lexed.tokens[0].needs_decoding);
}

TEST(Lexer, MalformedNumbersAreOneRecoverableError) {
  const auto lexed = lex_all("-1.#INF, 1E5, 1.E, .5");
  std::vector<std::string> codes;
  for (const auto& d : lexed.diagnostics.items()) codes.emplace_back(d.code_id());
  EXPECT_EQ(codes, (std::vector<std::string>{"P21-007", "P21-007", "P21-007", "P21-007"}));
  EXPECT_EQ(lexed.tokens[0].kind, Tok::Error);
  EXPECT_TRUE(lexed.tokens[0].recoverable);
  EXPECT_EQ(lexed.tokens[1].kind, Tok::Comma);
}

TEST(Lexer, NumberRanges) {
  EXPECT_TRUE(lex_all("9223372036854775807").diagnostics.items().empty());
  EXPECT_TRUE(lex_all("-9223372036854775808").diagnostics.items().empty());
  EXPECT_TRUE(lex_all("1.E-400").diagnostics.items().empty());  // underflow reads as 0
  for (const char* bad : {"9223372036854775808", "123456789012345678901234", "1.E400"}) {
    const auto lexed = lex_all(bad);
    ASSERT_EQ(lexed.diagnostics.items().size(), 1u) << bad;
    EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "P21-008") << bad;
  }
}

TEST(Lexer, IdOverflow) {
  const auto lexed = lex_all("#99999999999999999999999");
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "P21-009");
  EXPECT_TRUE(lex_all("#1152921504606846975").diagnostics.items().empty());  // 2^60 - 1
  EXPECT_FALSE(lex_all("#1152921504606846976").diagnostics.items().empty());
}

TEST(Lexer, BadEnumerationAndBinary) {
  EXPECT_EQ(lex_all(".ABC").diagnostics.items().at(0).code_id(), "P21-010");
  EXPECT_EQ(lex_all("\"4F\"").diagnostics.items().at(0).code_id(), "P21-011");
  EXPECT_EQ(lex_all("\"0FG\"").diagnostics.items().at(0).code_id(), "P21-011");
}

TEST(Lexer, NulRunIsOneDiagnostic) {
  const std::string text("A\0\0\0B", 5);
  const auto lexed = lex_all(text);
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "P21-001");
  EXPECT_EQ(lexed.tokens[2].kind, Tok::Keyword);
}

TEST(Lexer, InvalidCharacterRun) {
  const auto lexed = lex_all("A %%% B");
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "P21-002");
  EXPECT_EQ(lexed.diagnostics.items()[0].column, 3u);
}

TEST(Lexer, UnterminatedStringStopsBeforeTheNextInstance) {
  const std::string text = "#1=A('oops);\n#2=B(1);";
  const auto lexed = lex_all(text);
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "P21-003");
  // The next instance is still there, token by token.
  bool found = false;
  for (const auto& t : lexed.tokens)
    found = found || (t.kind == Tok::InstanceName && instance_id(text, t) == 2);
  EXPECT_TRUE(found);
}

TEST(Lexer, StringMaySpanLines) {
  const auto lexed = lex_all("'first line\nsecond line' X");
  EXPECT_TRUE(lexed.diagnostics.items().empty());
  EXPECT_EQ(lexed.tokens[0].kind, Tok::String);
  EXPECT_EQ(lexed.tokens[1].kind, Tok::Keyword);
}

TEST(Lexer, UnterminatedComment) {
  const auto lexed = lex_all("A /* never closed");
  ASSERT_EQ(lexed.diagnostics.items().size(), 1u);
  EXPECT_EQ(lexed.diagnostics.items()[0].code_id(), "P21-004");
}

TEST(Lexer, QuietModeSuppressesReports) {
  diag::DiagnosticList diagnostics;
  Lexer lexer("%% 1.#X", diagnostics);
  lexer.set_quiet(true);
  while (lexer.next().kind != Tok::Eof) {
  }
  EXPECT_TRUE(diagnostics.items().empty());
}

}  // namespace
}  // namespace ncpost::p21::detail
