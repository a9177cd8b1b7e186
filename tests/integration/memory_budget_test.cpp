// The memory budget end to end (issue 24, docs/server.md "Memory budget"): eight concurrent
// uploads of a 100 MB program against a 300 MiB budget are each answered 200 or 503 with
// Retry-After, the server's resident memory stays under the budget plus a stated overhead, and
// /healthz answers throughout; a chunked upload is cut with 503 or 413; /readyz and /metrics
// show the budget; without --max-inflight the budget is half the machine's memory.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <regex>
#include <thread>

#include "corpus.hpp"
#include "server_helpers.hpp"
#include "server_process.hpp"

namespace ncpost::test {
namespace {

using namespace std::chrono_literals;
constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
// What the server holds beyond its budget: the process itself (about 10 MB), a stream's 1 MiB
// of pending text, the stylesheet's transforms, and the allocator's slack (measured: a 104 MB
// post peaks 11 MB above what it reserves).
constexpr std::uint64_t kOverhead = 64 * kMiB;

std::string metric(const std::string& text, const std::string& name) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex("\n" + name + " ([0-9]+)"))) return m[1];
  return "";
}

TEST(ServerMemoryBudget, EightLargeUploadsStayWithinTheBudget) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "resident memory under AddressSanitizer says nothing of the budget; the "
                  "Release pass runs this test";
#endif
  REQUIRE_LARGE_PROGRAM(large, 100);
  const std::uint64_t budget = 300 * kMiB;
  ServerProcess server(with_args({"--max-inflight", std::to_string(budget)}));
  ASSERT_TRUE(server.started()) << server.log();

  std::atomic<bool> done{false};
  std::uint64_t peak = 0;
  std::thread sampler([&] {
    while (!done) {
      peak = std::max(peak, resident_bytes(server.pid()));
      std::this_thread::sleep_for(10ms);
    }
  });
  int health_checks = 0;
  int health_failures = 0;
  std::thread health([&] {
    while (!done) {
      const auto r = curl({"--max-time", "2", server.url("/healthz")});
      ++health_checks;
      if (r.status != 200) ++health_failures;
      std::this_thread::sleep_for(100ms);
    }
  });

  const auto started = Clock::now();
  std::vector<std::future<CurlResult>> uploads;
  for (int i = 0; i < 8; ++i)
    uploads.push_back(std::async(std::launch::async, [&] {
      // curl asks "Expect: 100-continue" for a body this large: a refused upload is not sent.
      return curl({"--data-binary", "@" + large.string(), server.url(kLargeTarget)});
    }));
  int admitted = 0;
  int refused = 0;
  for (auto& upload : uploads) {
    const CurlResult r = upload.get();
    if (r.status == 200) {
      ++admitted;
      EXPECT_EQ(r.exit_code, 0) << "a complete program";
    } else {
      EXPECT_EQ(r.status, 503) << "curl exit " << r.exit_code << "\n" << r.body;
      EXPECT_EQ(r.header("Retry-After"), "1");
      EXPECT_NE(r.body.find("HTTP-011"), std::string::npos) << r.body;
      ++refused;
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  done = true;
  sampler.join();
  health.join();
  EXPECT_GE(admitted, 1);
  EXPECT_EQ(admitted + refused, 8);
  EXPECT_LT(peak, budget + kOverhead) << "peak resident " << (peak >> 20) << " MiB";
  EXPECT_GT(health_checks, 0);
  EXPECT_EQ(health_failures, 0) << "of " << health_checks;
  const std::string metrics = curl({server.url("/metrics")}).body;
  EXPECT_EQ(metric(metrics, "ncpost_inflight_budget_bytes"), std::to_string(budget));
  EXPECT_EQ(metric(metrics, "ncpost_inflight_bytes"), "0") << "every share went back";
  EXPECT_NE(
      metrics.find("ncpost_inflight_refusals_total{reason=\"header\"} " + std::to_string(refused)),
      std::string::npos)
      << metrics;
  RecordProperty("peak_resident_mib", std::to_string(peak >> 20));
  RecordProperty("admitted", admitted);
  RecordProperty("refused", refused);
  RecordProperty("seconds", std::to_string(seconds));
  std::printf("budget 300 MiB: peak resident %llu MiB, %d admitted, %d refused, %.1f s\n",
              static_cast<unsigned long long>(peak >> 20), admitted, refused, seconds);
}

// A budget of 64 MiB keeps 8 MiB for small requests: large ones may hold 56 MiB.
ServerOptions small_budget() {
  return with_args({"--max-inflight", std::to_string(64 * kMiB)});
}

// A raw upload to a model route announced and not sent: its share (2.3 times) is held.
std::unique_ptr<RawConnection> hold(const ServerProcess& server, std::uint64_t bytes) {
  auto c = std::make_unique<RawConnection>(server.port());
  std::string head = post_head("/v1/inspections", bytes);
  head.insert(head.size() - 2, "Expect: 100-continue\r\n");
  EXPECT_TRUE(c->send(head));
  EXPECT_NE(c->receive_until("\r\n\r\n", 5s).find("100 Continue"), std::string::npos);
  return c;
}

TEST(ServerMemoryBudget, ChunkedUploadIsCutWith503OrAloneWith413) {
  ServerProcess server(small_budget());
  ASSERT_TRUE(server.started()) << server.log();
  TempDir dir;
  const auto file = dir.path() / "big.stp";
  {
    std::ofstream out(file, std::ios::binary);
    out << std::string(30 * kMiB, ' ');
  }
  // 30 MB chunked to a model route would hold 69 MB: more than any request may.
  const auto alone = curl({"-H", "Transfer-Encoding: chunked", "--data-binary", "@" + file.string(),
                           server.url("/v1/inspections")});
  EXPECT_EQ(alone.status, 413) << alone.body;
  EXPECT_NE(alone.body.find("HTTP-011"), std::string::npos) << alone.body;
  // With 46 MB held, 10 MB chunked (23 MB) does not fit now: 503, and the connection closes.
  const auto holder = hold(server, 20 * kMiB);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << std::string(10 * kMiB, ' ');
  }
  const auto busy = curl({"-H", "Transfer-Encoding: chunked", "--data-binary", "@" + file.string(),
                          server.url("/v1/inspections")});
  EXPECT_EQ(busy.status, 503) << busy.body;
  EXPECT_EQ(busy.header("Retry-After"), "1");
  // A small post still gets through (the reserve).
  EXPECT_EQ(
      curl({"--data-binary", "@" + src(kCurves).string(), server.url("/v1/posts?profile=linuxcnc")})
          .status,
      200);
  const std::string metrics = curl({server.url("/metrics")}).body;
  EXPECT_NE(metrics.find("ncpost_inflight_refusals_total{reason=\"too_large\"} 1"),
            std::string::npos)
      << metrics;
  EXPECT_NE(metrics.find("ncpost_inflight_refusals_total{reason=\"upload\"} 1"), std::string::npos)
      << metrics;
  // Only the holder's share is left: 2.3 times 20 MiB, rounded up.
  EXPECT_EQ(metric(metrics, "ncpost_inflight_bytes"),
            std::to_string(static_cast<std::uint64_t>(std::ceil(20.0 * kMiB * 2.3))))
      << metrics;
}

TEST(ServerMemoryBudget, ReadyzIsNotReadyWhileTheBudgetIsExhausted) {
  ServerProcess server(small_budget());
  ASSERT_TRUE(server.started()) << server.log();
  EXPECT_EQ(curl({server.url("/readyz")}).status, 200);
  // A header whose upload does not fit now is refused before its body is sent.
  auto holder = hold(server, 22 * kMiB);  // 50.6 MB of 56: less than 8 MiB left
  const auto ready = curl({server.url("/readyz")});
  EXPECT_EQ(ready.status, 503) << ready.body;
  EXPECT_NE(ready.body.find("\"memory_exhausted\": true"), std::string::npos) << ready.body;
  RawConnection refused(server.port());
  std::string head = post_head("/v1/inspections", 4 * kMiB);
  head.insert(head.size() - 2, "Expect: 100-continue\r\n");
  ASSERT_TRUE(refused.send(head));
  const std::string answer = refused.receive_until("\r\n\r\n", 5s);
  EXPECT_EQ(answer.substr(0, 12), "HTTP/1.1 503") << answer;
  EXPECT_NE(answer.find("Retry-After: 1"), std::string::npos) << answer;
  EXPECT_EQ(curl({server.url("/healthz")}).status, 200) << "no body: never refused";
  holder->close(true);  // the client goes: its share goes back
  const auto deadline = Clock::now() + 10s;
  int status = 0;
  do {
    std::this_thread::sleep_for(50ms);
    status = curl({server.url("/readyz")}).status;
  } while (status != 200 && Clock::now() < deadline);
  EXPECT_EQ(status, 200);
}

TEST(ServerMemoryBudget, WithoutTheOptionTheBudgetIsHalfTheMachine) {
  ServerProcess server;
  ASSERT_TRUE(server.started()) << server.log();
  std::smatch m;
  const std::string log = server.log();
  ASSERT_TRUE(std::regex_search(log, m, std::regex("\"max_inflight\":([0-9]+)"))) << log;
  const std::uint64_t budget = std::stoull(m[1]);
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  meminfo >> key >> kib;
  ASSERT_EQ(key, "MemTotal:");
  EXPECT_LE(budget, kib * 1024 / 2) << "at most half the machine (less under a cgroup limit)";
  EXPECT_GT(budget, 0u);
  EXPECT_EQ(metric(curl({server.url("/metrics")}).body, "ncpost_inflight_budget_bytes"),
            std::to_string(budget));
}

}  // namespace
}  // namespace ncpost::test
