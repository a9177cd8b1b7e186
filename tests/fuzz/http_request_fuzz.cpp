// libFuzzer target for the HTTP request path without a socket: the bytes are what a client
// sent on one connection. They go through what the session (server/session.cpp) does with them,
// in the same order: Beast's request parser with the server's header limit, the head checks
// (obs-fold in the bytes taken, check_head: framing, Host), the absolute-form target, the
// router, the repeated-parameter check, then the route's handler through a recording Exchange,
// for up to four pipelined requests while the connection would stay open. Admin routes need a
// token (the seeds hold it); the profiles are the read-only built-ins, so nothing is written.
// Any bytes must give answers, never a crash, a hang, an uncaught exception or a sanitizer
// report; each handler answers exactly once, ends any stream it begins, and every problem is
// RFC 9457 JSON with the status of its response.

#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/http/parser.hpp>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "handlers.hpp"
#include "multipart.hpp"
#include "ncpost/pipeline/process.hpp"
#include "negotiation.hpp"
#include "request_head.hpp"

namespace server = ncpost::server;
namespace http = server::http;

namespace {

class RecordingExchange final : public server::Exchange {
 public:
  void respond(server::Response r) override {
    if (answered) __builtin_trap();  // a handler answers once
    answered = true;
    check_problem(r);
  }
  bool begin_stream(server::StreamHead head) override {
    if (answered) __builtin_trap();
    answered = streamed = true;
    (void)head;
    return true;
  }
  bool write(std::string_view piece) override {
    if (!streamed || ended) __builtin_trap();
    bytes += piece.size();
    return true;
  }
  void end_stream(bool, http::fields) override {
    if (!streamed || ended) __builtin_trap();
    ended = true;
  }
  [[nodiscard]] const std::atomic<bool>* cancel_flag() const noexcept override { return &cancel; }
  [[nodiscard]] bool timed_out() const noexcept override { return false; }

  static void check_problem(const server::Response& r) {
    if (r[http::field::content_type] != "application/problem+json") return;
    const auto problem = nlohmann::json::parse(r.body(), nullptr, false);
    if (problem.is_discarded() || !problem.is_object() ||
        problem.value("status", 0u) != r.result_int())
      __builtin_trap();
    if (r.result_int() < 400) __builtin_trap();
  }

  std::atomic<bool> cancel{false};
  bool answered = false, streamed = false, ended = false;
  std::size_t bytes = 0;
};

server::Services& services() {
  static server::Services* s = [] {
    // The source tree has the installed data's layout (stylesheets, schemas, web, openapi).
    ::setenv("NCPOST_DATA_DIR", NCPOST_SOURCE_DIR, 0);
    ncpost::pipeline::initialise_process();
    auto* out = new server::Services;
    out->profiles = new ncpost::pipeline::Profiles;
    out->schemas = new ncpost::pipeline::Schemas;
    out->metrics = new server::Metrics;
    out->admin_token = "fuzz-admin-token";
    out->web_root = std::string(NCPOST_SOURCE_DIR) + "/web";
    out->openapi_file = std::string(NCPOST_SOURCE_DIR) + "/openapi/openapi.yaml";
    out->engine_version = "fuzz";
    return out;
  }();
  return *s;
}

// One request from the front of `bytes`; false when the connection would end here (an error
// answered and closed, a request not complete, Connection: close).
bool one_request(std::string_view& bytes) {
  auto& s = services();
  http::request_parser<http::string_body> parser;
  parser.header_limit(s.config.max_header);
  parser.body_limit(std::uint64_t{1} << 20);
  boost::beast::error_code ec;
  std::size_t taken = 0;
  while (!bytes.empty() && !parser.is_header_done()) {
    const std::size_t n = parser.put(boost::asio::buffer(bytes.data(), bytes.size()), ec);
    if (server::has_obs_fold(bytes.substr(0, n))) return false;  // 400, closed
    bytes.remove_prefix(n);
    taken += n;
    if (ec == http::error::need_more) ec = {};
    if (ec || n == 0) break;
  }
  if (ec || !parser.is_header_done() || taken > s.config.max_header) return false;
  auto& header = parser.get();
  if (server::check_head(header) != server::HeadProblem::None) return false;  // 400/501, closed
  if (auto origin = server::origin_form(header.target())) header.target(*origin);
  while (!bytes.empty() && !parser.is_done()) {
    const std::size_t n = parser.put(boost::asio::buffer(bytes.data(), bytes.size()), ec);
    bytes.remove_prefix(n);
    if (ec == http::error::need_more) ec = {};
    if (ec || n == 0) break;
  }
  if (!parser.is_done() && !ec) parser.put_eof(ec);
  if (ec || !parser.is_done()) return false;
  server::Request request = parser.release();
  const bool keep_alive = request.keep_alive();
  server::RouteMatch match = server::match_route(request.method(), request.target());
  if (match.route == nullptr) {
    if (match.status != 404 && match.status != 405) __builtin_trap();
    return keep_alive;
  }
  if (!server::repeated_query_parameter(request.target()).empty()) return keep_alive;
  RecordingExchange exchange;
  exchange.path_id = std::move(match.id);
  exchange.received = std::chrono::steady_clock::now();
  match.route->handler(request, s, exchange);
  if (!exchange.answered || (exchange.streamed && !exchange.ended)) __builtin_trap();
  return keep_alive;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (int i = 0; i < 4 && !bytes.empty(); ++i)
    if (!one_request(bytes)) break;
  return 0;
}
