#include "records.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

namespace {

constexpr double kPowersOf10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                  1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                  1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

}  // namespace

std::optional<double> fast_decimal(std::string_view text) noexcept {
  // [sign] digits [. digits]: with at most 15 significant digits the digits are an exact
  // integer and 10^decimals an exact power, so one division rounds correctly (Clinger's fast
  // path) and equals from_chars. Anything else goes the slow way.
  const char* p = text.data();
  const char* const end = p + text.size();
  bool negative = false;
  if (p != end && (*p == '-' || *p == '+')) negative = *p++ == '-';
  std::uint64_t mantissa = 0;
  int digits = 0;
  int decimals = 0;
  bool point = false;
  bool any = false;
  for (; p != end; ++p) {
    const char c = *p;
    if (c >= '0' && c <= '9') {
      any = true;
      if (mantissa != 0 || c != '0') ++digits;
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(c - '0');
      decimals += point ? 1 : 0;
    } else if (c == '.' && !point) {
      point = true;
    } else {
      return std::nullopt;
    }
  }
  if (!any || digits > 15 || decimals > 22) return std::nullopt;
  const double value = static_cast<double>(mantissa) / kPowersOf10[decimals];
  return negative ? -value : value;
}

std::optional<double> parse_number(std::string_view text) noexcept {
  if (text.empty()) return std::nullopt;
  if (const auto fast = fast_decimal(text)) return fast;
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
  // Fields are a few bytes long: a plain loop is faster than a memchr call per field.
  std::size_t start = 0;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == ',') {
      out.push_back(trim(args.substr(start, i - start)));
      start = i + 1;
    }
  }
  out.push_back(trim(args.substr(start)));
}

std::size_t fast_numbers(std::string_view args, double* out, std::size_t max) noexcept {
  std::size_t n = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= args.size(); ++i) {
    if (i < args.size() && args[i] != ',') continue;
    if (n == max) return 0;
    std::string_view field = args.substr(start, i - start);
    if (!field.empty() && (field.front() == ' ' || field.back() == ' ')) field = trim(field);
    const auto v = fast_decimal(field);
    if (!v) return 0;
    out[n++] = *v;
    start = i + 1;
  }
  return n;
}

std::string format_number(double value) {
  char buffer[64];
  const bool plain = std::fabs(value) < 1e15;
  const int n = std::snprintf(buffer, sizeof buffer, plain ? "%.4f" : "%.6g", value);
  return std::string(buffer, static_cast<std::size_t>(std::clamp(n, 0, int{sizeof buffer} - 1)));
}

std::string_view unquote(std::string_view text) noexcept {
  text = trim(text);
  if (text.size() >= 2 && (text.front() == '\'' || text.front() == '"') &&
      text.back() == text.front())
    return text.substr(1, text.size() - 2);
  return text;
}

}  // namespace ncpost::cls::detail
