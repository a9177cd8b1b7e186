#pragma once
// The access log line, one JSON object per request, formatted directly: building a json object
// of twelve members for every request cost more than the rest of a cheap request's logging.
// Client-controlled text (the path, the profile id) may hold any bytes; invalid UTF-8 becomes
// U+FFFD, so the line is always valid JSON (a JSON library in strict mode throws there instead).

#include <cstdint>
#include <string>
#include <string_view>

namespace ncpost::server {

struct AccessRecord {
  std::string_view request_id;
  std::string_view remote;
  std::string_view method;
  std::string_view path;  // never the query string
  std::string_view route;
  std::string_view profile;  // empty: left out
  unsigned status = 0;
  std::uint64_t bytes_in = 0;
  std::uint64_t bytes_out = 0;
  double duration_ms = 0;
  bool complete = false;
};

// {"event":"access","request_id":…,"remote":…,"method":…,"path":…,"route":…,"status":…,
//  "bytes_in":…,"bytes_out":…,"duration_ms":…,["profile":…,]"complete":…}
[[nodiscard]] std::string access_line(const AccessRecord& record);

// `text` as a JSON string literal (quotes included) appended to `out`.
void append_json_string(std::string& out, std::string_view text);

}  // namespace ncpost::server
