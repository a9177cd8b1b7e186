#include "config.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <thread>
#include <vector>

#include "memory_budget.hpp"

namespace ncpost::server {
namespace {

constexpr std::string_view kUsage = R"(usage: ncpostd --listen HOST:PORT [options]

  --listen HOST:PORT        address to bind (port 0 picks a free port; the log says which)
  --profiles DIR            writable profile directory (default: the built-in profiles, read-only)
  --admin-token-file FILE   bearer token for PUT/DELETE /v1/profiles (or NCPOST_ADMIN_TOKEN)
  --max-body BYTES          request body limit, 413 beyond it (default 268435456)
  --max-header BYTES        request header limit, 431 beyond it (default 16384)
  --stream-read-min BYTES   raw model uploads this large are read while they arrive; 0: never
                            (default 1048576)
  --hold-back BYTES          a post's first bytes kept until an error in them can still be a
                            422 (default 65536; 0: stream at once)
  --io-threads N            threads running the connections (default: 1 per 2 cores, at least 1)
  --workers N               threads running jobs (default: the core count)
  --queue N                 jobs that may wait for a worker; 503 beyond (default 64)
  --job-timeout SECONDS     per-job time limit, 504 beyond (default 120)
  --read-timeout SECONDS    whole-request read limit, 408 beyond (default 60)
  --idle-timeout SECONDS    keep-alive idle limit (default 30)
  --write-timeout SECONDS   a client that reads nothing for this long is dropped (default 60)
  --shutdown-timeout SECONDS  SIGTERM: time given to in-flight requests (default 30)
  --web-root DIR            the front end served at / (default: DATA/web; DATA: docs/deploy.md)
  --openapi FILE            the file served at /openapi.yaml (default: DATA/openapi.yaml)
  --access-log on|off       one JSON line per request on stderr (default on)
  --max-inflight BYTES      memory budget: bytes that admitted requests may hold (uploads, and
                            2.3x the upload for a model); 503 beyond (default: half the memory)
  --inflight-reserve BYTES  the part of the budget kept for small requests (default: an eighth)
)";

template <typename T>
bool parse_number(std::string_view text, T& out) {
  const auto* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, out);
  return ec == std::errc() && ptr == end;
}

bool parse_seconds(std::string_view text, std::chrono::milliseconds& out) {
  double seconds = 0;
  const auto* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, seconds);
  if (ec != std::errc() || ptr != end || !std::isfinite(seconds) || seconds < 0 ||
      seconds > 86400.0 * 365)
    return false;
  out = std::chrono::milliseconds(static_cast<std::int64_t>(std::llround(seconds * 1000.0)));
  return true;
}

}  // namespace

std::string_view usage() noexcept {
  return kUsage;
}

ParsedArgs parse_args(std::span<const std::string_view> args) {
  ParsedArgs result;
  Config config;
  bool listen_given = false;
  const auto fail = [&](std::string message) {
    result.error = std::move(message);
    return result;
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string_view arg = args[i];
    if (arg == "--help" || arg == "-h") {
      result.help = true;
      return result;
    }
    if (arg.substr(0, 2) != "--") return fail("unexpected argument '" + std::string(arg) + "'");
    std::string_view name = arg.substr(2);
    std::string_view value;
    if (const auto eq = name.find('='); eq != std::string_view::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    } else if (i + 1 < args.size()) {
      value = args[++i];
    } else {
      return fail("option --" + std::string(name) + " needs a value");
    }
    const auto bad = [&] {
      return fail("invalid value '" + std::string(value) + "' for --" + std::string(name));
    };
    if (name == "listen") {
      const auto colon = value.rfind(':');
      if (colon == std::string_view::npos || colon == 0) return bad();
      config.host = std::string(value.substr(0, colon));
      if (!parse_number(value.substr(colon + 1), config.port)) return bad();
      listen_given = true;
    } else if (name == "profiles") {
      config.profiles = std::filesystem::path(value);
    } else if (name == "admin-token-file") {
      config.admin_token_file = std::filesystem::path(value);
    } else if (name == "web-root") {
      config.web_root = std::filesystem::path(value);
    } else if (name == "openapi") {
      config.openapi_file = std::filesystem::path(value);
    } else if (name == "max-body") {
      if (!parse_number(value, config.max_body) || config.max_body == 0) return bad();
    } else if (name == "hold-back") {
      if (!parse_number(value, config.hold_back)) return bad();
    } else if (name == "stream-read-min") {
      if (!parse_number(value, config.stream_read_min)) return bad();
    } else if (name == "max-header") {
      if (!parse_number(value, config.max_header) || config.max_header < 1024) return bad();
    } else if (name == "io-threads") {
      if (!parse_number(value, config.io_threads) || config.io_threads > 256) return bad();
    } else if (name == "workers") {
      if (!parse_number(value, config.workers) || config.workers > 1024) return bad();
    } else if (name == "queue") {
      if (!parse_number(value, config.queue) || config.queue > 1000000) return bad();
    } else if (name == "job-timeout") {
      if (!parse_seconds(value, config.job_timeout)) return bad();
    } else if (name == "read-timeout") {
      if (!parse_seconds(value, config.read_timeout)) return bad();
    } else if (name == "idle-timeout") {
      if (!parse_seconds(value, config.idle_timeout)) return bad();
    } else if (name == "write-timeout") {
      if (!parse_seconds(value, config.write_timeout)) return bad();
    } else if (name == "shutdown-timeout") {
      if (!parse_seconds(value, config.shutdown_timeout)) return bad();
    } else if (name == "max-inflight") {
      std::uint64_t bytes = 0;
      if (!parse_number(value, bytes) || bytes < (std::uint64_t{1} << 20)) return bad();
      config.max_inflight = bytes;
    } else if (name == "inflight-reserve") {
      std::uint64_t bytes = 0;
      if (!parse_number(value, bytes)) return bad();
      config.inflight_reserve = bytes;
    } else if (name == "access-log") {
      if (value != "on" && value != "off") return bad();
      config.access_log = value == "on";
    } else {
      return fail("unknown option --" + std::string(name));
    }
  }
  if (!listen_given) return fail("--listen HOST:PORT is required");
  if (config.max_inflight && config.inflight_reserve &&
      *config.inflight_reserve >= *config.max_inflight)
    return fail("--inflight-reserve must be smaller than --max-inflight");
  result.config = std::move(config);
  return result;
}

Config resolve_memory(Config config) {
  if (!config.max_inflight) config.max_inflight = default_max_inflight(machine_memory());
  if (!config.inflight_reserve)
    config.inflight_reserve = default_inflight_reserve(*config.max_inflight);
  config.inflight_reserve = std::min(*config.inflight_reserve, *config.max_inflight - 1);
  return config;
}

Config resolve_threads(Config config) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (config.io_threads == 0) config.io_threads = std::max(1u, cores / 2);
  if (config.workers == 0) config.workers = cores;
  return config;
}

}  // namespace ncpost::server
