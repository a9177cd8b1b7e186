#pragma once
// EXPRESS lexer: turns the whole source into a vector of tokens that are offsets into the one
// source buffer (the IfcOpenShell idea), with 1-based line:column for diagnostics. Remarks
// `(* ... *)` nest; `--` tail remarks run to the end of the line. Keywords are recognised
// case-insensitively and only for the words the parser dispatches on; every other word is an
// identifier, so a schema that uses e.g. `value` as an attribute name still parses.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"

namespace ncpost::express::detail {

enum class TokenKind : std::uint8_t {
  Identifier,  // also keywords; see Token::keyword
  Integer,
  Real,
  String,  // 'simple' or "encoded"
  Binary,  // %0101
  Punct,   // operators and separators, see Token::text
  End,     // end of input
};

// The reserved words that steer the parser. Everything else is Keyword::None.
enum class Keyword : std::uint8_t {
  None,
  Abstract,
  Aggregate,
  And,
  AndOr,
  Array,
  As,
  Bag,
  BasedOn,
  Binary,
  Boolean,
  Constant,
  Derive,
  EndConstant,
  EndEntity,
  EndFunction,
  EndProcedure,
  EndRule,
  EndSchema,
  EndSubtypeConstraint,
  EndType,
  Entity,
  Enumeration,
  Extensible,
  Fixed,
  For,
  From,
  Function,
  Generic,
  GenericEntity,
  Integer,
  Inverse,
  List,
  Logical,
  Number,
  Of,
  OneOf,
  Optional,
  Procedure,
  Real,
  Reference,
  Renamed,
  Rule,
  Schema,
  Select,
  Self,
  Set,
  String,
  Subtype,
  SubtypeConstraint,
  Supertype,
  Type,
  Unique,
  Use,
  Where,
  With,
};

struct Token {
  TokenKind kind = TokenKind::End;
  Keyword keyword = Keyword::None;
  std::uint32_t offset = 0;
  std::uint32_t length = 0;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

// Spelling of a keyword in upper case, for messages ("expected END_ENTITY").
[[nodiscard]] std::string_view keyword_spelling(Keyword keyword) noexcept;

// True for every reserved word of ISO 10303-11 (not only the parser's keywords); used to print
// expressions with keywords in upper case and identifiers in lower case.
[[nodiscard]] bool is_reserved_word(std::string_view lower_case_word) noexcept;

// Lower-cases ASCII letters; EXPRESS identifiers are case-insensitive.
[[nodiscard]] std::string to_lower(std::string_view text);

// Tokenises `source`. The last token is always TokenKind::End. Lexical errors go to
// `diagnostics` and the offending characters are skipped, so the parser always gets a stream.
[[nodiscard]] std::vector<Token> tokenize(std::string_view source,
                                          diag::DiagnosticList& diagnostics);

}  // namespace ncpost::express::detail
