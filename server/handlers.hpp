#pragma once
// The request handlers: each is a function of the request that produces its response through
// an Exchange, with no I/O of its own. The session (session.cpp) decides where a handler runs
// (on the IO thread for cheap routes, on the worker pool for pipeline work) and carries what it
// produces to the socket. Unit tests call handlers with a recording Exchange.

#include <atomic>
#include <boost/beast/http.hpp>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config.hpp"
#include "metrics.hpp"
#include "ncpost/pipeline/block_map.hpp"
#include "ncpost/pipeline/job.hpp"
#include "ncpost/pipeline/profiles.hpp"
#include "upload.hpp"

namespace ncpost::server {

namespace http = boost::beast::http;
using Request = http::request<http::string_body>;
using Response = http::response<http::string_body>;
using StreamHead = http::response<http::empty_body>;

// What every handler may use. Shared by all threads; everything in it is thread-safe.
struct Services {
  Config config;
  pipeline::Profiles* profiles = nullptr;
  const pipeline::Schemas* schemas = nullptr;
  Metrics* metrics = nullptr;
  std::optional<std::string> admin_token;  // none: PUT/DELETE answer 401 to everyone
  std::filesystem::path web_root;
  std::filesystem::path openapi_file;
  std::function<bool()> saturated;  // the job queue is full (readyz)
  // Only the memory budget's reserve is left (readyz): large requests are refused.
  std::function<bool()> memory_exhausted;
  std::string engine_version;
  // The worker pool lent to a job for reading and checking a large upload in pieces: a piece
  // waits behind queued jobs, and the job does it itself if no worker is free first.
  pipeline::Helpers helpers;
};

// The handler's side of one request. A handler either calls respond() once, or
// begin_stream() once, write() any number of times and end_stream() once.
class Exchange {
 public:
  Exchange() = default;
  Exchange(const Exchange&) = delete;
  Exchange& operator=(const Exchange&) = delete;
  virtual ~Exchange() = default;

  virtual void respond(Response response) = 0;
  // Sends the head with chunked transfer encoding. False when the client is gone or the job
  // was already answered (time limit): the handler should stop.
  virtual bool begin_stream(StreamHead head) = 0;
  // One chunk. May block while the client is behind (bounded buffering). False: client gone.
  virtual bool write(std::string_view piece) = 0;
  // complete=false cuts the stream without its last chunk, so that the client sees an
  // incomplete transfer, never a complete-looking program. `trailer`: fields sent after the
  // last chunk of a complete stream (announced in the head's Trailer field).
  virtual void end_stream(bool complete, http::fields trailer) = 0;
  void end_stream(bool complete) { end_stream(complete, {}); }
  // Set when the client went away or the job's time limit passed; the engine polls it.
  [[nodiscard]] virtual const std::atomic<bool>* cancel_flag() const noexcept = 0;
  [[nodiscard]] virtual bool timed_out() const noexcept = 0;
  // The memory budget (docs/server.md, "Memory budget"): the job no longer holds its upload's
  // text nor the model read from it (after interpretation, say), so their share of
  // --max-inflight may go to the next request now rather than when the handler returns, which
  // gives it back anyway. Any thread; once is enough.
  virtual void release_model() {}

  // Filled by the router / handler for the access log.
  std::string path_id;  // the {id} of /v1/profiles/{id}
  std::string profile;  // the profile a post used
  // Filled by the session: a large raw upload it took in as it arrived (then the request's body
  // is empty), and when the request's last byte arrived.
  std::shared_ptr<StreamedUpload> upload;
  std::chrono::steady_clock::time_point received{};
};

using Handler = void (*)(Request& request, Services& services, Exchange& exchange);

enum class Where : std::uint8_t { Inline, Worker };

struct Route {
  http::verb method;
  std::string_view pattern;  // "/v1/profiles/{id}": one trailing segment parameter
  std::string_view name;     // for metrics and logs: the pattern, with the method
  Where where;
  Handler handler;
  // Its upload is a model (P21/P28): a large raw one is read while it arrives (upload.hpp).
  bool reads_model = false;
};

struct RouteMatch {
  const Route* route = nullptr;  // null: no route (status says 404 or 405)
  std::string id;
  unsigned status = 0;
  std::string allow;         // for 405
  std::string_view pattern;  // for 405: the pattern the path matched (metrics count it there)
};

[[nodiscard]] const std::vector<Route>& routes();
[[nodiscard]] RouteMatch match_route(http::verb method, std::string_view target);

// RFC 9457 problem details, with diagnostics {file, line, column, severity, code, message}.
[[nodiscard]] Response problem(unsigned status, std::string_view type, std::string_view title,
                               std::string_view detail,
                               const std::vector<diag::FileDiagnostic>& diagnostics = {});
[[nodiscard]] std::string problem_body(unsigned status, std::string_view type,
                                       std::string_view title, std::string_view detail,
                                       const std::vector<diag::FileDiagnostic>& diagnostics = {});

// The decoded value of a query parameter of `target`, nullopt when absent.
[[nodiscard]] std::optional<std::string> query_param(std::string_view target,
                                                     std::string_view name);

// The upload of a job route: the raw body, or the `file` part (else the only part) of a
// multipart/form-data body.
struct Upload {
  std::string bytes;  // empty when `streamed` holds them
  std::shared_ptr<StreamedUpload> streamed;
  std::string name = "upload";  // names the input in diagnostics
  std::string content_type;
  // The further `file` parts of a G-code upload, by their filenames: the program's subprogram
  // files (docs/gcode.md, "Subprograms"). Null when the upload is one file.
  std::shared_ptr<const std::vector<pipeline::SourceFile>> others;
};
// Whether a route takes several `file` parts: only those that read G-code do (the first part
// is the program, the others its subprogram files); elsewhere a repeated `file` part is a 400.
enum class FileParts : std::uint8_t { One, Several };
// nullopt: a 400 problem is in `error`. `streamed`: what the session took in as it arrived.
[[nodiscard]] std::optional<Upload> take_upload(Request& request, std::optional<Response>& error,
                                                std::shared_ptr<StreamedUpload> streamed = {},
                                                FileParts file_parts = FileParts::One);

// At most this much of the diagnostics goes into the Ncpost-Diagnostics trailer (whole entries;
// Ncpost-Warnings still counts them all), so that the trailer stays within any client's limits:
// curl (7.88) fails a transfer whose trailer line passes 4 KiB ("Out of memory in
// chunked-encoding"), and the line holds the field's name too.
inline constexpr std::size_t kMaxDiagnosticsTrailer = 4000;
// The trailer of a complete stream: Ncpost-Warnings (how many diagnostics the job gave; a job
// that streams to the end has no errors) and Ncpost-Diagnostics (them as compact ASCII JSON).
[[nodiscard]] http::fields diagnostics_trailer(
    const std::vector<diag::FileDiagnostic>& diagnostics);

}  // namespace ncpost::server
