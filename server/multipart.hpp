#pragma once
// A small, strict multipart/form-data parser (RFC 7578 over RFC 2046) for uploads held in
// memory. Strict means: CRLF line ends, every part has a Content-Disposition of form-data with
// a name, the closing delimiter is present. Parts are views into the body, so nothing is copied.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ncpost::server {

struct MultipartLimits {
  std::size_t max_parts = 16;
  std::size_t max_part_header_bytes = 8 * 1024;  // all header lines of one part together
  std::size_t max_boundary = 70;                 // RFC 2046
};

struct MultipartPart {
  std::string name;
  std::string filename;      // empty when the part has none
  std::string content_type;  // empty when the part has none
  std::string_view body;     // a view into the parsed body
};

struct MultipartResult {
  std::vector<MultipartPart> parts;
  std::string error;  // empty on success
  [[nodiscard]] bool ok() const noexcept { return error.empty(); }
  [[nodiscard]] const MultipartPart* find(std::string_view name) const noexcept;
};

// The boundary parameter of a multipart/form-data Content-Type; nullopt when the type is not
// multipart/form-data or has no valid boundary.
[[nodiscard]] std::optional<std::string> multipart_boundary(std::string_view content_type);
// True when the media type (before any ';') is multipart/form-data, case-insensitively.
[[nodiscard]] bool is_multipart(std::string_view content_type) noexcept;

[[nodiscard]] MultipartResult parse_multipart(std::string_view body, std::string_view boundary,
                                              const MultipartLimits& limits = {});

}  // namespace ncpost::server
