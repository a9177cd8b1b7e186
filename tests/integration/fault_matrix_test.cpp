// The fault matrix of docs/reliability.md, the cases no other suite covers: many idle
// connections, clients that leave mid-upload and mid-stream again and again on a one-worker
// server, and SIGTERM while requests are in flight. Each ends with the server still serving
// (or, after SIGTERM, with every accepted request answered completely and exit status 0).

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <csignal>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "corpus.hpp"
#include "server_helpers.hpp"
#include "server_process.hpp"

namespace ncpost::test {
namespace {

using namespace std::chrono_literals;

// Whether `raw` holds one whole response: its head, then all of a chunked body (with its last
// chunk) or Content-Length bytes.
bool whole_response(const std::string& raw) {
  const auto head_end = raw.find("\r\n\r\n");
  if (head_end == std::string::npos) return false;
  const std::string head = raw.substr(0, head_end);
  if (head.find("Transfer-Encoding: chunked") != std::string::npos)
    return decode_chunked(raw).complete;
  const auto at = head.find("Content-Length: ");
  if (at == std::string::npos) return false;
  return raw.size() - head_end - 4 >= std::stoull(head.substr(at + 16));
}

// Reads a response to its end (or until `timeout`).
std::string read_response(RawConnection& c, std::chrono::milliseconds timeout) {
  std::string raw;
  const auto deadline = Clock::now() + timeout;
  while (!whole_response(raw) && !c.closed() && Clock::now() < deadline)
    raw += c.receive(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()),
                     1 << 20);
  return raw;
}

TEST(FaultMatrix, AThousandIdleConnectionsDoNotStopTheService) {
  // A thousand connections on each side of loopback, plus the server's own files.
  rlimit files{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &files), 0);
  if (files.rlim_cur < 4096 && files.rlim_max >= 4096) {
    files.rlim_cur = 4096;
    ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &files), 0);
  }
  if (files.rlim_cur < 2200) GTEST_SKIP() << "RLIMIT_NOFILE " << files.rlim_cur << " is too low";
  ServerProcess server;  // started after the limit was raised: it inherits it
  ASSERT_TRUE(server.started()) << server.log();
  std::vector<std::unique_ptr<RawConnection>> idle;
  for (int i = 0; i < 1000; ++i) {
    idle.push_back(std::make_unique<RawConnection>(server.port()));
    ASSERT_TRUE(idle.back()->connected()) << "connection " << i;
    // A third say nothing, a third half a request line, a third half a header.
    if (i % 3 == 1) {
      ASSERT_TRUE(idle.back()->send("GET /heal"));
    } else if (i % 3 == 2) {
      ASSERT_TRUE(idle.back()->send("GET /healthz HTTP/1.1\r\nHost: x\r\nX-A: "));
    }
  }
  const auto started = Clock::now();
  const auto health = curl({"--max-time", "10", server.url("/healthz")});
  EXPECT_EQ(health.status, 200) << server.log().substr(0, 2000);
  EXPECT_LT(Clock::now() - started, 2s);
  const auto posted = curl({"--max-time", "30", "--data-binary", "@" + src(kCurves).string(),
                            server.url("/v1/posts?profile=linuxcnc")});
  EXPECT_EQ(posted.status, 200);
  // One of the idle ones finishes its request and is answered too.
  ASSERT_TRUE(idle[2]->send("1\r\n\r\n"));
  EXPECT_NE(idle[2]->receive_until("\"ok\"", 5s).find("HTTP/1.1 200"), std::string::npos);
  idle.clear();
  expect_serving(server);
}

TEST(FaultMatrix, ClientsThatLeaveMidUploadAndMidStreamTakeNoSlotAway) {
  REQUIRE_LARGE_PROGRAM(large, 4);
  // One worker and no queue: a slot that a departed client kept would make every later post
  // a 503.
  ServerProcess server(with_args({"--workers", "1", "--queue", "0", "--stream-read-min", "0"}));
  ASSERT_TRUE(server.started()) << server.log();
  const std::string body = read_file(large);
  for (int round = 0; round < 3; ++round) {
    {  // mid-upload: a third of the body, then gone
      RawConnection c(server.port());
      ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body.substr(0, body.size() / 3)));
      std::this_thread::sleep_for(100ms);
      c.close(round % 2 == 0);
    }
    {  // mid-stream: the head and some text arrived, then gone
      RawConnection c(server.port());
      ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body));
      const std::string head = c.receive_until("\r\n\r\n", 60s);
      ASSERT_NE(head.find("HTTP/1.1 200"), std::string::npos) << head.substr(0, 300);
      c.close(round % 2 == 1);
    }
    ASSERT_TRUE(until_idle(server, 30s).has_value()) << "round " << round << "\n" << server.log();
  }
  EXPECT_EQ(gauge(server, "ncpost_jobs_queued"), 0);
  EXPECT_EQ(curl({server.url("/readyz")}).status, 200);
  const auto r = curl(
      {"--data-binary", "@" + src(kCurves).string(), server.url("/v1/posts?profile=linuxcnc")});
  EXPECT_EQ(r.status, 200) << r.body;
}

TEST(FaultMatrix, SigtermUnderLoadAnswersEveryAcceptedRequestCompletely) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  constexpr int kMegabytes = 2;  // a sanitizer's build posts them some ten times slower
#else
  constexpr int kMegabytes = 6;
#endif
  REQUIRE_LARGE_PROGRAM(large, kMegabytes);
  ServerProcess server(with_args({"--workers", "2", "--queue", "16"}));
  ASSERT_TRUE(server.started()) << server.log();
  const std::string big = read_file(large);
  const std::string small = read_file(src(kCurves));
  const std::string expected_small = ncpost("post --profile linuxcnc " + src(kCurves).string());
  ASSERT_FALSE(expected_small.empty());
  constexpr int kClients = 8;
  std::vector<std::unique_ptr<RawConnection>> clients;
  for (int i = 0; i < kClients; ++i) {
    clients.push_back(std::make_unique<RawConnection>(server.port()));
    const std::string& program = i % 2 == 0 ? big : small;
    ASSERT_TRUE(clients.back()->send(post_head(kLargeTarget, program.size()) + program));
  }
  // Accepted: every request was read and admitted (running or queued) before the signal.
  const auto deadline = Clock::now() + 30s;
  long long admitted = 0;
  do {
    admitted = gauge(server, "ncpost_jobs_active").value_or(0) +
               gauge(server, "ncpost_jobs_queued").value_or(0);
    if (admitted >= 2) break;
    std::this_thread::sleep_for(5ms);
  } while (Clock::now() < deadline);
  ASSERT_GE(admitted, 2) << "the load never built up";
  server.signal(SIGTERM);
  const auto signalled = Clock::now();
  std::string first_big;
  for (int i = 0; i < kClients; ++i) {
    const std::string raw = read_response(*clients[i], 120s);
    ASSERT_TRUE(whole_response(raw)) << "request " << i << " was not answered completely:\n"
                                     << raw.substr(0, 300) << "\n"
                                     << server.log();
    EXPECT_EQ(raw.substr(0, 12), "HTTP/1.1 200") << raw.substr(0, 300);
    const RawResponse r = decode_chunked(raw);
    if (i % 2 == 1) {
      EXPECT_EQ(r.body, expected_small) << "request " << i;
    } else if (first_big.empty()) {
      first_big = r.body;
      EXPECT_GT(first_big.size(), 100000u);
    } else {
      EXPECT_EQ(r.body, first_big) << "request " << i;
    }
  }
  // The load outlived the signal: the drain had work to finish.
  EXPECT_GT(Clock::now() - signalled, 100ms);
  const auto status = server.wait(60s);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 0) << server.log();
}

}  // namespace
}  // namespace ncpost::test
