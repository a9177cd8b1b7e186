#include "records.hpp"

#include <cmath>

namespace ncpost::cls::detail {

Position Record::at(std::size_t offset) const noexcept {
  const std::vector<Segment>& s = *segments;
  std::size_t i = s.size() - 1;
  while (i > 0 && s[i].offset > offset) --i;
  return {s[i].line, s[i].column + static_cast<std::uint32_t>(offset - s[i].offset)};
}

std::string_view trim(std::string_view s) noexcept {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool is_word(std::string_view text, std::string_view upper) noexcept {
  if (text.size() != upper.size()) return false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    if (c != upper[i]) return false;
  }
  return true;
}

std::optional<double> parse_number(std::string_view text) noexcept {
  if (text.empty()) return std::nullopt;
  bool negative = false;
  if (text.front() == '+' || text.front() == '-') {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  if (text.empty() || text.front() == '+' || text.front() == '-') return std::nullopt;
  // Fortran's D exponent (1.5D-3) is read as E; anything else from_chars refuses.
  char buffer[64];
  std::string_view digits = text;
  if (const std::size_t d = text.find_first_of("dD"); d != std::string_view::npos) {
    if (text.size() >= sizeof buffer) return std::nullopt;
    text.copy(buffer, text.size());
    buffer[d] = 'E';
    digits = std::string_view(buffer, text.size());
  }
  double value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value))
    return std::nullopt;
  return negative ? -value : value;
}

void split_fields(std::string_view args, std::vector<std::string_view>& out) {
  out.clear();
  while (true) {
    const std::size_t comma = args.find(',');
    out.push_back(trim(args.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    args.remove_prefix(comma + 1);
  }
}

std::string_view unquote(std::string_view text) noexcept {
  text = trim(text);
  if (text.size() >= 2 && (text.front() == '\'' || text.front() == '"') &&
      text.back() == text.front())
    return text.substr(1, text.size() - 2);
  return text;
}

}  // namespace ncpost::cls::detail
