#include "access_log.hpp"

#include <cstdio>

namespace ncpost::server {
namespace {

// The length of the well-formed UTF-8 sequence at the start of `s`, or 0 (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF).
std::size_t utf8_sequence(std::string_view s) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char b0 = byte(0);
  std::size_t n = 0;
  unsigned char lo = 0x80;
  unsigned char hi = 0xBF;
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    n = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    n = 3;
    if (b0 == 0xE0) lo = 0xA0;
    if (b0 == 0xED) hi = 0x9F;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    n = 4;
    if (b0 == 0xF0) lo = 0x90;
    if (b0 == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (s.size() < n || byte(1) < lo || byte(1) > hi) return 0;
  for (std::size_t i = 2; i < n; ++i)
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  return n;
}

void append_number(std::string& out, std::uint64_t v) {
  char buffer[24];
  const int n = std::snprintf(buffer, sizeof buffer, "%llu", static_cast<unsigned long long>(v));
  out.append(buffer, static_cast<std::size_t>(n));
}

}  // namespace

void append_json_string(std::string& out, std::string_view text) {
  out += '"';
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      const std::size_t n = utf8_sequence(text.substr(i));
      if (n == 0) {
        out += "\\ufffd";
        ++i;
      } else {
        out.append(text.substr(i, n));
        i += n;
      }
      continue;
    }
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7F) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
    } else {
      out += static_cast<char>(c);
    }
    ++i;
  }
  out += '"';
}

std::string access_line(const AccessRecord& r) {
  std::string out;
  out.reserve(256 + r.path.size() + r.profile.size());
  out += R"({"event":"access","request_id":)";
  append_json_string(out, r.request_id);
  out += R"(,"remote":)";
  append_json_string(out, r.remote);
  out += R"(,"method":)";
  append_json_string(out, r.method);
  out += R"(,"path":)";
  append_json_string(out, r.path);
  out += R"(,"route":)";
  append_json_string(out, r.route);
  out += R"(,"status":)";
  append_number(out, r.status);
  out += R"(,"bytes_in":)";
  append_number(out, r.bytes_in);
  out += R"(,"bytes_out":)";
  append_number(out, r.bytes_out);
  char duration[32];
  std::snprintf(duration, sizeof duration, ",\"duration_ms\":%.3f", r.duration_ms);
  out += duration;
  if (!r.profile.empty()) {
    out += R"(,"profile":)";
    append_json_string(out, r.profile);
  }
  out += r.complete ? R"(,"complete":true})" : R"(,"complete":false})";
  return out;
}

}  // namespace ncpost::server
