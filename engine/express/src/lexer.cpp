#include "lexer.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <unordered_map>
#include <unordered_set>

#include "ncpost/express/parse.hpp"
#include "text.hpp"

namespace ncpost::express::detail {
namespace {

struct KeywordEntry {
  std::string_view spelling;  // lower case
  Keyword keyword;
};

constexpr std::array kKeywords = {
    KeywordEntry{"abstract", Keyword::Abstract},
    KeywordEntry{"aggregate", Keyword::Aggregate},
    KeywordEntry{"and", Keyword::And},
    KeywordEntry{"andor", Keyword::AndOr},
    KeywordEntry{"array", Keyword::Array},
    KeywordEntry{"as", Keyword::As},
    KeywordEntry{"bag", Keyword::Bag},
    KeywordEntry{"based_on", Keyword::BasedOn},
    KeywordEntry{"binary", Keyword::Binary},
    KeywordEntry{"boolean", Keyword::Boolean},
    KeywordEntry{"constant", Keyword::Constant},
    KeywordEntry{"derive", Keyword::Derive},
    KeywordEntry{"end_constant", Keyword::EndConstant},
    KeywordEntry{"end_entity", Keyword::EndEntity},
    KeywordEntry{"end_function", Keyword::EndFunction},
    KeywordEntry{"end_procedure", Keyword::EndProcedure},
    KeywordEntry{"end_rule", Keyword::EndRule},
    KeywordEntry{"end_schema", Keyword::EndSchema},
    KeywordEntry{"end_subtype_constraint", Keyword::EndSubtypeConstraint},
    KeywordEntry{"end_type", Keyword::EndType},
    KeywordEntry{"entity", Keyword::Entity},
    KeywordEntry{"enumeration", Keyword::Enumeration},
    KeywordEntry{"extensible", Keyword::Extensible},
    KeywordEntry{"fixed", Keyword::Fixed},
    KeywordEntry{"for", Keyword::For},
    KeywordEntry{"from", Keyword::From},
    KeywordEntry{"function", Keyword::Function},
    KeywordEntry{"generic", Keyword::Generic},
    KeywordEntry{"generic_entity", Keyword::GenericEntity},
    KeywordEntry{"integer", Keyword::Integer},
    KeywordEntry{"inverse", Keyword::Inverse},
    KeywordEntry{"list", Keyword::List},
    KeywordEntry{"logical", Keyword::Logical},
    KeywordEntry{"number", Keyword::Number},
    KeywordEntry{"of", Keyword::Of},
    KeywordEntry{"oneof", Keyword::OneOf},
    KeywordEntry{"optional", Keyword::Optional},
    KeywordEntry{"procedure", Keyword::Procedure},
    KeywordEntry{"real", Keyword::Real},
    KeywordEntry{"reference", Keyword::Reference},
    KeywordEntry{"renamed", Keyword::Renamed},
    KeywordEntry{"rule", Keyword::Rule},
    KeywordEntry{"schema", Keyword::Schema},
    KeywordEntry{"select", Keyword::Select},
    KeywordEntry{"self", Keyword::Self},
    KeywordEntry{"set", Keyword::Set},
    KeywordEntry{"string", Keyword::String},
    KeywordEntry{"subtype", Keyword::Subtype},
    KeywordEntry{"subtype_constraint", Keyword::SubtypeConstraint},
    KeywordEntry{"supertype", Keyword::Supertype},
    KeywordEntry{"type", Keyword::Type},
    KeywordEntry{"unique", Keyword::Unique},
    KeywordEntry{"use", Keyword::Use},
    KeywordEntry{"where", Keyword::Where},
    KeywordEntry{"with", Keyword::With},
};

// ISO 10303-11:2004, 7.2: reserved words (keywords, built-in constants, functions, procedures).
constexpr std::string_view kReservedWords[] = {
    "abs",
    "abstract",
    "acos",
    "aggregate",
    "alias",
    "and",
    "andor",
    "array",
    "as",
    "asin",
    "atan",
    "bag",
    "based_on",
    "begin",
    "binary",
    "blength",
    "boolean",
    "by",
    "case",
    "const_e",
    "constant",
    "cos",
    "derive",
    "div",
    "else",
    "end",
    "end_alias",
    "end_case",
    "end_constant",
    "end_entity",
    "end_function",
    "end_if",
    "end_local",
    "end_procedure",
    "end_repeat",
    "end_rule",
    "end_schema",
    "end_subtype_constraint",
    "end_type",
    "entity",
    "enumeration",
    "escape",
    "exists",
    "exp",
    "extensible",
    "false",
    "fixed",
    "for",
    "format",
    "from",
    "function",
    "generic",
    "generic_entity",
    "hibound",
    "hiindex",
    "if",
    "in",
    "insert",
    "integer",
    "inverse",
    "length",
    "like",
    "list",
    "lobound",
    "local",
    "log",
    "log10",
    "log2",
    "logical",
    "loindex",
    "mod",
    "not",
    "number",
    "nvl",
    "odd",
    "of",
    "oneof",
    "optional",
    "or",
    "otherwise",
    "pi",
    "procedure",
    "query",
    "real",
    "reference",
    "remove",
    "renamed",
    "repeat",
    "return",
    "rolesof",
    "rule",
    "schema",
    "select",
    "self",
    "set",
    "sin",
    "sizeof",
    "skip",
    "sqrt",
    "string",
    "subtype",
    "subtype_constraint",
    "supertype",
    "tan",
    "then",
    "to",
    "total_over",
    "true",
    "type",
    "typeof",
    "unique",
    "unknown",
    "until",
    "use",
    "usedin",
    "value",
    "value_in",
    "value_unique",
    "var",
    "where",
    "while",
    "with",
    "xor",
};

char lower(char c) noexcept {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}
bool is_letter(char c) noexcept {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) noexcept {
  return c >= '0' && c <= '9';
}
bool is_word_char(char c) noexcept {
  return is_letter(c) || is_digit(c) || c == '_';
}

Keyword lookup_keyword(std::string_view word) {
  static const std::unordered_map<std::string_view, Keyword> table = [] {
    std::unordered_map<std::string_view, Keyword> t;
    for (const auto& entry : kKeywords) t.emplace(entry.spelling, entry.keyword);
    return t;
  }();
  // The longest keyword is "end_subtype_constraint"; longer words cannot be keywords.
  std::array<char, 24> buffer{};
  if (word.size() > buffer.size()) return Keyword::None;
  std::transform(word.begin(), word.end(), buffer.begin(), lower);
  const auto it = table.find(std::string_view(buffer.data(), word.size()));
  return it == table.end() ? Keyword::None : it->second;
}

// Scans the source once, keeping line and column in step with the read position.
class Lexer {
 public:
  Lexer(std::string_view source, diag::DiagnosticList& diagnostics)
      : src_(source), diagnostics_(diagnostics) {}

  std::vector<Token> run() {
    std::vector<Token> tokens;
    tokens.reserve(src_.size() / 5 + 1);  // a measured average of ~6 bytes per token
    for (;;) {
      skip_blanks_and_remarks();
      if (at_end() || diagnostics_.full()) break;
      Token token = next_token();
      if (token.length > 0) tokens.push_back(token);
    }
    tokens.push_back(
        Token{TokenKind::End, Keyword::None, static_cast<std::uint32_t>(pos_), 0, line_, column()});
    return tokens;
  }

 private:
  [[nodiscard]] bool at_end() const noexcept { return pos_ >= src_.size(); }
  [[nodiscard]] char peek(std::size_t ahead = 0) const noexcept {
    return pos_ + ahead < src_.size() ? src_[pos_ + ahead] : '\0';
  }
  [[nodiscard]] std::uint32_t column() const noexcept {
    return static_cast<std::uint32_t>(pos_ - line_start_ + 1);
  }
  void advance() noexcept {
    if (src_[pos_] == '\n') {
      ++line_;
      line_start_ = pos_ + 1;
    }
    ++pos_;
  }

  void skip_blanks_and_remarks() {
    while (!at_end()) {
      const char c = peek();
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
        advance();
      } else if (c == '(' && peek(1) == '*') {
        skip_embedded_remark();
      } else if (c == '-' && peek(1) == '-') {
        while (!at_end() && peek() != '\n') advance();
      } else {
        return;
      }
    }
  }

  // Embedded remarks nest (ISO 10303-11, 7.1.6.1). A counter, not recursion, tracks the depth.
  void skip_embedded_remark() {
    const std::uint32_t start_line = line_;
    const std::uint32_t start_column = column();
    std::size_t depth = 0;
    while (!at_end()) {
      if (peek() == '(' && peek(1) == '*') {
        ++depth;
        advance();
        advance();
      } else if (peek() == '*' && peek(1) == ')') {
        advance();
        advance();
        if (--depth == 0) return;
      } else {
        advance();
      }
    }
    diagnostics_.add(diag::Code::ExpUnterminatedRemark, start_line, start_column,
                     "remark '(*' is not closed by '*)'");
  }

  Token start_token(TokenKind kind) const noexcept {
    return Token{kind, Keyword::None, static_cast<std::uint32_t>(pos_), 0, line_, column()};
  }
  void finish(Token& token) const noexcept {
    token.length = static_cast<std::uint32_t>(pos_ - token.offset);
  }

  Token next_token() {
    const char c = peek();
    if (is_letter(c)) return word();
    if (is_digit(c)) return number();
    if (c == '\'') return simple_string();
    if (c == '"') return encoded_string();
    if (c == '%') return binary();
    return punctuation();
  }

  Token word() {
    Token token = start_token(TokenKind::Identifier);
    while (!at_end() && is_word_char(peek())) advance();
    finish(token);
    token.keyword = lookup_keyword(src_.substr(token.offset, token.length));
    return token;
  }

  Token number() {
    Token token = start_token(TokenKind::Integer);
    while (is_digit(peek())) advance();
    // A real needs a digit-free '.' that is not the start of `..` (which EXPRESS does not have,
    // but a stray one should not swallow the next token).
    if (peek() == '.' && peek(1) != '.') {
      token.kind = TokenKind::Real;
      advance();
      while (is_digit(peek())) advance();
      if ((peek() == 'e' || peek() == 'E') &&
          (is_digit(peek(1)) || ((peek(1) == '+' || peek(1) == '-') && is_digit(peek(2))))) {
        advance();
        if (peek() == '+' || peek() == '-') advance();
        while (is_digit(peek())) advance();
      }
    }
    finish(token);
    return token;
  }

  Token simple_string() {
    Token token = start_token(TokenKind::String);
    advance();
    for (;;) {
      if (at_end()) {
        diagnostics_.add(diag::Code::ExpUnterminatedString, token.line, token.column,
                         "string literal is not closed by an apostrophe");
        break;
      }
      if (peek() == '\'') {
        advance();
        if (peek() != '\'') break;  // '' is an escaped apostrophe inside the literal
      }
      advance();
    }
    finish(token);
    return token;
  }

  Token encoded_string() {
    Token token = start_token(TokenKind::String);
    advance();
    while (!at_end() && peek() != '"') advance();
    if (at_end()) {
      diagnostics_.add(diag::Code::ExpUnterminatedString, token.line, token.column,
                       "encoded string literal is not closed by '\"'");
    } else {
      advance();
    }
    finish(token);
    return token;
  }

  Token binary() {
    Token token = start_token(TokenKind::Binary);
    advance();
    while (peek() == '0' || peek() == '1') advance();
    finish(token);
    return token;
  }

  Token punctuation() {
    Token token = start_token(TokenKind::Punct);
    // Longest match first: `:=:` and `:<>:` are instance comparison operators.
    static constexpr std::array<std::string_view, 10> kMulti = {
        ":<>:", ":=:", ":=", "<>", "<=", ">=", "<*", "**", "||", "|"};
    const std::string_view rest = src_.substr(pos_);
    for (const auto op : kMulti) {
      if (rest.substr(0, op.size()) == op) {
        for (std::size_t i = 0; i < op.size(); ++i) advance();
        finish(token);
        return token;
      }
    }
    static constexpr std::string_view kSingle = ";:,()[]{}=<>+-*/\\.?@";
    if (kSingle.find(peek()) != std::string_view::npos) {
      advance();
      finish(token);
      return token;
    }
    diagnostics_.add(diag::Code::ExpInvalidCharacter, line_, column(),
                     cat("character ", describe(peek()), " cannot start an EXPRESS token"));
    advance();
    return Token{};  // length 0: dropped by run()
  }

  static std::string describe(char c) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f) return std::string{'\'', c, '\''};
    static constexpr std::string_view kHex = "0123456789ABCDEF";
    return std::string{'0', 'x', kHex[byte >> 4], kHex[byte & 0xf]};
  }

  std::string_view src_;
  diag::DiagnosticList& diagnostics_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  std::uint32_t line_ = 1;
};

}  // namespace

std::string_view keyword_spelling(Keyword keyword) noexcept {
  static const std::array<std::string, kKeywords.size() + 1> upper = [] {
    std::array<std::string, kKeywords.size() + 1> names;
    for (const auto& entry : kKeywords) {
      std::string name(entry.spelling);
      for (char& ch : name)
        if (ch >= 'a' && ch <= 'z') ch = static_cast<char>(ch - 'a' + 'A');
      names[static_cast<std::size_t>(entry.keyword)] = std::move(name);
    }
    return names;
  }();
  return upper[static_cast<std::size_t>(keyword)];
}

bool is_reserved_word(std::string_view lower_case_word) noexcept {
  static const std::unordered_set<std::string_view> words(std::begin(kReservedWords),
                                                          std::end(kReservedWords));
  return words.count(lower_case_word) != 0;
}

std::string to_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = lower(c);
  return out;
}

std::vector<Token> tokenize(std::string_view source, diag::DiagnosticList& diagnostics) {
  return Lexer(source, diagnostics).run();
}

}  // namespace ncpost::express::detail

namespace ncpost::express {

bool can_name_a_declaration(std::string_view name) noexcept {
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (name.empty() || !letter(name.front())) return false;
  constexpr std::size_t kLongestReservedWord = 24;
  std::array<char, kLongestReservedWord> lowered{};
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (!letter(c) && !(c >= '0' && c <= '9') && c != '_') return false;
    if (i < lowered.size()) lowered[i] = detail::lower(c);
  }
  return name.size() > lowered.size() || !detail::is_reserved_word({lowered.data(), name.size()});
}

}  // namespace ncpost::express
