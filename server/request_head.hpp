#pragma once
// What the session checks in a request's head beyond Beast's parser (RFC 9112), as pure
// functions over the parsed header or its bytes, so that tests/unit/server drives each case:
// framing that a smuggled request could hide behind (Transfer-Encoding), Host, obsolete line
// folding, and the absolute form of a target.

#include <boost/beast/http/fields.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/verb.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ncpost::server {

enum class HeadProblem : std::uint8_t {
  None,
  // RFC 9112 §6.3: Transfer-Encoding whose final coding is not chunked (or in HTTP/1.0): the
  // body's length cannot be known, so a server must answer 400 and close.
  TransferEncodingNotChunked,
  // A coding besides chunked (gzip, chunked): not one this server decodes; 501 and close.
  TransferCodingNotImplemented,
  // RFC 9112 §3.2: HTTP/1.1 without Host, or more than one Host: 400.
  HostMissing,
  HostRepeated,
  // RFC 9112 §5.2: obs-fold in a request: 400.
  ObsFold,
};

// The problems of a parsed header (not obs-fold, which needs the bytes: see has_obs_fold).
[[nodiscard]] HeadProblem check_head(
    const boost::beast::http::request_header<boost::beast::http::fields>& header);

// The status and the client-facing text of a problem.
[[nodiscard]] unsigned status_of(HeadProblem problem) noexcept;
[[nodiscard]] std::string_view describe(HeadProblem problem) noexcept;

// Whether header bytes fold a field onto a next line (CRLF followed by SP or HTAB). Called with
// the bytes the parser took, which always end with a whole line.
[[nodiscard]] bool has_obs_fold(std::string_view header_bytes) noexcept;

// The origin form (path and query) of an absolute-form target ("http://host:port/p?q" gives
// "/p?q", "http://host" gives "/"); nullopt when the target is not in absolute form.
[[nodiscard]] std::optional<std::string> origin_form(std::string_view target);

// The method as a metrics label: its name for the methods HTTP defines, "OTHER" for any other
// token, so that clients cannot make label values up.
[[nodiscard]] std::string_view method_label(boost::beast::http::verb method) noexcept;

}  // namespace ncpost::server
