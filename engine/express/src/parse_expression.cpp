// Expressions (DERIVE formulas, WHERE rules, bounds, constant values) are scanned, not parsed:
// the scanner checks bracket balance with a counter (hostile nesting cannot grow the stack) and
// produces normalised text. Nothing in ncpost evaluates EXPRESS expressions; they are carried
// into the EXPRESS-X output and shown in messages.

#include <charconv>
#include <vector>

#include "parser.hpp"
#include "text.hpp"

namespace ncpost::express::detail {
namespace {

bool is_opening(std::string_view punct) noexcept {
  return punct == "(" || punct == "[" || punct == "{";
}
bool is_closing(std::string_view punct) noexcept {
  return punct == ")" || punct == "]" || punct == "}";
}
char matching_open(char close) noexcept {
  return close == ')' ? '(' : close == ']' ? '[' : '{';
}

// Words that act as infix/prefix operators: keep a space before a following '(' or '['.
bool is_operator_word(std::string_view lower) noexcept {
  return lower == "and" || lower == "or" || lower == "not" || lower == "xor" || lower == "in" ||
         lower == "like" || lower == "mod" || lower == "div" || lower == "andor" ||
         lower == "oneof";
}

// Joins tokens with single spaces, except where EXPRESS is conventionally written tight:
// around `\` and `.` in `SELF\entity.attribute`, inside brackets, before `,`, and between a
// function name and its argument list.
class ExpressionText {
 public:
  void append(TokenKind kind, std::string_view spelling) {
    std::string word;
    if (kind == TokenKind::Identifier) {
      word = to_lower(spelling);
      if (is_reserved_word(word))
        for (char& c : word)
          if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    } else {
      word = std::string(spelling);
    }
    if (!text_.empty() && needs_space(kind, spelling)) text_ += ' ';
    text_ += word;
    previous_kind_ = kind;
    previous_ = word;
  }
  [[nodiscard]] std::string take() && { return std::move(text_); }

 private:
  [[nodiscard]] bool needs_space(TokenKind kind, std::string_view spelling) const {
    const bool punct = kind == TokenKind::Punct;
    if (punct && (spelling == "," || spelling == ")" || spelling == "]" || spelling == "}" ||
                  spelling == "." || spelling == "\\"))
      return false;
    if (previous_kind_ == TokenKind::Punct &&
        (previous_ == "(" || previous_ == "[" || previous_ == "{" || previous_ == "." ||
         previous_ == "\\"))
      return false;
    if (punct && (spelling == "(" || spelling == "[")) {
      if (previous_kind_ == TokenKind::Identifier) return is_operator_word(to_lower(previous_));
      if (previous_ == ")" || previous_ == "]") return false;
    }
    return true;
  }

  std::string text_;
  TokenKind previous_kind_ = TokenKind::End;
  std::string previous_;
};

}  // namespace

std::optional<Expression> Parser::parse_expression(std::string_view stops) {
  const Token& first = peek();
  ExpressionText text_out;
  std::vector<char> open;  // the brackets currently open, innermost last
  bool empty = true;
  for (;;) {
    const Token& token = peek();
    const std::string_view spelling = text(token);
    const bool punct = token.kind == TokenKind::Punct;
    if (open.empty() && punct && spelling.size() == 1 &&
        stops.find(spelling[0]) != std::string_view::npos)
      break;
    if (at_block_boundary()) {
      if (!open.empty()) {
        report(diag::Code::ExpUnbalanced, first,
               cat("'", std::string_view(&open.back(), 1), "' is not closed in this expression"));
      } else {
        syntax_error("end of expression");
      }
      return std::nullopt;
    }
    if (punct && is_opening(spelling)) {
      if (open.size() >= limits_.max_nesting_depth) {
        report(diag::Code::ExpNestingTooDeep, token,
               cat("expression nested deeper than ", std::to_string(limits_.max_nesting_depth)));
        return std::nullopt;
      }
      open.push_back(spelling[0]);
    } else if (punct && is_closing(spelling)) {
      if (open.empty() || open.back() != matching_open(spelling[0])) {
        report(diag::Code::ExpUnbalanced, token,
               cat("'", spelling, "' does not close an open bracket"));
        return std::nullopt;
      }
      open.pop_back();
    } else if (punct && spelling == ";") {
      // ';' is never inside an expression: a bracket was left open or the context is wrong.
      if (!open.empty()) {
        report(diag::Code::ExpUnbalanced, token,
               cat("'", std::string_view(&open.back(), 1), "' is not closed before ';'"));
      } else {
        syntax_error("end of expression");
      }
      return std::nullopt;
    }
    text_out.append(token.kind, spelling);
    empty = false;
    take();
  }
  if (empty) {
    syntax_error("an expression");
    return std::nullopt;
  }
  return Expression{std::move(text_out).take(), pos(first)};
}

std::optional<Bound> Parser::parse_bound(std::string_view stops) {
  const Token& first = peek();
  const bool single_token = [&] {
    const Token& after = peek(1);
    return after.kind == TokenKind::Punct && text(after).size() == 1 &&
           stops.find(text(after)[0]) != std::string_view::npos;
  }();
  auto expression = parse_expression(stops);
  if (!expression) return std::nullopt;
  Bound bound{std::move(expression->text), std::nullopt};
  if (single_token && first.kind == TokenKind::Integer) {
    std::int64_t value = 0;
    const std::string_view digits = text(first);
    const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (result.ec == std::errc{}) bound.value = value;
  }
  return bound;
}

}  // namespace ncpost::express::detail
