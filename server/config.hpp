#pragma once
// ncpostd's command line: every limit the server enforces is named here, with its default, so
// that docs/server.md, `ncpostd --help` and the code agree.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace ncpost::server {

struct Config {
  std::string host = "127.0.0.1";
  std::uint16_t port = 8080;
  std::optional<std::filesystem::path> profiles;  // none: the built-in profiles (read-only)
  std::optional<std::filesystem::path> admin_token_file;
  std::optional<std::filesystem::path> web_root;      // none: data_directory()/web
  std::optional<std::filesystem::path> openapi_file;  // none: data_directory()/openapi.yaml
  std::uint64_t max_body = std::uint64_t{256} << 20;
  std::uint32_t max_header = 16 * 1024;
  // Raw uploads at least this large to a route that reads a model are read while they arrive
  // (docs/server.md, "Large uploads"); 0 turns it off.
  std::uint64_t stream_read_min = std::uint64_t{1} << 20;
  // The first bytes of a posted program kept back before the head goes out, so that an error
  // found in them is a 422 instead of a cut stream (docs/server.md); 0: stream at once.
  std::uint64_t hold_back = 64 * 1024;
  unsigned io_threads = 0;  // 0: from the core count
  unsigned workers = 0;     // 0: from the core count
  // Jobs that may wait for a worker; beyond workers + queue a job route answers 503 at once.
  unsigned queue = 64;
  std::chrono::milliseconds job_timeout{std::chrono::seconds(120)};
  // From a request's first byte to its last: the slowloris defence (408).
  std::chrono::milliseconds read_timeout{std::chrono::seconds(60)};
  // A kept-alive connection with no new request for this long is closed.
  std::chrono::milliseconds idle_timeout{std::chrono::seconds(30)};
  // A response that the client does not read for this long is abandoned.
  std::chrono::milliseconds write_timeout{std::chrono::seconds(60)};
  // SIGTERM: in-flight requests get this long to finish before they are cut.
  std::chrono::milliseconds shutdown_timeout{std::chrono::seconds(30)};
  bool access_log = true;
  // The memory budget (docs/server.md, "Memory budget"): what admitted requests may hold in
  // bytes; none given: half the machine's (or the cgroup's) memory, read at start.
  std::optional<std::uint64_t> max_inflight;
  // The top of the budget kept for small requests; none given: an eighth of the budget.
  std::optional<std::uint64_t> inflight_reserve;
};

struct ParsedArgs {
  std::optional<Config> config;  // nullopt: `error` says why, or help was asked for
  bool help = false;
  std::string error;
};

// Parses `--name value` / `--name=value` options; durations take seconds (fractions allowed).
[[nodiscard]] ParsedArgs parse_args(std::span<const std::string_view> args);
[[nodiscard]] std::string_view usage() noexcept;

// Resolves the 0 ("from the core count") thread settings.
[[nodiscard]] Config resolve_threads(Config config);
// Resolves the memory budget's defaults from the machine (memory_budget.hpp).
[[nodiscard]] Config resolve_memory(Config config);

}  // namespace ncpost::server
