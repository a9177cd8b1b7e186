#include "negotiation.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <optional>
#include <unordered_set>
#include <vector>

namespace ncpost::server {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

// Calls `each` with every element of a comma-separated header list, trimmed, empty ones skipped.
// Commas inside quoted strings (entity tags may hold them) do not split.
template <typename Each>
void for_each_element(std::string_view list, Each&& each) {
  std::size_t start = 0;
  bool quoted = false;
  for (std::size_t i = 0; i <= list.size(); ++i) {
    if (i < list.size() && list[i] == '"') quoted = !quoted;
    if (i == list.size() || (list[i] == ',' && !quoted)) {
      const std::string_view element = trim(list.substr(start, i - start));
      if (!element.empty()) each(element);
      start = i + 1;
    }
  }
}

// qvalue = ( "0" [ "." 0*3DIGIT ] ) / ( "1" [ "." 0*3("0") ] ), in thousandths.
std::optional<int> parse_qvalue(std::string_view s) {
  if (s.empty() || (s[0] != '0' && s[0] != '1')) return std::nullopt;
  int thousandths = (s[0] - '0') * 1000;
  if (s.size() == 1) return thousandths;
  if (s[1] != '.' || s.size() > 5) return std::nullopt;
  int scale = 100;
  for (const char c : s.substr(2)) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    thousandths += (c - '0') * scale;
    scale /= 10;
  }
  return thousandths <= 1000 ? std::optional<int>(thousandths) : std::nullopt;
}

struct MediaRange {
  std::string_view type;
  std::string_view subtype;
  int q = 1000;
};

std::optional<MediaRange> parse_media_range(std::string_view element) {
  MediaRange range;
  const auto semicolon = element.find(';');
  const std::string_view media = trim(element.substr(0, semicolon));
  const auto slash = media.find('/');
  if (slash == std::string_view::npos) return std::nullopt;
  range.type = trim(media.substr(0, slash));
  range.subtype = trim(media.substr(slash + 1));
  if (range.type.empty() || range.subtype.empty()) return std::nullopt;
  std::string_view parameters =
      semicolon == std::string_view::npos ? std::string_view{} : element.substr(semicolon + 1);
  while (!parameters.empty()) {
    const auto next = parameters.find(';');
    const std::string_view parameter = trim(parameters.substr(0, next));
    parameters = next == std::string_view::npos ? std::string_view{} : parameters.substr(next + 1);
    const auto eq = parameter.find('=');
    if (eq == std::string_view::npos || !iequals(trim(parameter.substr(0, eq)), "q")) continue;
    const auto q = parse_qvalue(trim(parameter.substr(eq + 1)));
    if (!q) return std::nullopt;
    range.q = *q;
  }
  return range;
}

// The q a media type gets from the ranges and how specific the deciding range was
// (3 exact, 2 type/*, 1 */*, 0 none).
struct Preference {
  int q = 0;
  int specificity = 0;
};

Preference preference_for(const std::vector<MediaRange>& ranges, std::string_view type,
                          std::string_view subtype) {
  Preference best;
  for (const MediaRange& range : ranges) {
    int specificity = 0;
    if (iequals(range.type, type) && iequals(range.subtype, subtype))
      specificity = 3;
    else if (iequals(range.type, type) && range.subtype == "*")
      specificity = 2;
    else if (range.type == "*" && range.subtype == "*")
      specificity = 1;
    if (specificity > best.specificity) best = {range.q, specificity};
  }
  return best;
}

std::string_view opaque_tag(std::string_view tag) {
  if (tag.size() >= 2 && tag[0] == 'W' && tag[1] == '/') tag.remove_prefix(2);
  return tag;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The length of the UTF-8 sequence starting at s[i], or 0 when it is not well formed.
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto lead = static_cast<unsigned char>(s[i]);
  std::size_t length = 0;
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF)
    length = 2;
  else if (lead >= 0xE0 && lead <= 0xEF)
    length = 3;
  else if (lead >= 0xF0 && lead <= 0xF4)
    length = 4;
  else
    return 0;
  if (i + length > s.size()) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
  return length;
}

// The upload's base name without its extension.
std::string_view stem_of(std::string_view name) {
  const auto slash = name.find_last_of("/\\");
  if (slash != std::string_view::npos) name.remove_prefix(slash + 1);
  if (const auto dot = name.rfind('.'); dot != std::string_view::npos && dot > 0)
    name = name.substr(0, dot);
  return name;
}

// The stem as UTF-8 a download may carry: control characters, quotes and malformed bytes
// become '_'.
std::string utf8_file_stem(std::string_view upload_name) {
  const std::string_view stem = stem_of(upload_name);
  std::string safe;
  for (std::size_t i = 0; i < stem.size();) {
    const std::size_t length = utf8_sequence_length(stem, i);
    const auto c = static_cast<unsigned char>(stem[i]);
    if (length == 0 || (length == 1 && (c < 0x20 || c == 0x7F || c == '"'))) {
      safe += '_';
      ++i;
      continue;
    }
    safe.append(stem.substr(i, length));
    i += length;
  }
  return safe;
}

bool is_attr_char(unsigned char c) {
  return std::isalnum(c) ||
         std::string_view("!#$&+-.^_`|~").find(static_cast<char>(c)) != std::string_view::npos;
}

}  // namespace

std::size_t accept_choice(std::string_view accept,
                          std::initializer_list<std::string_view> offered) {
  std::vector<MediaRange> ranges;
  for_each_element(accept, [&ranges](std::string_view element) {
    if (auto range = parse_media_range(element)) ranges.push_back(*range);
  });
  std::size_t chosen = 0;
  Preference best{0, -1};
  std::size_t k = 0;
  for (const std::string_view type : offered) {
    const auto slash = type.find('/');
    const Preference p =
        ranges.empty() ? Preference{}
                       : preference_for(ranges, type.substr(0, slash), type.substr(slash + 1));
    if (p.q > best.q || (p.q == best.q && p.q > 0 && p.specificity > best.specificity)) {
      best = p;
      chosen = k;
    }
    ++k;
  }
  return chosen;
}

bool accept_prefers_json(std::string_view accept) {
  return accept_choice(accept, {"text/plain", "application/json"}) == 1;
}

bool none_match_matches(std::string_view if_none_match, std::string_view etag) {
  if (trim(if_none_match) == "*") return true;
  bool matched = false;
  for_each_element(if_none_match, [&](std::string_view tag) {
    if (opaque_tag(tag) == opaque_tag(etag)) matched = true;
  });
  return matched;
}

std::string ascii_file_stem(std::string_view upload_name) {
  const std::string_view stem = stem_of(upload_name);
  std::string safe;
  for (std::size_t i = 0; i < stem.size();) {
    const auto c = static_cast<unsigned char>(stem[i]);
    const std::size_t length = std::max<std::size_t>(1, utf8_sequence_length(stem, i));
    // One '_' per character, not per byte: "Ø" is one character of two bytes.
    safe += (c < 0x80 && (std::isalnum(c) || c == '-' || c == '_' || c == '.')) ? stem[i] : '_';
    i += length;
  }
  return safe.empty() ? "program" : safe;
}

std::string attachment_disposition(std::string_view upload_name, std::string_view extension) {
  const std::string ascii = ascii_file_stem(upload_name) + std::string(extension);
  std::string utf8 = utf8_file_stem(upload_name);
  std::string disposition = "attachment; filename=\"" + ascii + "\"";
  if (utf8.empty()) return disposition;
  utf8 += extension;
  if (utf8 == ascii) return disposition;
  static constexpr char kHex[] = "0123456789ABCDEF";
  disposition += "; filename*=UTF-8''";
  for (const char ch : utf8) {
    const auto c = static_cast<unsigned char>(ch);
    if (is_attr_char(c)) {
      disposition += ch;
    } else {
      disposition += '%';
      disposition += kHex[c >> 4];
      disposition += kHex[c & 0xF];
    }
  }
  return disposition;
}

std::string percent_decode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && i + 2 < s.size() && hex_value(s[i + 1]) >= 0 &&
               hex_value(s[i + 2]) >= 0) {
      out += static_cast<char>(hex_value(s[i + 1]) * 16 + hex_value(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

std::string repeated_query_parameter(std::string_view target) {
  const auto q = target.find('?');
  if (q == std::string_view::npos) return {};
  std::string_view query = target.substr(q + 1);
  std::unordered_set<std::string> seen;
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    if (pair.empty()) continue;
    std::string name = percent_decode(pair.substr(0, pair.find('=')));
    if (!seen.insert(name).second) return name;
  }
  return {};
}

}  // namespace ncpost::server
