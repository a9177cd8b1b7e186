#include "request_head.hpp"

#include <boost/beast/core/string.hpp>
#include <boost/beast/http/rfc7230.hpp>

namespace ncpost::server {

namespace http = boost::beast::http;

HeadProblem check_head(const http::request_header<http::fields>& header) {
  // Every coding of every Transfer-Encoding field, in order.
  std::size_t codings = 0;
  bool chunked_last = false;
  bool other_coding = false;
  for (auto [field, end] = header.equal_range(http::field::transfer_encoding); field != end;
       ++field) {
    for (const auto coding : http::token_list{field->value()}) {
      ++codings;
      chunked_last = boost::beast::iequals(coding, "chunked");
      if (!chunked_last) other_coding = true;
    }
    if (field->value().find_first_not_of(" \t,") == std::string_view::npos) {
      ++codings;  // an empty value is no coding this server knows either
      chunked_last = false;
    }
  }
  if (codings > 0) {
    if (!chunked_last || header.version() < 11) return HeadProblem::TransferEncodingNotChunked;
    if (other_coding) return HeadProblem::TransferCodingNotImplemented;
  }
  const auto hosts = header.count(http::field::host);
  if (hosts > 1) return HeadProblem::HostRepeated;
  if (hosts == 0 && header.version() >= 11) return HeadProblem::HostMissing;
  return HeadProblem::None;
}

unsigned status_of(HeadProblem problem) noexcept {
  return problem == HeadProblem::TransferCodingNotImplemented ? 501 : 400;
}

std::string_view describe(HeadProblem problem) noexcept {
  switch (problem) {
    case HeadProblem::None:
      return "";
    case HeadProblem::TransferEncodingNotChunked:
      return "Transfer-Encoding must end in chunked (RFC 9112 section 6.3); the body's length "
             "cannot be known";
    case HeadProblem::TransferCodingNotImplemented:
      return "only the chunked transfer coding is supported";
    case HeadProblem::HostMissing:
      return "an HTTP/1.1 request needs a Host header field (RFC 9112 section 3.2)";
    case HeadProblem::HostRepeated:
      return "more than one Host header field (RFC 9112 section 3.2)";
    case HeadProblem::ObsFold:
      return "a header field folded onto a second line (obs-fold, RFC 9112 section 5.2)";
  }
  return "";
}

bool has_obs_fold(std::string_view bytes) noexcept {
  for (auto at = bytes.find("\r\n"); at != std::string_view::npos; at = bytes.find("\r\n", at + 2))
    if (at + 2 < bytes.size() && (bytes[at + 2] == ' ' || bytes[at + 2] == '\t')) return true;
  return false;
}

std::optional<std::string> origin_form(std::string_view target) {
  std::size_t scheme = 0;
  if (target.size() >= 7 && boost::beast::iequals(target.substr(0, 7), "http://"))
    scheme = 7;
  else if (target.size() >= 8 && boost::beast::iequals(target.substr(0, 8), "https://"))
    scheme = 8;
  else
    return std::nullopt;
  const auto rest = target.substr(scheme);
  const auto path = rest.find_first_of("/?");
  if (path == std::string_view::npos) return std::string("/");
  if (rest[path] == '?') return "/" + std::string(rest.substr(path));
  return std::string(rest.substr(path));
}

std::string_view method_label(http::verb method) noexcept {
  return method == http::verb::unknown ? std::string_view("OTHER") : http::to_string(method);
}

}  // namespace ncpost::server
