#pragma once
// What the ncpostd integration tests share: paths, the CLI, server options, large programs
// (bench/make_large_stepnc), and a decoder for chunked responses read from a raw socket.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "corpus.hpp"
#include "server_process.hpp"

namespace ncpost::test {

using Clock = std::chrono::steady_clock;

inline std::filesystem::path src(std::string_view relative) {
  return source_dir() / relative;
}

// Runs a command and returns its stdout (the CLI side of byte-identity checks).
inline std::string run_stdout(const std::string& command, int* status = nullptr) {
  FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r");
  std::string out;
  if (pipe == nullptr) return out;
  char buffer[65536];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int s = ::pclose(pipe);
  if (status != nullptr) *status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return out;
}

inline std::string ncpost(const std::string& args, int* status = nullptr) {
  return run_stdout(ncpost_path().string() + " " + args, status);
}

inline ServerOptions with_args(std::vector<std::string> args) {
  ServerOptions options;
  options.args = std::move(args);
  return options;
}

inline void expect_serving(const ServerProcess& server) {
  const auto r = curl({server.url("/healthz")});
  EXPECT_EQ(r.status, 200) << "the server stopped serving after a failure path\n" << server.log();
}

// A large program: NIST's ex1E replicated to `megabytes` (bench/make_large_stepnc), made once
// per test run. Empty when the corpus or the generator is missing.
inline std::filesystem::path large_program(int megabytes) {
  static std::map<int, std::filesystem::path> made;
  static TempDir dir;
  if (auto it = made.find(megabytes); it != made.end()) return it->second;
  const auto corpus = corpus_dir();
  const auto generator = ncpostd_path().parent_path() / "make_large_stepnc";
  if (!corpus || !std::filesystem::exists(generator)) return {};
  const auto out = dir.path() / ("large-" + std::to_string(megabytes) + ".stp");
  const std::string command = generator.string() + " " +
                              (*corpus / "p21" / "nist_toolkit_ex1E.stp").string() + " " +
                              std::to_string(megabytes) + " " + out.string() + " >/dev/null 2>&1";
  if (std::system(command.c_str()) != 0) return {};
  made[megabytes] = out;
  return out;
}

#define REQUIRE_LARGE_PROGRAM(var, mb)                                                      \
  const auto var = large_program(mb);                                                       \
  if (var.empty()) {                                                                        \
    if (corpus_required()) FAIL() << "the corpus or make_large_stepnc is missing";          \
    GTEST_SKIP() << "needs the corpus (nist_toolkit_ex1E.stp) and bench/make_large_stepnc " \
                    "(built with the tests)";                                               \
  }

// What a raw client read of a chunked response: head, decoded body, whether the terminal chunk
// came, and the trailer fields after it (as received, once the blank line that ends them came).
struct RawResponse {
  std::string head;
  std::string body;
  bool complete = false;
  bool closed = false;
  std::string trailer;
};

// Decodes as much of a chunked response as `raw` holds.
inline RawResponse decode_chunked(const std::string& raw) {
  RawResponse r;
  const auto head_end = raw.find("\r\n\r\n");
  if (head_end == std::string::npos) return r;
  r.head = raw.substr(0, head_end);
  std::size_t pos = head_end + 4;
  for (;;) {
    const auto eol = raw.find("\r\n", pos);
    if (eol == std::string::npos) return r;
    const std::size_t size = std::stoul(raw.substr(pos, eol - pos), nullptr, 16);
    if (size == 0) {
      const auto trailer_end = raw.find("\r\n\r\n", eol);
      r.complete = trailer_end != std::string::npos || raw.compare(eol, 4, "\r\n\r\n") == 0;
      if (trailer_end != std::string::npos && trailer_end > eol)
        r.trailer = raw.substr(eol + 2, trailer_end - eol - 2);
      return r;
    }
    if (raw.size() < eol + 2 + size + 2) {
      r.body += raw.substr(eol + 2, raw.size() - eol - 2);  // partial chunk
      return r;
    }
    r.body += raw.substr(eol + 2, size);
    pos = eol + 2 + size + 2;
  }
}

// The resident memory of a process, from /proc (0 when it cannot be read).
inline std::uint64_t resident_bytes(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

// Everything a raw connection receives until the server closes it (or `timeout` passes).
inline std::string receive_all(RawConnection& c, std::chrono::milliseconds timeout) {
  std::string all;
  const auto deadline = Clock::now() + timeout;
  while (!c.closed() && Clock::now() < deadline)
    all +=
        c.receive(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
  return all;
}

inline std::size_t count_of(std::string_view text, std::string_view needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string_view::npos; at = text.find(needle, at + 1))
    ++n;
  return n;
}

inline std::string post_head(std::string_view target, std::size_t length) {
  return "POST " + std::string(target) +
         " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: " + std::to_string(length) + "\r\n\r\n";
}

// A gauge of /metrics without labels (ncpost_jobs_active, ncpost_jobs_queued); nullopt when
// the server did not answer.
inline std::optional<long long> gauge(const ServerProcess& server, const std::string& name) {
  const auto r = curl({server.url("/metrics")});
  std::smatch m;
  const std::regex line("\n" + name + " ([0-9]+)\n");
  if (r.status != 200 || !std::regex_search(r.body, m, line)) return std::nullopt;
  return std::stoll(m[1]);
}

// How long until no job runs, polling /metrics; nullopt when `limit` passes first.
inline std::optional<std::chrono::milliseconds> until_idle(const ServerProcess& server,
                                                           std::chrono::milliseconds limit) {
  const auto start = Clock::now();
  while (Clock::now() - start < limit) {
    if (gauge(server, "ncpost_jobs_active") == 0)
      return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return std::nullopt;
}

inline const std::string kCurves = "tests/golden/trace/cases/curves.stp";
// The replicated ex1E keeps P21 ids as tool numbers; linuxcnc's tool range takes them (fanuc-0i
// stops at T9999 with RENDER-001), so the whole program is posted.
inline constexpr std::string_view kLargeTarget = "/v1/posts?profile=linuxcnc";

}  // namespace ncpost::test
