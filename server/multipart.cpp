#include "multipart.hpp"

#include <algorithm>
#include <cctype>

namespace ncpost::server {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// One `; key=value` parameter of a header value, quoted-string or token; nullopt when absent.
std::optional<std::string> parameter(std::string_view value, std::string_view key) {
  std::size_t pos = value.find(';');
  while (pos != std::string_view::npos) {
    std::string_view rest = trim(value.substr(pos + 1));
    const auto eq = rest.find('=');
    if (eq == std::string_view::npos) return std::nullopt;
    const std::string k = lower(trim(rest.substr(0, eq)));
    std::string_view v = trim(rest.substr(eq + 1));
    std::string decoded;
    std::size_t consumed = 0;
    if (!v.empty() && v.front() == '"') {
      std::size_t i = 1;
      for (; i < v.size() && v[i] != '"'; ++i) {
        if (v[i] == '\\' && i + 1 < v.size()) ++i;
        decoded += v[i];
      }
      if (i >= v.size()) return std::nullopt;  // unterminated quoted string
      consumed = i + 1;
    } else {
      const auto semi = v.find(';');
      decoded = std::string(trim(v.substr(0, semi)));
      consumed = semi == std::string_view::npos ? v.size() : semi;
    }
    if (k == key) return decoded;
    const std::string_view after = v.substr(consumed);
    const auto next = after.find(';');
    if (next == std::string_view::npos) return std::nullopt;
    value = after.substr(next);
    pos = 0;
  }
  return std::nullopt;
}

}  // namespace

const MultipartPart* MultipartResult::find(std::string_view name) const noexcept {
  for (const auto& part : parts)
    if (part.name == name) return &part;
  return nullptr;
}

bool is_multipart(std::string_view content_type) noexcept {
  const auto semi = content_type.find(';');
  const std::string_view type = trim(content_type.substr(0, semi));
  constexpr std::string_view want = "multipart/form-data";
  if (type.size() != want.size()) return false;
  for (std::size_t i = 0; i < want.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(type[i])) != want[i]) return false;
  return true;
}

std::optional<std::string> multipart_boundary(std::string_view content_type) {
  if (!is_multipart(content_type)) return std::nullopt;
  auto boundary = parameter(content_type, "boundary");
  if (!boundary || boundary->empty() || boundary->size() > 70) return std::nullopt;
  return boundary;
}

MultipartResult parse_multipart(std::string_view body, std::string_view boundary,
                                const MultipartLimits& limits) {
  MultipartResult result;
  const auto fail = [&](std::string message) {
    result.parts.clear();
    result.error = std::move(message);
    return result;
  };
  if (boundary.empty() || boundary.size() > limits.max_boundary)
    return fail("multipart boundary is empty or longer than " +
                std::to_string(limits.max_boundary) + " characters");
  const std::string first = "--" + std::string(boundary);
  const std::string delimiter = "\r\n--" + std::string(boundary);

  // The preamble (before the first delimiter) is ignored, as RFC 2046 says.
  std::size_t pos;
  if (body.substr(0, first.size()) == first) {
    pos = first.size();
  } else {
    const auto at = body.find(delimiter);
    if (at == std::string_view::npos) return fail("multipart body has no opening boundary");
    pos = at + delimiter.size();
  }
  for (;;) {
    // After a delimiter: "--" closes the body; otherwise optional whitespace and CRLF.
    if (body.substr(pos, 2) == "--") return result;
    while (pos < body.size() && (body[pos] == ' ' || body[pos] == '\t')) ++pos;
    if (body.substr(pos, 2) != "\r\n") return fail("multipart boundary not followed by CRLF");
    pos += 2;
    if (result.parts.size() == limits.max_parts)
      return fail("more than " + std::to_string(limits.max_parts) + " multipart parts");

    const auto header_end = body.find("\r\n\r\n", pos);
    const bool empty_headers = body.substr(pos, 2) == "\r\n";
    const std::size_t headers_size = empty_headers ? 0 : header_end - pos;
    if (!empty_headers && header_end == std::string_view::npos)
      return fail("multipart part headers not terminated by an empty line");
    if (headers_size > limits.max_part_header_bytes)
      return fail("multipart part headers longer than " +
                  std::to_string(limits.max_part_header_bytes) + " bytes");
    MultipartPart part;
    bool disposition = false;
    std::string_view headers = body.substr(pos, headers_size);
    while (!headers.empty()) {
      const auto eol = headers.find("\r\n");
      const std::string_view line = headers.substr(0, eol);
      headers = eol == std::string_view::npos ? std::string_view{} : headers.substr(eol + 2);
      const auto colon = line.find(':');
      if (colon == std::string_view::npos || line.find_first_of("\r\n") != std::string_view::npos)
        return fail("malformed multipart part header line");
      const std::string name = lower(trim(line.substr(0, colon)));
      const std::string_view value = trim(line.substr(colon + 1));
      if (name == "content-disposition") {
        const auto semi = value.find(';');
        if (lower(trim(value.substr(0, semi))) != "form-data")
          return fail("multipart part disposition is not form-data");
        auto n = parameter(value, "name");
        if (!n || n->empty()) return fail("multipart part without a name");
        part.name = std::move(*n);
        part.filename = parameter(value, "filename").value_or("");
        disposition = true;
      } else if (name == "content-type") {
        part.content_type = std::string(value);
      }
      // Other part headers (Content-Transfer-Encoding is deprecated by RFC 7578) are ignored.
    }
    if (!disposition) return fail("multipart part without Content-Disposition");
    pos += empty_headers ? 2 : headers_size + 4;
    const auto end = body.find(delimiter, pos);
    if (end == std::string_view::npos) return fail("multipart body has no closing boundary");
    part.body = body.substr(pos, end - pos);
    result.parts.push_back(std::move(part));
    pos = end + delimiter.size();
  }
}

}  // namespace ncpost::server
