// libFuzzer target for the server's multipart/form-data parser (server/multipart.cpp) and the
// upload it gives a job route (take_upload): the input's first line is the request's
// Content-Type, the rest its body. Any bytes must give parts or one error, never a crash, a hang
// or a sanitizer report; a successful parse keeps to its limits, every part has a name and its
// body is a view into the request body; take_upload answers an upload or a 400 problem.

#include <cstddef>
#include <cstdint>
#include <string>

#include "handlers.hpp"
#include "multipart.hpp"

namespace server = ncpost::server;

namespace {

void check_parse(std::string_view body, std::string_view boundary) {
  server::MultipartLimits limits;
  const auto result = server::parse_multipart(body, boundary, limits);
  if (!result.ok()) {
    if (!result.parts.empty() && result.parts.size() > limits.max_parts) __builtin_trap();
    return;
  }
  if (result.parts.size() > limits.max_parts) __builtin_trap();
  for (const auto& part : result.parts) {
    if (part.name.empty()) __builtin_trap();
    if (part.body.data() < body.data() ||
        part.body.data() + part.body.size() > body.data() + body.size())
      __builtin_trap();
  }
  (void)result.find("file");
}

void check_upload(std::string_view content_type, std::string_view body, server::FileParts parts) {
  server::Request request{server::http::verb::post, "/v1/posts", 11};
  request.set(server::http::field::content_type, content_type);
  request.body() = std::string(body);
  request.prepare_payload();
  std::optional<server::Response> error;
  const auto upload = server::take_upload(request, error, {}, parts);
  if (upload.has_value() == error.has_value()) __builtin_trap();
  if (error && error->result_int() != 400) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t eol = input.find('\n');
  const std::string_view content_type = input.substr(0, std::min<std::size_t>(eol, 512));
  const std::string_view body =
      eol == std::string_view::npos ? std::string_view{} : input.substr(eol + 1);
  (void)server::is_multipart(content_type);
  if (const auto boundary = server::multipart_boundary(content_type)) check_parse(body, *boundary);
  // A boundary that the header did not name: the body's own first line, as a client might mean.
  if (body.starts_with("--")) {
    const std::size_t end = body.find("\r\n");
    if (end != std::string_view::npos && end > 2) check_parse(body, body.substr(2, end - 2));
  }
  check_upload(content_type, body, server::FileParts::One);
  check_upload(content_type, body, server::FileParts::Several);
  return 0;
}
