#pragma once
// The harness of the integration tests: starts the real build/bin/ncpostd on 127.0.0.1 with
// port 0, learns the port from the server's start-up log line ({"listening":"127.0.0.1:PORT"}),
// and stops it (SIGTERM, then SIGKILL after a deadline) when the object goes away. Requests go
// through `curl` (the client the issue names) or, for what curl cannot do on purpose (send half
// a request, hang up mid-stream), through RawConnection.

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ncpost::test {

// build/bin/ncpostd (NCPOSTD overrides it).
[[nodiscard]] std::filesystem::path ncpostd_path();
// build/bin/ncpost (NCPOST overrides it).
[[nodiscard]] std::filesystem::path ncpost_path();

struct ServerOptions {
  // Extra command-line arguments, e.g. {"--workers", "1", "--queue", "1"}.
  std::vector<std::string> args;
  // Extra environment, e.g. {"NCPOST_ADMIN_TOKEN", "secret"}; the rest is inherited.
  std::vector<std::pair<std::string, std::string>> env;
  // How long to wait for the "listening" line.
  std::chrono::milliseconds start_timeout{10000};
};

class ServerProcess {
 public:
  explicit ServerProcess(ServerOptions options = {});
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;
  // Stops the server if it still runs (SIGTERM, then SIGKILL after 10 s).
  ~ServerProcess();

  // False when the server did not start; log() says why.
  [[nodiscard]] bool started() const noexcept { return port_ != 0; }
  [[nodiscard]] int port() const noexcept { return port_; }
  [[nodiscard]] pid_t pid() const noexcept { return pid_; }
  // "http://127.0.0.1:PORT"
  [[nodiscard]] std::string url(std::string_view path = "") const;
  // Everything the server wrote to stdout and stderr so far.
  [[nodiscard]] std::string log() const;

  // Sends a signal to the server (SIGTERM, SIGHUP, SIGKILL).
  void signal(int sig) const;
  // Waits for the process to exit; its exit status (or 128 + signal), nullopt on timeout.
  [[nodiscard]] std::optional<int> wait(std::chrono::milliseconds timeout);
  // SIGTERM, then wait; SIGKILL when the deadline passes. Returns the exit status.
  std::optional<int> stop(std::chrono::milliseconds deadline = std::chrono::seconds(10));
  [[nodiscard]] bool running();

 private:
  pid_t pid_ = -1;
  int port_ = 0;
  std::optional<int> status_;
  std::filesystem::path dir_;
  std::filesystem::path log_path_;
};

struct CurlResult {
  int exit_code = -1;   // curl's own exit status (0 ok, 18 partial transfer, 28 timeout, ...)
  int status = 0;       // HTTP status of the last response, 0 when none
  std::string headers;  // raw response header block(s)
  std::string body;
  // The value of a response header (case-insensitive name), empty when absent.
  [[nodiscard]] std::string header(std::string_view name) const;
};

// Runs `curl -sS` with `args` (which name the URL) and collects status, headers and body.
// A bounded run: --max-time defaults to 60 s unless `args` set one.
[[nodiscard]] CurlResult curl(const std::vector<std::string>& args);

// A plain TCP connection to 127.0.0.1:port for requests curl cannot make on purpose.
class RawConnection {
 public:
  explicit RawConnection(int port);
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;
  ~RawConnection();

  [[nodiscard]] bool connected() const noexcept { return fd_ >= 0; }
  // False when the peer closed or the write failed.
  bool send(std::string_view bytes);
  // Appends what arrives within `timeout` (at most `max` bytes) to the returned string; empty
  // on timeout or when the peer closed (closed() tells which).
  [[nodiscard]] std::string receive(std::chrono::milliseconds timeout, std::size_t max = 65536);
  // Reads until `needle` appears in everything received, the peer closes, or `timeout` passes.
  [[nodiscard]] std::string receive_until(std::string_view needle,
                                          std::chrono::milliseconds timeout);
  [[nodiscard]] bool closed() const noexcept { return closed_; }
  // Closes at once; with `reset`, with an RST (SO_LINGER 0), as a client that crashed.
  void close(bool reset = false);

 private:
  int fd_ = -1;
  bool closed_ = false;
};

// A unique temporary directory, removed with its contents when the object goes away.
class TempDir {
 public:
  TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir();
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace ncpost::test
