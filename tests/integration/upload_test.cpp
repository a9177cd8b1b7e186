// ncpostd with large uploads (docs/server.md, "Large uploads"): a raw upload read while it
// arrives gives the same program, ETag and diagnostics as one read whole; warnings of a
// successful stream come in its trailer; and a job cancelled while it reads (client gone, time
// limit) lets go of its worker at once instead of when the read ends.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <thread>

#include "corpus.hpp"
#include "server_helpers.hpp"
#include "server_process.hpp"

namespace ncpost::test {
namespace {

using namespace std::chrono_literals;

const std::string kEx1E = "p21/nist_toolkit_ex1E.stp";

// A Server-Timing metric's duration in ms ("read;dur=12.5"), or -1.
double timing(const std::string& head, const std::string& metric) {
  std::smatch m;
  const std::regex re("[ ,:]" + metric + ";dur=([0-9.]+)");
  return std::regex_search(head, m, re) ? std::stod(m[1]) : -1;
}

std::string trailer_field(const std::string& trailer, const std::string& name) {
  std::smatch m;
  const std::regex re("(?:^|\r\n)" + name + ": ([^\r\n]*)", std::regex::icase);
  return std::regex_search(trailer, m, re) ? m[1].str() : std::string();
}

TEST(LargeUploads, ReadWhileArrivingGivesTheSameProgramAndETag) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto file = corpus / kEx1E;
  // ex1E (95 KB) is read as it arrives from 4 KB on, in slices of 4 KB.
  ServerProcess streaming(with_args({"--stream-read-min", "4096"}));
  ServerProcess whole(with_args({"--stream-read-min", "0"}));
  ASSERT_TRUE(streaming.started()) << streaming.log();
  ASSERT_TRUE(whole.started()) << whole.log();
  const std::string target = "/v1/posts?profile=fanuc-0i&name=nist_toolkit_ex1E.stp";
  const auto a = curl({"--data-binary", "@" + file.string(), streaming.url(target)});
  const auto b = curl({"--data-binary", "@" + file.string(), whole.url(target)});
  const auto c =
      curl({"-F", "file=@" + file.string(), streaming.url("/v1/posts?profile=fanuc-0i")});
  ASSERT_EQ(a.status, 200) << a.body.substr(0, 2000);
  ASSERT_EQ(b.status, 200);
  ASSERT_EQ(c.status, 200);
  EXPECT_NE(a.header("Server-Timing").find("arrival;desc="), std::string::npos)
      << a.header("Server-Timing");
  EXPECT_EQ(b.header("Server-Timing").find("arrival"), std::string::npos);
  EXPECT_EQ(a.body, ncpost("post --profile fanuc-0i " + file.string()));
  EXPECT_EQ(a.body, b.body);
  EXPECT_EQ(a.body, c.body);
  // The ETag hashes the input, however it came: raw and streamed, raw and whole, multipart.
  EXPECT_FALSE(a.header("ETag").empty());
  EXPECT_EQ(a.header("ETag"), b.header("ETag"));
  EXPECT_EQ(a.header("ETag"), c.header("ETag"));
  const auto again = curl({"--data-binary", "@" + file.string(), "-H",
                           "If-None-Match: " + a.header("ETag"), streaming.url(target)});
  EXPECT_EQ(again.status, 304);
  expect_serving(streaming);
}

TEST(LargeUploads, ABrokenUploadIsRejectedWithTheSameDiagnostics) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::string text = read_file(corpus / kEx1E);
  // A lexical error and a dangling reference in the middle, where slices read first.
  const auto middle = text.find("\n#", text.size() / 2);
  ASSERT_NE(middle, std::string::npos);
  text.insert(middle + 1, "#7777777=CARTESIAN_POINT('',(1.,2.,3.E));\n#7777778=A(#8888888);\n");
  TempDir dir;
  const auto broken = dir.path() / "broken.stp";
  std::ofstream(broken, std::ios::binary) << text;
  ServerProcess streaming(with_args({"--stream-read-min", "4096"}));
  ServerProcess whole(with_args({"--stream-read-min", "0"}));
  ASSERT_TRUE(streaming.started()) << streaming.log();
  ASSERT_TRUE(whole.started()) << whole.log();
  const auto a = curl({"--data-binary", "@" + broken.string(),
                       streaming.url("/v1/posts?profile=fanuc-0i&name=broken.stp")});
  const auto b = curl({"--data-binary", "@" + broken.string(),
                       whole.url("/v1/posts?profile=fanuc-0i&name=broken.stp")});
  EXPECT_EQ(a.status, 422);
  EXPECT_EQ(a.body, b.body);
  EXPECT_NE(a.body.find("P21-"), std::string::npos) << a.body;
  expect_serving(streaming);
}

TEST(LargeUploads, XmlIsTakenBackAndReadAsP28) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  TempDir dir;
  const auto xml = dir.path() / "ex1E.stpx";
  {
    std::ofstream out(xml, std::ios::binary);
    out << ncpost("convert --to p28 " + (corpus / kEx1E).string());
  }
  ASSERT_GT(std::filesystem::file_size(xml), 100000u);
  ServerProcess streaming(with_args({"--stream-read-min", "4096"}));
  ServerProcess whole(with_args({"--stream-read-min", "0"}));
  ASSERT_TRUE(streaming.started()) << streaming.log();
  ASSERT_TRUE(whole.started()) << whole.log();
  const std::string target = "/v1/conversions?to=p21";
  const auto a = curl({"--data-binary", "@" + xml.string(), streaming.url(target)});
  const auto b = curl({"--data-binary", "@" + xml.string(), whole.url(target)});
  ASSERT_EQ(a.status, 200) << a.body.substr(0, 2000);
  EXPECT_EQ(a.body, b.body);
  EXPECT_EQ(a.body, ncpost("convert --to p21 " + xml.string()));
  expect_serving(streaming);
}

TEST(LargeUploads, EarlyAnswersLetGoOfTheUpload) {
  REQUIRE_LARGE_PROGRAM(large, 2);
  // One worker, one stream-read slot: each answer below must give it back.
  ServerProcess server(with_args({"--workers", "1"}));
  ASSERT_TRUE(server.started()) << server.log();
  const std::string file = "@" + large.string();
  EXPECT_EQ(curl({"--data-binary", file, server.url("/v1/posts?profile=none")}).status, 404);
  EXPECT_EQ(curl({"--data-binary", file, server.url("/v1/traces?format=bogus")}).status, 400);
  EXPECT_EQ(curl({"--data-binary", file, server.url("/v1/conversions")}).status, 400);
  const auto first = curl({"--data-binary", file, server.url(std::string(kLargeTarget))});
  ASSERT_EQ(first.status, 200);
  const auto again = curl({"--data-binary", file, "-H", "If-None-Match: " + first.header("ETag"),
                           server.url(std::string(kLargeTarget))});
  EXPECT_EQ(again.status, 304);
  const auto last = curl({"--data-binary", file, server.url(std::string(kLargeTarget))});
  EXPECT_EQ(last.status, 200);
  EXPECT_NE(last.header("Server-Timing").find("arrival;desc="), std::string::npos)
      << last.header("Server-Timing");
  EXPECT_EQ(last.body, first.body);
  EXPECT_EQ(until_idle(server, 20s).has_value(), true);
  expect_serving(server);
}

TEST(LargeUploads, MostOfAnUploadIsReadBeforeItsLastByte) {
  REQUIRE_LARGE_PROGRAM(large, 24);
  ServerProcess server;
  ASSERT_TRUE(server.started()) << server.log();
  const std::string body = read_file(large);
  RawConnection c(server.port());
  // Two thirds, a pause in which the slices read them, then the rest.
  const std::size_t part = body.size() * 2 / 3;
  ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body.substr(0, part)));
  std::this_thread::sleep_for(3s);
  ASSERT_TRUE(c.send(std::string_view(body).substr(part)));
  const std::string head = c.receive_until("\r\n\r\n", 120s);
  ASSERT_NE(head.find("HTTP/1.1 200"), std::string::npos) << head.substr(0, 400);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(head, m, std::regex("read ([0-9]+)% while arriving"))) << head;
  // Two thirds had arrived three seconds before the end: the slices read most of them.
  EXPECT_GE(std::stoi(m[1]), 40) << head;
  RecordProperty("read_while_arriving_percent", m[1].str());
  c.close(true);
  expect_serving(server);
}

TEST(LargeUploads, UploadsThatStopHalfWayLeaveTheServerServing) {
  REQUIRE_LARGE_PROGRAM(large, 24);
  // One worker: one stream-read slot. Each abandoned upload must give its slot back, or the
  // last post below would not be read while it arrives.
  ServerProcess server(with_args({"--workers", "1", "--read-timeout", "2"}));
  ASSERT_TRUE(server.started()) << server.log();
  const std::string body = read_file(large);
  for (int i = 0; i < 3; ++i) {
    RawConnection c(server.port());
    ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body.substr(0, body.size() / 3)));
    std::this_thread::sleep_for(300ms);
    c.close(i % 2 == 0);  // reset, or a plain close
  }
  {
    // One that stops sending: 408 after --read-timeout.
    RawConnection c(server.port());
    ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body.substr(0, body.size() / 3)));
    const std::string answer = c.receive_until("\r\n\r\n", 20s);
    EXPECT_NE(answer.find("HTTP/1.1 408"), std::string::npos) << answer.substr(0, 300);
  }
  EXPECT_EQ(until_idle(server, 20s).has_value(), true);
  RawConnection c(server.port());
  ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body));
  const std::string head = c.receive_until("\r\n\r\n", 120s);
  EXPECT_NE(head.find("HTTP/1.1 200"), std::string::npos) << head.substr(0, 400);
  EXPECT_NE(head.find("arrival;desc="), std::string::npos) << head;
  c.close(true);
  expect_serving(server);
}

TEST(StreamTrailer, WarningsOfASuccessfulStreamComeAfterTheLastChunk) {
  std::string text = read_file(src(kCurves));
  text.insert(text.rfind("ENDSEC;"), "#999999=SOMETHING_ELSE(1.);\n");
  ServerProcess server;
  ASSERT_TRUE(server.started()) << server.log();
  for (const bool with_warning : {true, false}) {
    SCOPED_TRACE(with_warning ? "with a warning" : "clean");
    const std::string body = with_warning ? text : read_file(src(kCurves));
    RawConnection c(server.port());
    ASSERT_TRUE(c.send(post_head("/v1/posts?profile=linuxcnc&name=w.stp", body.size()) + body));
    std::string raw = c.receive_until("\r\n0\r\n", 30s);
    RawResponse r = decode_chunked(raw);
    while (!r.complete && !c.closed()) {
      raw += c.receive(10s);
      r = decode_chunked(raw);
    }
    ASSERT_TRUE(r.complete) << raw.substr(0, 400);
    EXPECT_NE(r.head.find("Trailer: Ncpost-Warnings, Ncpost-Diagnostics"), std::string::npos)
        << r.head;
    EXPECT_EQ(trailer_field(r.trailer, "Ncpost-Warnings"), with_warning ? "1" : "0") << r.trailer;
    const std::string listed = trailer_field(r.trailer, "Ncpost-Diagnostics");
    if (with_warning) {
      EXPECT_NE(listed.find("\"code\":\"EXP-060\""), std::string::npos) << listed;
      EXPECT_NE(listed.find("\"file\":\"w.stp\""), std::string::npos) << listed;
      EXPECT_NE(listed.find("\"severity\":\"warning\""), std::string::npos) << listed;
    } else {
      EXPECT_EQ(listed, "[]");
    }
  }
  // curl reads the trailer too: it writes trailer fields after the header block.
  TempDir dir;
  std::ofstream(dir.path() / "w.stp", std::ios::binary) << text;
  const auto via_curl = curl({"--data-binary", "@" + (dir.path() / "w.stp").string(),
                              server.url("/v1/posts?profile=linuxcnc")});
  EXPECT_EQ(via_curl.status, 200);
  EXPECT_NE(via_curl.headers.find("Ncpost-Warnings: 1"), std::string::npos) << via_curl.headers;
  expect_serving(server);
}

// ---- cancellation while reading -------------------------------------------------------------

// Large enough that reading takes clearly longer than noticing a cancellation: 100 MB in a
// Release build; under AddressSanitizer, which reads several times slower, 24 MB does (and
// keeps the tests within their time limit).
#if defined(__SANITIZE_ADDRESS__)
constexpr int kReadMegabytes = 24;
#else
constexpr int kReadMegabytes = 100;
#endif

// How long this machine takes to read (and check) the large program in a job: from a post's
// Server-Timing. The server reads whole uploads (--stream-read-min 0), in its one worker.
struct ReadCost {
  double read_ms = -1;
  double check_ms = -1;
};

ReadCost measure_read(const ServerProcess& server, const std::string& body) {
  RawConnection c(server.port());
  EXPECT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body));
  const std::string head = c.receive_until("\r\n\r\n", 120s);
  c.close(true);
  EXPECT_NE(head.find("HTTP/1.1 200"), std::string::npos) << head.substr(0, 400);
  return {timing(head, "read"), timing(head, "check")};
}

TEST(ReadCancellation, ClientGoneDuringTheReadFreesTheWorkerAtOnce) {
  REQUIRE_LARGE_PROGRAM(large, kReadMegabytes);
  ServerProcess server(with_args({"--workers", "1", "--stream-read-min", "0"}));
  ASSERT_TRUE(server.started()) << server.log();
  const std::string body = read_file(large);
  const ReadCost cost = measure_read(server, body);
  ASSERT_GT(cost.read_ms, 0);
  ASSERT_TRUE(until_idle(server, 60s).has_value());
  if (cost.read_ms < 200)
    GTEST_SKIP() << "reading takes " << cost.read_ms << " ms here: too short to tell";
  RawConnection c(server.port());
  ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body));
  // Hang up while the job reads: a quarter of the way in.
  std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(cost.read_ms / 4)));
  c.close(true);
  const auto freed = until_idle(server, 60s);
  ASSERT_TRUE(freed.has_value());
  // Without a cancellation point the worker would stay until the read and check ended: about
  // three quarters of the read plus the check from now.
  EXPECT_LT(freed->count(), cost.read_ms / 2)
      << "read " << cost.read_ms << " ms, check " << cost.check_ms << " ms";
  RecordProperty("read_ms", std::to_string(cost.read_ms));
  RecordProperty("freed_after_ms", std::to_string(freed->count()));
  EXPECT_NE(server.log().find("\"complete\":false"), std::string::npos);
  expect_serving(server);
}

TEST(ReadCancellation, TimeLimitDuringTheReadIs504AndFreesTheWorker) {
  REQUIRE_LARGE_PROGRAM(large, kReadMegabytes);
  double read_ms = 0;
  {
    ServerProcess probe(with_args({"--workers", "1", "--stream-read-min", "0"}));
    ASSERT_TRUE(probe.started()) << probe.log();
    read_ms = measure_read(probe, read_file(large)).read_ms;
  }
  if (read_ms < 200) GTEST_SKIP() << "reading takes " << read_ms << " ms here: too short to tell";
  const double limit_s = read_ms / 4 / 1000;
  ServerProcess server(with_args(
      {"--workers", "1", "--stream-read-min", "0", "--job-timeout", std::to_string(limit_s)}));
  ASSERT_TRUE(server.started()) << server.log();
  const std::string body = read_file(large);
  RawConnection c(server.port());
  ASSERT_TRUE(c.send(post_head(kLargeTarget, body.size()) + body));
  const std::string answer = c.receive_until("\r\n\r\n", 60s);
  EXPECT_NE(answer.find("HTTP/1.1 504"), std::string::npos) << answer.substr(0, 400);
  const auto freed = until_idle(server, 60s);
  ASSERT_TRUE(freed.has_value());
  EXPECT_LT(freed->count(), read_ms / 2) << "read " << read_ms << " ms";
  expect_serving(server);
}

}  // namespace
}  // namespace ncpost::test
