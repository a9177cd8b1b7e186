#include "lexer.hpp"

#include <array>
#include <charconv>
#include <cstring>
#include <string>

#include "ncpost/p21/strings.hpp"
#include "ncpost/p21/value.hpp"

namespace ncpost::p21::detail {
namespace {

using diag::Code;

enum CharClass : std::uint8_t {
  kSpace = 1,
  kDigit = 2,
  kLetter = 4,       // A-Z a-z _
  kDelimiter = 8,    // characters that may follow a number
  kStringStop = 16,  // characters the string fast path must look at
};

constexpr std::array<std::uint8_t, 256> make_classes() {
  std::array<std::uint8_t, 256> t{};
  for (char c : {' ', '\t', '\r', '\n', '\f', '\v'}) t[static_cast<unsigned char>(c)] |= kSpace;
  for (int c = '0'; c <= '9'; ++c) t[c] |= kDigit;
  for (int c = 'A'; c <= 'Z'; ++c) t[c] |= kLetter;
  for (int c = 'a'; c <= 'z'; ++c) t[c] |= kLetter;
  t['_'] |= kLetter;
  for (char c : {' ', '\t', '\r', '\n', '\f', '\v', ',', ')', '(', ';', '/', '}', '=', '\0'})
    t[static_cast<unsigned char>(c)] |= kDelimiter;
  for (int c = 0; c < 0x20; ++c) t[c] |= kStringStop;
  for (int c = 0x7F; c < 0x100; ++c) t[c] |= kStringStop;
  t['\''] |= kStringStop;
  t['\\'] |= kStringStop;
  return t;
}
constexpr auto kClass = make_classes();

inline bool is(char c, std::uint8_t cls) {
  return (kClass[static_cast<unsigned char>(c)] & cls) != 0;
}
inline bool is_hex_upper(char c) {
  return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'F');
}

std::string quoted(const char* begin, const char* end) {
  constexpr std::size_t kMax = 40;
  std::string s(begin, static_cast<std::size_t>(end - begin) > kMax ? begin + kMax : end);
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = '?';
  if (static_cast<std::size_t>(end - begin) > kMax) s += "...";
  return "'" + s + "'";
}

}  // namespace

Lexer::Lexer(std::string_view text, diag::DiagnosticList& diagnostics)
    : begin_(text.data()),
      p_(text.data()),
      end_(text.data() + text.size()),
      diagnostics_(diagnostics) {}

LineIndex::Position Lexer::position(std::uint32_t offset) {
  if (!lines_) lines_.emplace(std::string_view(begin_, static_cast<std::size_t>(end_ - begin_)));
  return lines_->at(offset);
}

void Lexer::report(Code code, const char* at, std::string message) {
  if (quiet_) return;
  const auto pos = position(static_cast<std::uint32_t>(at - begin_));
  diagnostics_.add(code, pos.line, pos.column, std::move(message));
}

Token Lexer::make(Tok kind, const char* start, const char* value, const char* value_end) {
  Token t;
  t.kind = kind;
  t.start = static_cast<std::uint32_t>(start - begin_);
  t.offset = static_cast<std::uint32_t>(value - begin_);
  t.length = static_cast<std::uint32_t>(value_end - value);
  return t;
}

Token Lexer::make(Tok kind, const char* start, const char* end) {
  return make(kind, start, start, end);
}

Token Lexer::error(Code code, const char* at, const char* resume, std::string message,
                   bool recoverable) {
  Token t = make(Tok::Error, at, resume);
  t.recoverable = recoverable;
  report(code, at, std::move(message));
  p_ = resume;
  return t;
}

void Lexer::skip_space_and_comments() {
  for (;;) {
    while (p_ < end_ && is(*p_, kSpace)) ++p_;
    if (p_ + 1 < end_ && p_[0] == '/' && p_[1] == '*') {
      const char* start = p_;
      p_ += 2;
      for (;;) {
        const void* hit = std::memchr(p_, '*', static_cast<std::size_t>(end_ - p_));
        if (!hit) {
          p_ = end_;
          report(Code::P21UnterminatedComment, start,
                 "comment opened here is never closed by '*/'");
          return;
        }
        const char* star = static_cast<const char*>(hit);
        p_ = star + 1;
        if (p_ < end_ && *p_ == '/') {
          ++p_;
          break;
        }
      }
      continue;
    }
    return;
  }
}

bool Lexer::skip_raw_past(std::string_view terminator) {
  const std::string_view rest(p_, static_cast<std::size_t>(end_ - p_));
  const std::size_t at = rest.find(terminator);
  p_ = at == std::string_view::npos ? end_ : p_ + at + terminator.size();
  return at != std::string_view::npos;
}

Token Lexer::next() {
  skip_space_and_comments();
  if (p_ >= end_) return make(Tok::Eof, p_, p_);
  const char* start = p_;
  const char c = *p_;
  switch (c) {
    case '(':
      ++p_;
      return make(Tok::LParen, start, p_);
    case ')':
      ++p_;
      return make(Tok::RParen, start, p_);
    case ',':
      ++p_;
      return make(Tok::Comma, start, p_);
    case '=':
      ++p_;
      return make(Tok::Equals, start, p_);
    case ';':
      ++p_;
      return make(Tok::Semicolon, start, p_);
    case '$':
      ++p_;
      return make(Tok::Dollar, start, p_);
    case '*':
      ++p_;
      return make(Tok::Star, start, p_);
    case '{':
      ++p_;
      return make(Tok::LBrace, start, p_);
    case '}':
      ++p_;
      return make(Tok::RBrace, start, p_);
    case ':':
      ++p_;
      return make(Tok::Colon, start, p_);
    case '\'':
      return lex_string(start);
    case '"':
      return lex_binary(start);
    case '.':
      return lex_enumeration(start);
    case '#':
    case '@':
      return lex_hash_or_at(start);
    case '<':
      return lex_resource(start);
    case '+':
    case '-':
      return lex_number(start);
    case '\0': {
      const char* q = p_;
      while (q < end_ && *q == '\0') ++q;
      return error(Code::P21NulByte, start, q, "NUL byte in the file", false);
    }
    default:
      break;
  }
  if (is(c, kDigit)) return lex_number(start);
  if (is(c, kLetter) || c == '!') return lex_keyword(start);
  return lex_garbage(start);
}

Token Lexer::lex_garbage(const char* start) {
  // One diagnostic for a run of characters that cannot start a token.
  const char* q = start + 1;
  while (q < end_ && !is(*q, kSpace) && !is(*q, kLetter) && !is(*q, kDigit) &&
         std::strchr("()',;=$*#@.\"<{}:", *q) == nullptr && *q != '\0')
    ++q;
  const auto byte = static_cast<unsigned char>(*start);
  std::string what =
      byte >= 0x20 && byte < 0x7F
          ? "character '" + std::string(1, *start) + "'"
          : "byte 0x" + std::string{"0123456789ABCDEF"[byte >> 4]} + "0123456789ABCDEF"[byte & 15];
  return error(Code::P21InvalidCharacter, start, q, what + " cannot start a token", false);
}

Token Lexer::lex_number(const char* start) {
  const char* q = start;
  if (*q == '+' || *q == '-') ++q;
  const char* digits = q;
  while (q < end_ && is(*q, kDigit)) ++q;
  bool is_real = false;
  bool bad = q == digits;
  const char* exponent_digits = nullptr;
  if (!bad && q < end_ && *q == '.') {
    is_real = true;
    ++q;
    while (q < end_ && is(*q, kDigit)) ++q;
    if (q < end_ && (*q == 'E' || *q == 'e')) {
      ++q;
      if (q < end_ && (*q == '+' || *q == '-')) ++q;
      exponent_digits = q;
      while (q < end_ && is(*q, kDigit)) ++q;
      if (q == exponent_digits) bad = true;
    }
  }
  if (bad || (q < end_ && !is(*q, kDelimiter))) {
    // Consume the whole malformed word (for example 1.#INF or 1E5) so one diagnostic covers it.
    while (q < end_ && !is(*q, kDelimiter)) ++q;
    std::string hint;
    const std::string_view word(start, static_cast<std::size_t>(q - start));
    if (word.find('#') != std::string_view::npos)
      hint = " (infinities and NaNs cannot be written in ISO 10303-21)";
    else if (!is_real && word.find_first_of("Ee") != std::string_view::npos)
      hint = " (a real needs a decimal point, as in 1.E5)";
    return error(Code::P21BadNumber, start, q, "malformed number " + quoted(start, q) + hint, true);
  }
  p_ = q;
  const Tok kind = is_real ? Tok::Real : Tok::Integer;
  if (!is_real) {
    const char* first_significant = digits;
    while (first_significant + 1 < q && *first_significant == '0') ++first_significant;
    if (q - first_significant >= 19) {
      std::int64_t v = 0;
      const char* from = *start == '+' ? start + 1 : start;
      if (std::from_chars(from, q, v).ec != std::errc())
        return error(Code::P21NumberOutOfRange, start, q,
                     "integer " + quoted(start, q) + " does not fit in 64 bits", true);
    }
  } else if (exponent_digits != nullptr && q - exponent_digits >= 3) {
    double v = 0;
    const char* from = *start == '+' ? start + 1 : start;
    const auto result = std::from_chars(from, q, v);
    const bool negative_exponent = exponent_digits[-1] == '-';
    if (result.ec == std::errc::result_out_of_range && !negative_exponent)
      return error(Code::P21NumberOutOfRange, start, q,
                   "real " + quoted(start, q) + " is beyond the range of a double", true);
  }
  if (q - start > static_cast<std::ptrdiff_t>(Value::kMaxSliceLength))
    return error(Code::P21TokenTooLong, start, q, "number literal is too long", true);
  return make(kind, start, q);
}

bool Lexer::string_runs_away(const char* newline) const {
  // A literal may span lines, but a following line that starts like an instance (#12=) or
  // closes the section means the closing apostrophe was forgotten. Stopping there keeps one
  // missing apostrophe from swallowing the rest of the file.
  const char* q = newline + 1;
  while (q < end_ && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
  if (q < end_ && *q == '#') {
    const char* d = q + 1;
    while (d < end_ && is(*d, kDigit)) ++d;
    if (d == q + 1) return false;
    while (d < end_ && (*d == ' ' || *d == '\t')) ++d;
    return d < end_ && *d == '=';
  }
  const std::string_view rest(q, static_cast<std::size_t>(end_ - q));
  return rest.starts_with("ENDSEC;") || rest.starts_with("END-ISO-10303-21;");
}

Token Lexer::lex_string(const char* start) {
  const char* q = start + 1;
  bool needs_decoding = false;
  const char* nul_at = nullptr;
  for (;;) {
    while (q < end_ && !is(*q, kStringStop)) ++q;
    if (q >= end_) {
      report(Code::P21UnterminatedString, start, "string is never closed by an apostrophe");
      p_ = end_;
      return make(Tok::Error, start, end_);
    }
    const char c = *q;
    if (c == '\'') {
      if (q + 1 < end_ && q[1] == '\'') {
        needs_decoding = true;
        q += 2;
        continue;
      }
      break;
    }
    needs_decoding = true;
    if (c == '\\') {
      // \S\ takes the next character whatever it is, even an apostrophe.
      q += (end_ - q >= 4 && q[1] == 'S' && q[2] == '\\' && q[3] != '\n') ? 4 : 1;
      continue;
    }
    if (c == '\n') {
      if (string_runs_away(q)) {
        report(Code::P21UnterminatedString, start,
               "string is not closed before the next line, which starts a new instance");
        p_ = q;  // the next token starts on the following line
        return make(Tok::Error, start, q);
      }
      ++q;
      continue;
    }
    if (c == '\0' && nul_at == nullptr) nul_at = q;
    ++q;  // other control characters and non-ASCII bytes: checked below
  }
  const char* body = start + 1;
  p_ = q + 1;
  if (nul_at != nullptr) {
    report(Code::P21NulByte, nul_at, "NUL byte inside a string");
    return make(Tok::Error, start, p_);
  }
  if (q - body > static_cast<std::ptrdiff_t>(Value::kMaxSliceLength)) {
    Token t = make(Tok::Error, start, p_);
    t.recoverable = true;
    report(Code::P21TokenTooLong, start, "string literal is too long");
    return t;
  }
  Token t = make(Tok::String, start, body, q);
  t.needs_decoding = needs_decoding;
  if (needs_decoding) validate_string(t);
  return t;
}

void Lexer::validate_string(const Token& token) {
  const std::string_view raw(begin_ + token.offset, token.length);
  const StringProblem problem = check_string(raw);
  if (problem.kind == StringProblem::None) return;
  const Code code = problem.kind == StringProblem::Malformed       ? Code::P21BadEscape
                    : problem.kind == StringProblem::LoneBackslash ? Code::P21LoneBackslash
                                                                   : Code::P21StringEncoding;
  report(code, begin_ + token.offset + problem.offset, problem.message);
}

Token Lexer::lex_keyword(const char* start) {
  const char* q = start + 1;
  while (q < end_ && (is(*q, kLetter) || is(*q, kDigit))) ++q;
  const std::string_view word(start, static_cast<std::size_t>(q - start));
  if (q < end_ && *q == '-') {
    const std::string_view rest(q, static_cast<std::size_t>(end_ - q));
    if (word == "ISO" && rest.starts_with("-10303-21")) {
      p_ = q + 9;
      return make(Tok::Magic, start, p_);
    }
    if (word == "END" && rest.starts_with("-ISO-10303-21")) {
      p_ = q + 13;
      return make(Tok::EndMagic, start, p_);
    }
  }
  if (*start == '!' && q == start + 1)
    return error(Code::P21InvalidCharacter, start, q, "'!' must start a user-defined keyword",
                 false);
  p_ = q;
  return make(Tok::Keyword, start, q);
}

Token Lexer::lex_hash_or_at(const char* start) {
  const char* q = start + 1;
  if (q < end_ && is(*q, kDigit)) {
    std::uint64_t id = 0;
    bool overflow = false;
    while (q < end_ && is(*q, kDigit)) {
      const auto digit = static_cast<std::uint64_t>(*q - '0');
      if (id > (Value::kMaxId - digit) / 10) overflow = true;
      if (!overflow) id = id * 10 + digit;
      ++q;
    }
    if (overflow)
      return error(Code::P21IdOutOfRange, start, q,
                   "instance name " + quoted(start, q) + " is larger than the supported maximum " +
                       std::to_string(Value::kMaxId),
                   false);
    if (*start == '@') {
      p_ = q;
      return make(Tok::ValueName, start, start + 1, q);
    }
    p_ = q;
    return make(Tok::InstanceName, start, start + 1, q);
  }
  if (q < end_ && is(*q, kLetter)) {
    while (q < end_ && (is(*q, kLetter) || is(*q, kDigit))) ++q;
    p_ = q;
    return make(Tok::ConstantName, start, start + 1, q);
  }
  return error(Code::P21InvalidCharacter, start, q,
               std::string("'") + *start + "' must be followed by digits or a name", false);
}

Token Lexer::lex_enumeration(const char* start) {
  const char* q = start + 1;
  if (q < end_ && is(*q, kDigit)) {
    while (q < end_ && !is(*q, kDelimiter)) ++q;
    return error(Code::P21BadNumber, start, q,
                 "malformed number " + quoted(start, q) + " (a real must start with a digit)",
                 true);
  }
  while (q < end_ && (is(*q, kLetter) || is(*q, kDigit))) ++q;
  if (q == start + 1 || q >= end_ || *q != '.') {
    while (q < end_ && !is(*q, kDelimiter)) ++q;
    return error(Code::P21BadEnumeration, start, q,
                 "malformed enumeration " + quoted(start, q) + " (expected .NAME.)", true);
  }
  p_ = q + 1;
  return make(Tok::Enumeration, start, start + 1, q);
}

Token Lexer::lex_binary(const char* start) {
  const char* q = start + 1;
  const bool good_lead = q < end_ && *q >= '0' && *q <= '3';
  if (good_lead) ++q;
  while (q < end_ && is_hex_upper(*q)) ++q;
  if (!good_lead || q >= end_ || *q != '"') {
    while (q < end_ && *q != '"' && *q != '\n' && *q != ';') ++q;
    if (q < end_ && *q == '"') ++q;
    return error(Code::P21BadBinary, start, q,
                 "malformed binary " + quoted(start, q) +
                     " (expected a digit 0-3 then upper-case hex digits)",
                 true);
  }
  p_ = q + 1;
  return make(Tok::Binary, start, start + 1, q);
}

Token Lexer::lex_resource(const char* start) {
  const char* q = start + 1;
  while (q < end_ && *q != '>' && *q != '\n') ++q;
  if (q >= end_ || *q != '>')
    return error(Code::P21UnexpectedToken, start, q, "'<' opens a name that '>' never closes",
                 false);
  p_ = q + 1;
  return make(Tok::Resource, start, start + 1, q);
}

}  // namespace ncpost::p21::detail
