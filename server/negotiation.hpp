// What a request asks for in its headers, read the way RFC 9110 says: media ranges with
// q-values in Accept, entity tags in If-None-Match, and the download name of an answer
// (RFC 6266). Pure functions of header text, so that they are unit-tested without a server.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>

namespace ncpost::server {

// Whether an Accept header prefers application/json to text/plain. Absent or empty: text.
// Each candidate takes the q of its most specific matching range (type/subtype, then type/*,
// then */*); JSON wins when its q is higher, or equal and more specific. Media types compare
// case-insensitively; a range with a malformed q is ignored.
[[nodiscard]] bool accept_prefers_json(std::string_view accept);

// Which of the `offered` media types ("type/subtype", the default first) an Accept header
// prefers, by the same rules: the highest q, then the most specific range; the earlier one on a
// tie, and the first when none is acceptable or the header is absent.
[[nodiscard]] std::size_t accept_choice(std::string_view accept,
                                        std::initializer_list<std::string_view> offered);

// If-None-Match against the current entity tag with the weak comparison of RFC 9110 §13.1.2:
// `*`, a list of tags, and W/ prefixes on either side.
[[nodiscard]] bool none_match_matches(std::string_view if_none_match, std::string_view etag);

// Content-Disposition for a download called `stem + extension`, where the stem comes from the
// client's upload name (any path and extension removed): an ASCII `filename` fallback and the
// UTF-8 name as `filename*` when the two differ.
[[nodiscard]] std::string attachment_disposition(std::string_view upload_name,
                                                 std::string_view extension);

// The ASCII stem that attachment_disposition falls back to ("program" when nothing is left).
[[nodiscard]] std::string ascii_file_stem(std::string_view upload_name);

// A query string's text decoded: %XX escapes and '+' for a space.
[[nodiscard]] std::string percent_decode(std::string_view s);

// The first query parameter of a target that is given more than once, or empty.
[[nodiscard]] std::string repeated_query_parameter(std::string_view target);

}  // namespace ncpost::server
