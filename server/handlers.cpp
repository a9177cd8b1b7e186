#include "handlers.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>

#include "auth.hpp"
#include "body_hash.hpp"
#include "multipart.hpp"
#include "ncpost/pipeline/diagnostics.hpp"
#include "ncpost/pipeline/jobs.hpp"
#include "ncpost/pipeline/post.hpp"
#include "negotiation.hpp"

namespace ncpost::server {
namespace {

using Clock = std::chrono::steady_clock;
using json = nlohmann::ordered_json;

// ---- problem details and small responses ---------------------------------------------------

// A problem whose cause is the request itself, not its content: one diagnostic with the code.
Response http_problem(unsigned status, diag::Code code, std::string_view title,
                      std::string detail) {
  const std::vector<diag::FileDiagnostic> one = {{"request", diag::make(code, 0, 0, detail)}};
  return problem(status, diag::info(code).id, title, detail, one);
}

// Most handlers answer a malformed query the same way.
Response bad_request(std::string detail) {
  return http_problem(400, diag::Code::HttpBadRequest, "Bad request", std::move(detail));
}

// The upload of a job route, or nullopt after the problem (413, 415, a broken multipart body)
// has been sent.
std::optional<Upload> take_upload_or_respond(Request& request, Exchange& exchange,
                                             FileParts file_parts = FileParts::One) {
  std::optional<Response> error;
  auto upload = take_upload(request, error, exchange.upload, file_parts);
  if (!upload) exchange.respond(std::move(*error));
  return upload;
}

// Client text (a path, a file name, a profile id) may hold any bytes: invalid UTF-8 becomes
// U+FFFD instead of an exception from the JSON library.
std::string to_text(const json& body, int indent = 2) {
  return body.dump(indent, ' ', false, json::error_handler_t::replace);
}

Response json_response(unsigned status, const json& body) {
  Response r{static_cast<http::status>(status), 11};
  r.set(http::field::content_type, "application/json");
  r.body() = to_text(body);
  r.body() += '\n';
  return r;
}

Response text_response(std::string_view content_type, std::string body) {
  Response r{http::status::ok, 11};
  r.set(http::field::content_type, content_type);
  r.body() = std::move(body);
  return r;
}

std::optional<std::string> read_small_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return std::move(ss).str();
}

bool wants_json(const Request& request) {
  return accept_prefers_json(request[http::field::accept]);
}

// Collects small pieces into chunks of about 64 KiB: one chunk per engine callback would cost a
// lock and a syscall per P21 instance.
class Coalescer {
 public:
  explicit Coalescer(Exchange& exchange) : exchange_(exchange) {}
  void operator()(std::string_view piece) {
    buffer_.append(piece);
    if (buffer_.size() >= kChunk) flush();
  }
  void flush() {
    if (!buffer_.empty() && alive_) alive_ = exchange_.write(buffer_);
    buffer_.clear();
  }
  [[nodiscard]] bool alive() const { return alive_; }

 private:
  static constexpr std::size_t kChunk = 64 * 1024;
  Exchange& exchange_;
  std::string buffer_;
  bool alive_ = true;
};

// A streamed answer whose head goes out once `hold_back` bytes of it are there (with the first
// piece when 0), so that a job that fails before that is still an ordinary problem response;
// the pieces are coalesced. `before_head` may complete the head just before it goes out.
class LateStream {
 public:
  LateStream(Exchange& exchange, StreamHead head, std::uint64_t hold_back = 0,
             std::function<void(StreamHead&)> before_head = {})
      : exchange_(exchange),
        head_(std::move(head)),
        hold_back_(hold_back),
        before_head_(std::move(before_head)),
        out_(exchange) {}
  void operator()(std::string_view piece) {
    if (begun_) return out_(piece);
    held_.append(piece);
    if (held_.size() >= hold_back_) (void)begin();
  }
  [[nodiscard]] bool begun() const { return begun_; }
  // Sends the head and what is held: a job that ended with less than the hold-back (or no
  // output at all: still a complete, empty answer). False when the client has gone.
  bool begin() {
    begun_ = true;
    if (before_head_) before_head_(head_);
    if (!exchange_.begin_stream(std::move(head_))) return false;
    out_(held_);
    held_ = std::string();
    return true;
  }
  // Ends a begun stream: whole (with the trailer) when `whole` and every piece went out.
  void end(bool whole, http::fields trailer = {}) {
    out_.flush();
    if (whole && out_.alive())
      exchange_.end_stream(true, std::move(trailer));
    else
      exchange_.end_stream(false);
  }

 private:
  Exchange& exchange_;
  StreamHead head_;
  std::uint64_t hold_back_;
  std::function<void(StreamHead&)> before_head_;
  std::string held_;
  Coalescer out_;
  bool begun_ = false;
};

std::string hex64(std::uint64_t v) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(v));
  return buffer;
}

// A post's stages (pipeline::PostResult): interpretation and rendering interleave chunk by
// chunk, so besides their sum, `render` is the time in the stylesheet's transforms and
// `interpret` the rest.
void record_post_stages(Metrics& metrics, std::chrono::nanoseconds interpret,
                        std::chrono::nanoseconds render, std::chrono::nanoseconds both) {
  metrics.stage("interpret_render", both);
  metrics.stage("interpret", interpret);
  metrics.stage("render", render);
}

// A job whose time limit passed answers 504; the session has usually answered already, in
// which case this response is dropped.
bool stop_if_cancelled(Exchange& exchange) {
  const auto* flag = exchange.cancel_flag();
  if (flag == nullptr || !flag->load()) return false;
  if (exchange.timed_out())
    exchange.respond(http_problem(504, diag::Code::HttpJobTimeout, "Job time limit exceeded",
                                  "the job ran longer than --job-timeout"));
  else
    exchange.respond(http_problem(499, diag::Code::HttpInternal, "Client closed request",
                                  "the client went away"));
  return true;
}

// For Server-Timing: milliseconds with one decimal.
std::string timing_ms(std::chrono::nanoseconds d) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f",
                std::chrono::duration<double, std::milli>(d).count());
  return buffer;
}

// ---- what every job route shares -----------------------------------------------------------

// The context of a job route's pipeline call: the server's schemas and worker pool, the
// request's cancel flag, and `strict=true`. Nullopt after a 400 for a malformed `strict`.
// A true/false query parameter: its value (`otherwise` when absent), or nullopt after a 400.
std::optional<bool> bool_query(const Request& request, std::string_view name, bool otherwise,
                               Exchange& exchange) {
  const auto value = query_param(request.target(), name);
  if (!value) return otherwise;
  if (*value != "true" && *value != "false") {
    exchange.respond(
        bad_request("the query parameter '" + std::string(name) + "' must be true or false"));
    return std::nullopt;
  }
  return *value == "true";
}

pipeline::ProfileLookup find_profile_or_respond(Services& services, Exchange& exchange,
                                                std::string_view id);

std::optional<pipeline::JobContext> job_context(const Request& request, Services& services,
                                                Exchange& exchange) {
  pipeline::JobContext context;
  context.schemas = services.schemas;
  context.cancel = exchange.cancel_flag();
  context.helpers = &services.helpers;
  const auto strict = bool_query(request, "strict", false, exchange);
  if (!strict) return std::nullopt;
  context.strict = *strict;
  // from= (or dialect=): the profile whose dialect.json reads a G-code upload (docs/gcode.md).
  auto dialect = query_param(request.target(), "from");
  if (!dialect) dialect = query_param(request.target(), "dialect");
  if (dialect) {
    context.gcode_dialect = find_profile_or_respond(services, exchange, *dialect).profile;
    if (!context.gcode_dialect) return std::nullopt;
  }
  return context;
}

pipeline::Input job_input(Upload& upload) {
  pipeline::Input input;
  input.name = upload.name;
  input.bytes = std::move(upload.bytes);
  if (upload.streamed) input.arriving = &upload.streamed->reader();
  return input;
}

// A G-code upload's further files are its subprogram files.
void add_subprograms(pipeline::JobContext& context, const Upload& upload) {
  context.gcode_subprograms = upload.others;
}

// What the further files add to an ETag: their names and bytes.
std::string others_key(const Upload& upload) {
  if (!upload.others) return {};
  std::string key;
  for (const pipeline::SourceFile& file : *upload.others)
    key += "/" + file.name + ":" + std::to_string(body_hash(file.text));
  return key;
}

void record_read(Metrics& metrics, const pipeline::JobResult& job) {
  metrics.stage("read", job.read_time + job.check_time);
}

Response input_rejected(const std::vector<diag::FileDiagnostic>& diagnostics) {
  return problem(422, "input-rejected", "The upload was rejected",
                 "the input could not be read; see diagnostics", diagnostics);
}

// ---- handlers ------------------------------------------------------------------------------

void handle_healthz(Request&, Services&, Exchange& exchange) {
  Response r = text_response("application/json", "{\"status\":\"ok\"}\n");
  r.set(http::field::cache_control, "no-store");
  exchange.respond(std::move(r));
}

void handle_readyz(Request&, Services& services, Exchange& exchange) {
  const auto listed = services.profiles->list();
  const auto& profiles = listed.profiles;
  // A profile that does not load (its stylesheet, or the common templates it imports, broken)
  // would answer every post with 500: the server is not ready to serve it. Loaded profiles are
  // cached, so this compiles only what changed.
  json broken = json::array();
  for (const auto& summary : profiles)
    if (services.profiles->find(summary.id).outcome == pipeline::LookupOutcome::Broken)
      broken.push_back(summary.id);
  for (const auto& d : listed.diagnostics) broken.push_back(d.file);
  const bool saturated = services.saturated && services.saturated();
  const bool memory = services.memory_exhausted && services.memory_exhausted();
  const bool ready = !profiles.empty() && broken.empty() && !saturated && !memory;
  json body;
  body["status"] = ready ? "ready" : "not ready";
  body["profiles"] = profiles.size();
  body["broken_profiles"] = std::move(broken);
  body["queue_saturated"] = saturated;
  body["memory_exhausted"] = memory;
  Response r = json_response(ready ? 200 : 503, body);
  r.set(http::field::cache_control, "no-store");
  // A broken profile is mended by an operator, not by waiting a second: ask again later.
  if (saturated || memory)
    r.set(http::field::retry_after, "1");
  else if (!ready)
    r.set(http::field::retry_after, "30");
  exchange.respond(std::move(r));
}

void handle_metrics(Request&, Services& services, Exchange& exchange) {
  const auto stats = services.profiles->cache_stats();
  Response r = text_response("text/plain; version=0.0.4; charset=utf-8",
                             services.metrics->render({stats.hits, stats.misses}));
  r.set(http::field::cache_control, "no-store");
  exchange.respond(std::move(r));
}

void handle_openapi(Request&, Services& services, Exchange& exchange) {
  auto text = read_small_file(services.openapi_file);
  if (!text) {
    exchange.respond(http_problem(
        404, diag::Code::HttpNotFound, "Not found",
        "the OpenAPI description is not installed at " + services.openapi_file.string()));
    return;
  }
  exchange.respond(text_response("application/yaml", std::move(*text)));
}

void handle_index(Request&, Services& services, Exchange& exchange) {
  auto text = read_small_file(services.web_root / "index.html");
  if (!text) {
    exchange.respond(http_problem(404, diag::Code::HttpNotFound, "Not found",
                                  "the web front end is not installed"));
    return;
  }
  Response r = text_response("text/html; charset=utf-8", std::move(*text));
  r.set("Content-Security-Policy",
        "default-src 'self'; script-src 'unsafe-inline'; style-src 'unsafe-inline'");
  exchange.respond(std::move(r));
}

void handle_profiles_list(Request&, Services& services, Exchange& exchange) {
  const pipeline::ProfileList list = services.profiles->list();
  json body;
  body["profiles"] = json::array();
  for (const auto& p : list.profiles)
    body["profiles"].push_back(
        {{"id", p.id}, {"name", p.name}, {"controller", p.controller}, {"read_only", p.read_only}});
  body["writable"] = services.profiles->writable();
  body["diagnostics"] = pipeline::diagnostics_json(list.diagnostics);
  exchange.respond(json_response(200, body));
}

// The profile a request names; after its 404 (unknown) or 500 (broken), a lookup without one.
// A name no profile can have: the request is wrong, not the store (400 on every route, not
// 404), and the store is never asked.
std::optional<Response> invalid_profile_id(std::string_view id) {
  if (profile::valid_id(id)) return std::nullopt;
  return problem(
      400, "PROFILE-008", "Invalid profile id",
      "'" + std::string(id) + "' is not a profile id: [a-z0-9][a-z0-9._-]*, at most 64 characters");
}

pipeline::ProfileLookup find_profile_or_respond(Services& services, Exchange& exchange,
                                                std::string_view id) {
  if (auto refused = invalid_profile_id(id)) {
    exchange.respond(std::move(*refused));
    return {};
  }
  pipeline::ProfileLookup lookup = services.profiles->find(id);
  switch (lookup.outcome) {
    case pipeline::LookupOutcome::Found:
      break;
    case pipeline::LookupOutcome::Unknown:
      exchange.respond(problem(404, "PROFILE-003", "Unknown profile",
                               "no profile '" + std::string(id) + "' (see GET /v1/profiles)",
                               lookup.diagnostics));
      break;
    case pipeline::LookupOutcome::Broken:
      exchange.respond(problem(500, "PROFILE-004", "Broken profile",
                               "profile '" + std::string(id) + "' does not load",
                               lookup.diagnostics));
      break;
  }
  return lookup;
}

void handle_profile_get(Request& request, Services& services, Exchange& exchange) {
  exchange.profile = exchange.path_id;
  const pipeline::ProfileLookup lookup =
      find_profile_or_respond(services, exchange, exchange.path_id);
  const auto& loaded = lookup.profile;
  if (!loaded) return;
  const std::string etag = "\"" + loaded->version + "\"";
  if (none_match_matches(request[http::field::if_none_match], etag)) {
    Response r{http::status::not_modified, 11};
    r.set(http::field::etag, etag);
    exchange.respond(std::move(r));
    return;
  }
  json body;
  body["id"] = loaded->profile.id;
  body["name"] = loaded->profile.name;
  body["controller"] = loaded->profile.controller;
  body["extension"] = loaded->profile.extension;
  body["mime_type"] = loaded->profile.mime_type;
  body["version"] = loaded->version;
  body["read_only"] = loaded->read_only;
  // Whether its dialect.json can read this controller's G-code (from=ID, docs/gcode.md).
  body["reads_gcode"] = loaded->dialect_json.has_value();
  body["profile"] = json::parse(loaded->json, nullptr, false);
  body["diagnostics"] = pipeline::diagnostics_json(lookup.diagnostics);
  Response r = json_response(200, body);
  r.set(http::field::etag, etag);
  exchange.respond(std::move(r));
}

// Null when allowed; otherwise the 401/403 to answer. The token itself is never logged.
std::optional<Response> refuse_admin(const Request& request, const Services& services) {
  const auto header = request[http::field::authorization];
  if (header.empty()) {
    Response r = http_problem(401, diag::Code::HttpUnauthorized, "Unauthorized",
                              "changing profiles needs Authorization: Bearer <admin token>");
    r.set(http::field::www_authenticate, "Bearer realm=\"ncpost\"");
    return r;
  }
  const bool matches = services.admin_token && token_matches(*services.admin_token, header);
  if (!matches)
    return http_problem(403, diag::Code::HttpForbidden, "Forbidden",
                        "the bearer token does not match the admin token");
  return std::nullopt;
}

Response profile_put_problem(const pipeline::ProfilePut& put) {
  switch (put.outcome) {
    case pipeline::PutOutcome::ReadOnlyStore:
      return problem(409, "PROFILE-006", "Read-only profile store",
                     "this server has no writable profile directory", put.diagnostics);
    case pipeline::PutOutcome::WriteFailed:
      return problem(500, "PROFILE-007", "The profile was rejected",
                     "the previous version (if any) stays active; see diagnostics",
                     put.diagnostics);
    case pipeline::PutOutcome::Reserved:
      return problem(
          409, "PROFILE-009", "Not a profile",
          "the store only replaces profiles it wrote or profile folders; nothing changed",
          put.diagnostics);
    case pipeline::PutOutcome::BadId:
      return problem(400, "profile-rejected", "The profile was rejected",
                     "the previous version (if any) stays active; see diagnostics",
                     put.diagnostics);
    default:
      return problem(422, "profile-rejected", "The profile was rejected",
                     "the previous version (if any) stays active; see diagnostics",
                     put.diagnostics);
  }
}

void handle_profile_put(Request& request, Services& services, Exchange& exchange) {
  exchange.profile = exchange.path_id;
  if (auto refused = refuse_admin(request, services)) {
    exchange.respond(std::move(*refused));
    return;
  }
  if (auto refused = invalid_profile_id(exchange.path_id)) {
    exchange.respond(std::move(*refused));
    return;
  }
  const auto boundary = multipart_boundary(request[http::field::content_type]);
  if (!boundary) {
    exchange.respond(
        bad_request("PUT /v1/profiles/{id} takes multipart/form-data with the parts 'profile' and "
                    "'stylesheet' (and 'dialect', its dialect.json, optionally)"));
    return;
  }
  const MultipartResult parts = parse_multipart(request.body(), *boundary);
  if (!parts.ok()) {
    exchange.respond(bad_request(parts.error));
    return;
  }
  for (const std::string_view name : {"profile", "stylesheet", "dialect"}) {
    if (std::count_if(parts.parts.begin(), parts.parts.end(),
                      [&](const MultipartPart& part) { return part.name == name; }) > 1) {
      exchange.respond(bad_request("the part '" + std::string(name) + "' is repeated"));
      return;
    }
  }
  const auto* profile_part = parts.find("profile");
  const auto* stylesheet_part = parts.find("stylesheet");
  if (profile_part == nullptr || stylesheet_part == nullptr) {
    exchange.respond(bad_request("the parts 'profile' and 'stylesheet' are both required"));
    return;
  }
  // The dialect (how the machine's G-code is read: stylesheets/dialect.schema.json), if given.
  const auto* dialect_part = parts.find("dialect");
  const pipeline::ProfilePut put = services.profiles->put(
      exchange.path_id, profile_part->body, stylesheet_part->body,
      dialect_part != nullptr ? std::optional<std::string_view>(dialect_part->body) : std::nullopt);
  if (!put.profile) {
    exchange.respond(profile_put_problem(put));
    return;
  }
  const bool created = put.outcome == pipeline::PutOutcome::Created;
  json body;
  body["id"] = put.profile->profile.id;
  body["version"] = put.profile->version;
  body["created"] = created;
  body["diagnostics"] = pipeline::diagnostics_json(put.diagnostics);
  Response r = json_response(created ? 201 : 200, body);
  r.set(http::field::etag, "\"" + put.profile->version + "\"");
  if (created) r.set(http::field::location, "/v1/profiles/" + exchange.path_id);
  exchange.respond(std::move(r));
}

void handle_profile_delete(Request& request, Services& services, Exchange& exchange) {
  exchange.profile = exchange.path_id;
  if (auto refused = refuse_admin(request, services)) {
    exchange.respond(std::move(*refused));
    return;
  }
  if (auto refused = invalid_profile_id(exchange.path_id)) {
    exchange.respond(std::move(*refused));
    return;
  }
  switch (services.profiles->remove(exchange.path_id)) {
    case profile::RemoveOutcome::Removed: {
      Response r{http::status::no_content, 11};
      exchange.respond(std::move(r));
      return;
    }
    case profile::RemoveOutcome::NotFound:
      exchange.respond(http_problem(404, diag::Code::HttpNotFound, "Unknown profile",
                                    "no profile '" + exchange.path_id + "' to delete"));
      return;
    case profile::RemoveOutcome::Foreign: {
      const std::vector<diag::FileDiagnostic> one = {
          {"request", diag::make(diag::Code::ProfileReserved, 0, 0,
                                 "the folder '" + exchange.path_id +
                                     "' holds files that are not a profile's")}};
      exchange.respond(problem(409, "PROFILE-009", "Not a profile",
                               "the store deletes only profiles; nothing changed", one));
      return;
    }
    case profile::RemoveOutcome::ReadOnly: {
      const std::vector<diag::FileDiagnostic> one = {
          {"request", diag::make(diag::Code::ProfileReadOnly, 0, 0,
                                 "'" + exchange.path_id + "' is a built-in profile")}};
      exchange.respond(problem(409, "PROFILE-006", "Read-only profile",
                               "built-in profiles cannot be deleted", one));
      return;
    }
  }
}

// The diagnostics as JSON, each renderer diagnostic with the output line where the text of
// the call behind it begins ("output_line"; an error's is the error marker's line). The
// renderer's are the last `marks.size()` of `diagnostics`.
json diagnostics_with_output_lines(const std::vector<diag::FileDiagnostic>& diagnostics,
                                   std::string_view text, const std::vector<std::size_t>& marks) {
  json listed = pipeline::diagnostics_json(diagnostics);
  const std::vector<std::size_t> lines = pipeline::lines_at(text, marks);
  const std::size_t first = diagnostics.size() - std::min(diagnostics.size(), marks.size());
  for (std::size_t k = 0; k < lines.size() && first + k < listed.size(); ++k)
    listed[first + k]["output_line"] = lines[k];
  return listed;
}

// Accept: application/json: the whole program in one JSON document, with the map from its
// blocks to the workingsteps and the motions they came from (the browser front end's view).
void post_json(Services& services, Exchange& exchange, pipeline::Input input,
               const pipeline::JobContext& context, const profile::LoadedProfile& profile,
               const std::string& filename, const std::string& etag, bool shop_checks,
               bool motion_lines) {
  std::string text;
  std::vector<pipeline::WorkingstepMark> marks;
  std::vector<pipeline::MotionMark> motions;
  std::vector<std::size_t> render_marks;
  pipeline::PostOptions options;
  options.workingstep_marks = &marks;
  // motions=true: each call rendered on its own, a transform each (docs/server.md).
  if (motion_lines) {
    options.motion_marks = &motions;
    options.render_diagnostic_marks = &render_marks;
  }
  options.shop_checks = shop_checks;
  const pipeline::PostJobResult result = pipeline::post(
      std::move(input), context, profile, [&text](std::string_view piece) { text.append(piece); },
      options);
  record_read(*services.metrics, result.read);
  record_post_stages(*services.metrics, result.post.interpret, result.post.render,
                     result.post.interpret_and_render);
  if (stop_if_cancelled(exchange)) return;
  const auto diagnostics = services.profiles->without_server_paths(result.diagnostics());
  if (!result.read.ok) {
    exchange.respond(input_rejected(diagnostics));
    return;
  }
  if (!result.ok()) {
    Response r = problem(422, "post-failed", "The program could not be posted",
                         "the post stopped at the first error; see diagnostics", diagnostics);
    auto body = json::parse(r.body());
    body["diagnostics"] = diagnostics_with_output_lines(diagnostics, text, render_marks);
    r.body() = to_text(body) + "\n";
    exchange.respond(std::move(r));
    return;
  }
  json map = pipeline::block_map(text, marks, exchange.cancel_flag());
  if (stop_if_cancelled(exchange)) return;
  json motion_map = pipeline::motion_lines(text, motions);
  json listed = diagnostics_with_output_lines(diagnostics, text, render_marks);
  json body;
  body["profile"] = profile.profile.id;
  body["profile_version"] = profile.version;
  body["filename"] = filename;
  body["program"] = std::move(text);
  body["diagnostics"] = std::move(listed);
  body["blocks"] = std::move(map["blocks"]);
  body["workingsteps"] = std::move(map["workingsteps"]);
  if (motion_lines) body["motions"] = std::move(motion_map);
  // The streamed form's headers that describe the program; its name is in the body, and its
  // diagnostics, which the streamed form sends as trailer fields.
  Response r = json_response(200, body);
  r.set(http::field::etag, etag);
  r.set("X-Ncpost-Profile-Version", profile.version);
  r.set(http::field::vary, "Accept");
  exchange.respond(std::move(r));
}

void handle_post(Request& request, Services& services, Exchange& exchange) {
  const auto job_started = Clock::now();
  const auto id = query_param(request.target(), "profile");
  if (!id || id->empty()) {
    exchange.respond(
        bad_request("the query parameter 'profile' is required "
                    "(POST /v1/posts?profile=ID; see GET /v1/profiles)"));
    return;
  }
  exchange.profile = *id;
  // The job keeps this version even if the profile is replaced while it runs.
  const auto loaded_profile = find_profile_or_respond(services, exchange, *id).profile;
  if (!loaded_profile) return;
  auto context = job_context(request, services, exchange);
  if (!context) return;
  // checks=false: without the profile's pre-post checks of CL input (docs/cls.md).
  const auto shop_checks = bool_query(request, "checks", true, exchange);
  if (!shop_checks) return;
  // motions=true (JSON form): each motion's output lines, renderer diagnostics' output_line.
  const auto motion_lines = bool_query(request, "motions", false, exchange);
  if (!motion_lines) return;
  // A G-code post (from=) may bring its subprogram files as further `file` parts.
  auto upload = take_upload_or_respond(
      request, exchange, context->gcode_dialect ? FileParts::Several : FileParts::One);
  if (!upload) return;
  add_subprograms(*context, *upload);
  // The same input, profile version and engine give the same program. A large upload was
  // hashed as it arrived.
  const std::uint64_t input_hash =
      upload->streamed ? upload->streamed->hash() : body_hash(upload->bytes);
  const std::uint64_t context_hash =
      body_hash(loaded_profile->version + "/" + services.engine_version +
                (context->strict ? "/strict" : "") + (*shop_checks ? "" : "/no-checks") +
                (context->gcode_dialect ? "/from:" + context->gcode_dialect->version : "") +
                others_key(*upload));
  const std::string etag = "\"" + hex64(input_hash) + hex64(context_hash) + "\"";
  const bool as_json = wants_json(request);
  if (none_match_matches(request[http::field::if_none_match], etag) && !as_json) {
    Response r{http::status::not_modified, 11};
    r.set(http::field::etag, etag);
    exchange.respond(std::move(r));
    return;
  }
  const std::string filename = ascii_file_stem(upload->name) + loaded_profile->profile.extension;
  if (as_json) {
    post_json(services, exchange, job_input(*upload), *context, *loaded_profile, filename, etag,
              *shop_checks, *motion_lines);
    return;
  }

  StreamHead head{http::status::ok, 11};
  head.set(http::field::content_type, loaded_profile->profile.mime_type);
  head.set(http::field::content_disposition,
           attachment_disposition(upload->name, loaded_profile->profile.extension));
  head.set(http::field::etag, etag);
  head.set("X-Content-Type-Options", "nosniff");
  head.set("X-Ncpost-Profile-Version", loaded_profile->version);
  head.set(http::field::vary, "Accept");
  head.set(http::field::trailer, "Ncpost-Warnings, Ncpost-Diagnostics");
  pipeline::PostOptions options;
  options.shop_checks = *shop_checks;
  // One thread per job: --workers bounds the threads doing CPU work, which a render thread of
  // the job's own would not respect (docs/architecture.md, "Two threads in a post").
  options.render_thread_min_instances = 0;
  const StreamedUpload* streamed = upload->streamed.get();
  std::string read_timing;
  auto render_started = Clock::now();
  const auto on_read = [&](const pipeline::JobResult& read) {
    read_timing =
        "read;dur=" + timing_ms(read.read_time) + ", check;dur=" + timing_ms(read.check_time);
    render_started = Clock::now();
  };
  const auto server_timing = [&](StreamHead& h) {
    std::string timing;
    if (exchange.received != Clock::time_point{})
      timing = "queue;dur=" + timing_ms(job_started - exchange.received) + ", ";
    // How much of a large upload had been read before its last byte came.
    if (streamed != nullptr)
      timing += "arrival;desc=\"read " +
                std::to_string(streamed->read_while_arriving() * 100 /
                               std::max<std::size_t>(1, streamed->size())) +
                "% while arriving\", ";
    timing += read_timing + ", first-text;dur=" + timing_ms(Clock::now() - render_started);
    h.set("Server-Timing", timing);
  };
  // The head goes out once --hold-back bytes of text are there (or the job ends), so that an
  // error found before that is still an ordinary problem+json response. That matters for
  // inputs read as they are interpreted (G-code, CL), whose errors can follow the first
  // blocks; it costs a small program's first byte nothing, a large one's 64 KiB.
  LateStream out(exchange, std::move(head), services.config.hold_back, server_timing);
  const pipeline::PostJobResult result = pipeline::post(
      job_input(*upload), *context, *loaded_profile, [&out](std::string_view piece) { out(piece); },
      options, on_read);
  record_read(*services.metrics, result.read);
  record_post_stages(*services.metrics, result.post.interpret, result.post.render,
                     result.post.interpret_and_render);
  const auto diagnostics = services.profiles->without_server_paths(result.diagnostics());
  if (!out.begun()) {
    if (stop_if_cancelled(exchange)) return;
    if (!result.read.ok) {
      exchange.respond(input_rejected(diagnostics));
      return;
    }
    if (!result.ok()) {
      exchange.respond(problem(422, "post-failed", "The program could not be posted",
                               "the post stopped before any output; see diagnostics", diagnostics));
      return;
    }
    if (!out.begin()) return;
  }
  out.end(result.ok(), diagnostics_trailer(diagnostics));
}

void handle_conversion(Request& request, Services& services, Exchange& exchange) {
  const auto to = query_param(request.target(), "to");
  if (!to || (*to != "p21" && *to != "p28")) {
    exchange.respond(bad_request("the query parameter 'to' must be p21 or p28"));
    return;
  }
  const auto binding = query_param(request.target(), "binding");
  if (binding && ((*binding != "late" && *binding != "early") || *to != "p28")) {
    exchange.respond(bad_request("'binding' is late or early, and only with to=p28"));
    return;
  }
  const auto context = job_context(request, services, exchange);
  if (!context) return;
  auto upload = take_upload_or_respond(request, exchange);
  if (!upload) return;
  StreamHead head{http::status::ok, 11};
  head.set(http::field::content_type, *to == "p21" ? "application/p21" : "application/xml");
  head.set(http::field::content_disposition,
           attachment_disposition(upload->name, *to == "p21" ? ".stp" : ".stpx"));
  head.set(http::field::trailer, "Ncpost-Warnings, Ncpost-Diagnostics");
  const pipeline::ConvertTo target = *to == "p21" ? pipeline::ConvertTo::P21
                                     : binding.value_or("late") == "early"
                                         ? pipeline::ConvertTo::P28Early
                                         : pipeline::ConvertTo::P28Late;
  // The head goes out with the first piece, so that an input with errors is still a 422.
  LateStream out(exchange, std::move(head));
  const pipeline::JobResult result = pipeline::convert(
      job_input(*upload), *context, target, [&out](std::string_view piece) { out(piece); });
  record_read(*services.metrics, result);
  services.metrics->stage("convert", result.work_time);
  if (!out.begun()) {
    if (stop_if_cancelled(exchange)) return;
    exchange.respond(input_rejected(result.diagnostics));
    return;
  }
  out.end(true, diagnostics_trailer(result.diagnostics));
}

void handle_inspection(Request& request, Services& services, Exchange& exchange) {
  const auto context = job_context(request, services, exchange);
  if (!context) return;
  auto upload = take_upload_or_respond(request, exchange);
  if (!upload) return;
  const pipeline::Inspection inspection = pipeline::inspect(job_input(*upload), *context);
  record_read(*services.metrics, inspection.job);
  if (stop_if_cancelled(exchange)) return;
  json info = pipeline::inspection_json(inspection);
  if (!inspection.job.ok) {
    Response r = problem(422, "input-rejected", "The upload has errors",
                         "see diagnostics; the inspection member holds what could be read",
                         inspection.job.diagnostics);
    auto body = json::parse(r.body());
    body["inspection"] = std::move(info);
    r.body() = to_text(body) + "\n";
    exchange.respond(std::move(r));
    return;
  }
  exchange.respond(json_response(200, info));
}

// The JSON trace, streamed as the interpreter goes: NDJSON (format=json, or Accept:
// application/x-ndjson) or one JSON document (Accept: application/json). An input that cannot
// be read is a 422 as for the text; once the first record went out, the end record says
// whether the trace is whole (ok, diagnostics).
void trace_json(Services& services, Exchange& exchange, pipeline::Input input,
                const pipeline::JobContext& context, bool lines) {
  StreamHead head{http::status::ok, 11};
  head.set(http::field::content_type, lines ? "application/x-ndjson" : "application/json");
  head.set("X-Content-Type-Options", "nosniff");
  LateStream out(exchange, std::move(head));
  const pipeline::JobResult result =
      pipeline::trace(std::move(input), context,
                      lines ? pipeline::TraceFormat::Json : pipeline::TraceFormat::JsonDocument,
                      [&out](std::string_view piece) { out(piece); });
  record_read(*services.metrics, result);
  services.metrics->stage("interpret", result.work_time);
  if (!out.begun()) {
    if (stop_if_cancelled(exchange)) return;
    exchange.respond(input_rejected(result.diagnostics));
    return;
  }
  out.end(!result.cancelled);
}

// A trace; `file_parts`: Several when it is nc parse's (a G-code program and its subprogram
// files).
void trace_job(Request& request, Services& services, Exchange& exchange, FileParts file_parts) {
  const auto format_param = query_param(request.target(), "format");
  const std::string format = format_param.value_or("text");
  if (format != "text" && format != "xml" && format != "json") {
    exchange.respond(bad_request("the query parameter 'format' must be text, xml or json"));
    return;
  }
  // Without format=, the Accept header may ask for a JSON form (RFC 9110 negotiation).
  const std::size_t accepted =
      format_param ? 0
                   : accept_choice(request[http::field::accept],
                                   {"text/plain", "application/json", "application/x-ndjson"});
  const bool ndjson = format == "json" || accepted == 2;
  const bool document = accepted == 1;
  auto context = job_context(request, services, exchange);
  if (!context) return;
  auto upload = take_upload_or_respond(request, exchange, file_parts);
  if (!upload) return;
  add_subprograms(*context, *upload);
  if (ndjson || document) {
    trace_json(services, exchange, job_input(*upload), *context, ndjson);
    return;
  }
  std::string text;
  const pipeline::JobResult result =
      pipeline::trace(job_input(*upload), *context,
                      format == "text" ? pipeline::TraceFormat::Text : pipeline::TraceFormat::Xml,
                      [&text](std::string_view piece) { text.append(piece); });
  record_read(*services.metrics, result);
  services.metrics->stage("interpret", result.work_time);
  if (stop_if_cancelled(exchange)) return;
  if (!result.input_ok) {
    exchange.respond(input_rejected(result.diagnostics));
    return;
  }
  if (!result.ok) {
    exchange.respond(problem(422, "input-rejected", "The program could not be interpreted",
                             "see diagnostics", result.diagnostics));
    return;
  }
  exchange.respond(
      text_response(format == "text" ? "text/plain; charset=utf-8" : "application/xml", text));
}

void handle_trace(Request& request, Services& services, Exchange& exchange) {
  trace_job(request, services, exchange, FileParts::One);
}

// G-code read with ?dialect=PROFILE: the canonical program as text (as a trace), or the XML
// intermediate form (format=xml) with its <error> elements; a program with errors is still
// answered in XML (that is what the form is for), with their count in Ncpost-Errors.
void handle_nc_parse(Request& request, Services& services, Exchange& exchange) {
  if (!query_param(request.target(), "dialect")) {
    exchange.respond(bad_request(
        "the query parameter 'dialect' is required (POST /v1/nc/parse?dialect=PROFILE)"));
    return;
  }
  const std::string format = query_param(request.target(), "format").value_or("text");
  if (format == "text") {
    trace_job(request, services, exchange, FileParts::Several);
    return;
  }
  if (format != "xml") {
    exchange.respond(bad_request("the query parameter 'format' must be text or xml"));
    return;
  }
  auto context = job_context(request, services, exchange);
  if (!context) return;
  auto upload = take_upload_or_respond(request, exchange, FileParts::Several);
  if (!upload) return;
  add_subprograms(*context, *upload);
  std::string text;
  const pipeline::JobResult result = pipeline::gcode_xml(
      job_input(*upload), *context, [&text](std::string_view piece) { text.append(piece); });
  record_read(*services.metrics, result);
  if (stop_if_cancelled(exchange)) return;
  if (!result.input_ok || text.empty()) {
    exchange.respond(input_rejected(result.diagnostics));
    return;
  }
  Response r = text_response("application/xml", text);
  const auto errors = std::count_if(
      result.diagnostics.begin(), result.diagnostics.end(),
      [](const diag::FileDiagnostic& d) { return d.diagnostic.severity == diag::Severity::Error; });
  r.set("Ncpost-Errors", std::to_string(errors));
  exchange.respond(std::move(r));
}

// G-code of one machine (?from=PROFILE, read with its dialect.json) posted for another
// (?to=PROFILE): exactly a post of the upload with profile=to.
void handle_nc_translate(Request& request, Services& services, Exchange& exchange) {
  const auto to = query_param(request.target(), "to");
  if (!query_param(request.target(), "from") || !to || to->empty()) {
    exchange.respond(
        bad_request("the query parameters 'from' and 'to' are required "
                    "(POST /v1/nc/translate?from=PROFILE&to=PROFILE)"));
    return;
  }
  const std::string_view target = request.target();
  const auto question = target.find('?');
  request.target("/v1/posts?profile=" + *to + "&" + std::string(target.substr(question + 1)));
  handle_post(request, services, exchange);
}

void handle_verification(Request& request, Services& services, Exchange& exchange) {
  pipeline::VerifySettings settings;
  for (const auto& [name, target] : {std::pair{"tolerance", &settings.tolerance}}) {
    const auto value = query_param(request.target(), name);
    if (!value) continue;
    char* end = nullptr;
    const double v = std::strtod(value->c_str(), &end);
    if (end != value->c_str() + value->size() || !(v > 0) || v > 1000) {
      exchange.respond(
          bad_request("'" + std::string(name) + "' must be a length in mm, > 0 and <= 1000"));
      return;
    }
    *target = v;
  }
  const auto context = job_context(request, services, exchange);
  if (!context) return;
  auto upload = take_upload_or_respond(request, exchange);
  if (!upload) return;
  const std::string name = upload->name;
  const pipeline::VerifyOutcome outcome = pipeline::verify(job_input(*upload), *context, settings);
  record_read(*services.metrics, outcome.job);
  services.metrics->stage("verify", outcome.job.work_time);
  if (stop_if_cancelled(exchange)) return;
  if (!outcome.result) {
    exchange.respond(input_rejected(outcome.job.diagnostics));
    return;
  }
  // The report, whatever the checks found: a failed check is a finding, not a failed request.
  Response r = text_response("application/json", pipeline::verify_report_json(outcome, name));
  exchange.respond(std::move(r));
}

void handle_schema(Request& request, Services& services, Exchange& exchange) {
  auto upload = take_upload_or_respond(request, exchange);
  if (!upload) return;
  std::string xml;
  const pipeline::JobResult result = pipeline::schema_to_xml(
      upload->bytes, upload->name, [&xml](std::string_view piece) { xml.append(piece); });
  if (!result.ok) {
    exchange.respond(problem(422, "input-rejected", "The schema has errors", "see diagnostics",
                             result.diagnostics));
    return;
  }
  services.metrics->stage("schema", result.work_time);
  exchange.respond(text_response("application/xml", std::move(xml)));
}

// The `file` parts after `first`: the subprogram files of a G-code upload. Nullopt after a 400:
// a repeated `file` part on a route that reads one file, or one without a filename (the name
// is how a program calls it).
std::optional<std::vector<pipeline::SourceFile>> further_files(const MultipartResult& parts,
                                                               const MultipartPart& first,
                                                               FileParts file_parts,
                                                               std::optional<Response>& error) {
  std::vector<pipeline::SourceFile> files;
  for (const MultipartPart& part : parts.parts) {
    if (&part == &first || part.name != "file") continue;
    if (file_parts == FileParts::One) {
      error = bad_request(
          "the part 'file' is repeated: this route reads one file (several 'file' parts, a "
          "G-code program and its subprogram files, are taken by /v1/nc/parse, /v1/nc/translate "
          "and /v1/posts?from=PROFILE)");
      return std::nullopt;
    }
    if (part.filename.empty()) {
      error = bad_request(
          "a further 'file' part has no filename: a subprogram file is found by its name");
      return std::nullopt;
    }
    files.push_back({part.filename, std::string(part.body)});
  }
  return files;
}

}  // namespace

std::string problem_body(unsigned status, std::string_view type, std::string_view title,
                         std::string_view detail,
                         const std::vector<diag::FileDiagnostic>& diagnostics) {
  json body;
  body["type"] = "urn:ncpost:problem:" + std::string(type);
  body["title"] = title;
  body["status"] = status;
  body["detail"] = detail;
  body["diagnostics"] = pipeline::diagnostics_json(diagnostics);
  return to_text(body) + "\n";
}

Response problem(unsigned status, std::string_view type, std::string_view title,
                 std::string_view detail, const std::vector<diag::FileDiagnostic>& diagnostics) {
  Response r{static_cast<http::status>(status), 11};
  r.set(http::field::content_type, "application/problem+json");
  r.body() = problem_body(status, type, title, detail, diagnostics);
  return r;
}

http::fields diagnostics_trailer(const std::vector<diag::FileDiagnostic>& diagnostics) {
  std::string listed = "[";
  for (const auto& d : diagnostics) {
    // ASCII only (\\u escapes), no line breaks: a valid field value whatever the messages say.
    std::string one =
        pipeline::diagnostic_json(d).dump(-1, ' ', true, json::error_handler_t::replace);
    if (listed.size() + one.size() + 2 > kMaxDiagnosticsTrailer) break;
    if (listed.size() > 1) listed += ',';
    listed += one;
  }
  listed += ']';
  http::fields trailer;
  trailer.set("Ncpost-Warnings", std::to_string(diagnostics.size()));
  trailer.set("Ncpost-Diagnostics", listed);
  return trailer;
}

std::optional<std::string> query_param(std::string_view target, std::string_view name) {
  const auto q = target.find('?');
  if (q == std::string_view::npos) return std::nullopt;
  std::string_view query = target.substr(q + 1);
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    const auto eq = pair.find('=');
    if (percent_decode(pair.substr(0, eq)) == name)
      return eq == std::string_view::npos ? std::string{} : percent_decode(pair.substr(eq + 1));
  }
  return std::nullopt;
}

std::optional<Upload> take_upload(Request& request, std::optional<Response>& error,
                                  std::shared_ptr<StreamedUpload> streamed, FileParts file_parts) {
  Upload upload;
  const auto content_type = request[http::field::content_type];
  if (auto name = query_param(request.target(), "name"); name && !name->empty())
    upload.name = *name;
  if (streamed) {
    // The session took in only large raw bodies this way, never multipart ones.
    upload.streamed = std::move(streamed);
    upload.content_type = std::string(content_type);
    return upload;
  }
  if (is_multipart(content_type)) {
    const auto boundary = multipart_boundary(content_type);
    if (!boundary) {
      error = bad_request("multipart/form-data without a valid boundary parameter");
      return std::nullopt;
    }
    const MultipartResult parts = parse_multipart(request.body(), *boundary);
    if (!parts.ok()) {
      error = bad_request(parts.error);
      return std::nullopt;
    }
    const MultipartPart* part = parts.find("file");
    if (part == nullptr && parts.parts.size() == 1) part = &parts.parts.front();
    if (part == nullptr) {
      error = bad_request("multipart/form-data upload needs a part named 'file'");
      return std::nullopt;
    }
    auto others = further_files(parts, *part, file_parts, error);
    if (!others) return std::nullopt;
    if (!others->empty())
      upload.others = std::make_shared<const std::vector<pipeline::SourceFile>>(std::move(*others));
    if (!part->filename.empty()) upload.name = part->filename;
    upload.content_type = part->content_type;
    // The part is moved to the front of the body it is in, not copied: a large upload's copy
    // would cost a fresh allocation's page faults (about as much as reading it).
    const auto offset = static_cast<std::size_t>(part->body.data() - request.body().data());
    const std::size_t length = part->body.size();
    upload.bytes = std::move(request.body());
    upload.bytes.erase(0, offset);
    upload.bytes.resize(length);
  } else {
    upload.bytes = std::move(request.body());
    upload.content_type = std::string(content_type);
  }
  if (upload.bytes.empty()) {
    error = bad_request("the upload is empty");
    return std::nullopt;
  }
  return upload;
}

const std::vector<Route>& routes() {
  static const std::vector<Route> table = {
      {http::verb::post, "/v1/posts", "POST /v1/posts", Where::Worker, handle_post, true},
      {http::verb::post, "/v1/conversions", "POST /v1/conversions", Where::Worker,
       handle_conversion, true},
      {http::verb::post, "/v1/inspections", "POST /v1/inspections", Where::Worker,
       handle_inspection, true},
      {http::verb::post, "/v1/traces", "POST /v1/traces", Where::Worker, handle_trace, true},
      {http::verb::post, "/v1/verifications", "POST /v1/verifications", Where::Worker,
       handle_verification, true},
      {http::verb::post, "/v1/schemas", "POST /v1/schemas", Where::Worker, handle_schema},
      {http::verb::post, "/v1/nc/parse", "POST /v1/nc/parse", Where::Worker, handle_nc_parse, true},
      {http::verb::post, "/v1/nc/translate", "POST /v1/nc/translate", Where::Worker,
       handle_nc_translate, true},
      {http::verb::get, "/v1/profiles", "GET /v1/profiles", Where::Inline, handle_profiles_list},
      // Loading may compile a stylesheet, and PUT always does: worker work.
      {http::verb::get, "/v1/profiles/{id}", "GET /v1/profiles/{id}", Where::Worker,
       handle_profile_get},
      {http::verb::put, "/v1/profiles/{id}", "PUT /v1/profiles/{id}", Where::Worker,
       handle_profile_put},
      {http::verb::delete_, "/v1/profiles/{id}", "DELETE /v1/profiles/{id}", Where::Inline,
       handle_profile_delete},
      {http::verb::get, "/healthz", "GET /healthz", Where::Inline, handle_healthz},
      {http::verb::get, "/readyz", "GET /readyz", Where::Inline, handle_readyz},
      {http::verb::get, "/metrics", "GET /metrics", Where::Inline, handle_metrics},
      {http::verb::get, "/openapi.yaml", "GET /openapi.yaml", Where::Inline, handle_openapi},
      {http::verb::get, "/", "GET /", Where::Inline, handle_index},
  };
  return table;
}

RouteMatch match_route(http::verb method, std::string_view target) {
  RouteMatch result;
  const std::string_view path = target.substr(0, target.find('?'));
  std::string allow;
  for (const Route& route : routes()) {
    std::string id;
    const std::string_view pattern = route.pattern;
    bool matches = false;
    if (const auto brace = pattern.find("{id}"); brace != std::string_view::npos) {
      const std::string_view prefix = pattern.substr(0, brace);
      if (path.size() > prefix.size() && path.substr(0, prefix.size()) == prefix &&
          path.find('/', prefix.size()) == std::string_view::npos) {
        id = percent_decode(path.substr(prefix.size()));
        matches = true;
      }
    } else {
      matches = path == pattern;
    }
    if (!matches) continue;
    result.pattern = route.pattern;
    // HEAD is answered as GET by the session.
    if (route.method == method || (method == http::verb::head && route.method == http::verb::get)) {
      result.route = &route;
      result.id = std::move(id);
      return result;
    }
    if (!allow.empty()) allow += ", ";
    allow += std::string(http::to_string(route.method));
    if (route.method == http::verb::get) allow += ", HEAD";
  }
  result.status = allow.empty() ? 404 : 405;
  result.allow = std::move(allow);
  return result;
}

}  // namespace ncpost::server
