#pragma once
// ISO 10303-21 lexer: turns the text into tokens that are offsets into it, and never allocates
// per token. It validates every literal as it goes (numbers in range, escapes well formed), so
// that the Model can convert values later without failing. Lexical errors are reported once,
// to the diagnostic list, and the token comes back as `Error`.

#include <cstdint>
#include <optional>
#include <string_view>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/reader.hpp"

namespace ncpost::p21::detail {

enum class Tok : std::uint8_t {
  Eof,
  Keyword,       // STANDARD or !USER_DEFINED keyword; slice is the name
  InstanceName,  // #123; `id` holds the number
  ConstantName,  // #NAME or @NAME; slice is the name without the sigil
  ValueName,     // @123; slice is the digits
  Integer,
  Real,
  String,       // slice is the body between the apostrophes
  Binary,       // slice is the body between the quotes
  Enumeration,  // slice is the name between the dots
  Resource,     // <...>; slice is the body between the brackets
  LParen,
  RParen,
  Comma,
  Equals,
  Semicolon,
  Dollar,
  Star,
  LBrace,
  RBrace,
  Colon,
  Magic,     // ISO-10303-21
  EndMagic,  // END-ISO-10303-21
  Error,     // already reported; `recoverable` says whether its extent is trustworthy
};

// Positions are byte offsets only: line and column are worked out when a diagnostic needs
// them, so the hot path never counts newlines. The token is 16 bytes so that it comes back
// from next() in registers; an instance name's number is re-read from its (validated) digits
// with instance_id().
struct Token {
  Tok kind = Tok::Eof;
  bool needs_decoding = false;  // strings: more than a plain copy is needed to decode
  bool recoverable = false;     // errors: the token's extent is sound, a placeholder may stand in
  std::uint32_t start = 0;      // first byte of the token, delimiters included
  std::uint32_t offset = 0;     // the token's value: the slice without delimiters
  std::uint32_t length = 0;
};
static_assert(sizeof(Token) == 16);

// The number of an InstanceName token; the lexer has checked that it is in range.
[[nodiscard]] inline std::uint64_t instance_id(std::string_view text, const Token& t) {
  std::uint64_t id = 0;
  for (std::uint32_t i = 0; i < t.length; ++i)
    id = id * 10 + static_cast<std::uint64_t>(text[t.offset + i] - '0');
  return id;
}

class Lexer {
 public:
  // `text` is what may be lexed now: the whole file, or (p21::StreamReader) the part of it that
  // has arrived, cut after a ';' outside any literal or comment. Its end gives Tok::Eof.
  Lexer(std::string_view text, diag::DiagnosticList& diagnostics);

  [[nodiscard]] Token next();
  // While quiet, lexical errors are not reported: used while skipping the rest of a broken
  // instance, so one broken instance gives one diagnostic.
  void set_quiet(bool quiet) { quiet_ = quiet; }
  // Skips raw text up to and including `terminator` (for SIGNATURE sections, whose base64
  // content is not made of tokens). Returns false at end of input.
  bool skip_raw_past(std::string_view terminator);
  [[nodiscard]] bool at_end() const { return p_ >= end_; }
  // More of the same text has arrived: it now ends `length` bytes after its start. The text's
  // address may have changed (it was moved to its owner), its bytes have not.
  void extend(const char* text, std::size_t length) {
    p_ = text + (p_ - begin_);
    begin_ = text;
    end_ = text + length;
  }
  // Goes on at `offset`, with `length` bytes available: another reader has read what lies in
  // between (a piece of a file read in parallel).
  void jump(std::size_t offset, std::size_t length) {
    p_ = begin_ + offset;
    end_ = begin_ + length;
  }
  // Stops lexing here: every later token is Tok::Eof (a cancelled read unwinds this way).
  void cut() { end_ = p_; }
  // Line and column of a byte offset; the line table is built on the first call.
  [[nodiscard]] LineIndex::Position position(std::uint32_t offset);

 private:
  void skip_space_and_comments();
  Token make(Tok kind, const char* start, const char* end);
  Token make(Tok kind, const char* start, const char* value, const char* value_end);
  Token error(diag::Code code, const char* at, const char* resume, std::string message,
              bool recoverable);
  Token lex_number(const char* start);
  Token lex_string(const char* start);
  Token lex_keyword(const char* start);
  Token lex_hash_or_at(const char* start);
  Token lex_enumeration(const char* start);
  Token lex_binary(const char* start);
  Token lex_resource(const char* start);
  Token lex_garbage(const char* start);
  void report(diag::Code code, const char* at, std::string message);
  [[nodiscard]] bool string_runs_away(const char* newline) const;
  void validate_string(const Token& token);

  const char* begin_;
  const char* p_;
  const char* end_;
  std::optional<LineIndex> lines_;
  diag::DiagnosticList& diagnostics_;
  bool quiet_ = false;
};

}  // namespace ncpost::p21::detail
