// The pure parts of ncpostd, without a process: the multipart parser, the router, query
// parameters, the command line, problem details, the access log
// line, the ETag hash and the diagnostics trailer.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "access_log.hpp"
#include "body_hash.hpp"
#include "config.hpp"
#include "handlers.hpp"
#include "multipart.hpp"

namespace ncpost::server {
namespace {

TEST(Multipart, TwoPartsWithFileName) {
  const std::string body =
      "preamble\r\n--XyZ\r\nContent-Disposition: form-data; name=\"profile\"\r\n\r\n{\"id\":1}"
      "\r\n--XyZ\r\nContent-Disposition: form-data; name=\"stylesheet\"; filename=\"post.xsl\"\r\n"
      "Content-Type: application/xslt+xml\r\n\r\n<xsl/>\r\n--\r\nnot a boundary\r\n--XyZ--\r\n";
  const auto r = parse_multipart(body, "XyZ");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.parts.size(), 2u);
  EXPECT_EQ(r.parts[0].name, "profile");
  EXPECT_EQ(r.parts[0].body, "{\"id\":1}");
  EXPECT_EQ(r.parts[1].filename, "post.xsl");
  EXPECT_EQ(r.parts[1].content_type, "application/xslt+xml");
  EXPECT_EQ(r.parts[1].body, "<xsl/>\r\n--\r\nnot a boundary");
  EXPECT_EQ(r.find("stylesheet"), &r.parts[1]);
  EXPECT_EQ(r.find("file"), nullptr);
}

TEST(Multipart, RejectsMalformedBodies) {
  const auto part = [](std::string headers, std::string content) {
    return "--b\r\n" + headers + "\r\n\r\n" + content;
  };
  EXPECT_FALSE(parse_multipart("no boundary at all", "b").ok());
  EXPECT_FALSE(parse_multipart(part("Content-Disposition: form-data; name=\"a\"", "x"), "b").ok())
      << "no closing delimiter";
  EXPECT_FALSE(parse_multipart(part("Content-Type: text/plain", "x") + "\r\n--b--", "b").ok())
      << "no Content-Disposition";
  EXPECT_FALSE(
      parse_multipart(part("Content-Disposition: attachment; name=\"a\"", "x") + "\r\n--b--", "b")
          .ok());
  EXPECT_FALSE(parse_multipart(part("Content-Disposition: form-data", "x") + "\r\n--b--", "b").ok())
      << "no name";
  EXPECT_FALSE(parse_multipart(
                   part("Content-Disposition: form-data; name=\"a\"\nX: y", "x") + "\r\n--b--", "b")
                   .ok())
      << "bare LF inside a header line is not a line end";
  EXPECT_FALSE(
      parse_multipart("--b\nContent-Disposition: form-data; name=a\n\nx\n--b--", "b").ok());
  EXPECT_FALSE(parse_multipart("--b\r\n", "").ok());
}

TEST(Multipart, Limits) {
  std::string body;
  for (int i = 0; i < 3; ++i)
    body +=
        "--b\r\nContent-Disposition: form-data; name=\"p" + std::to_string(i) + "\"\r\n\r\nx\r\n";
  body += "--b--";
  MultipartLimits limits;
  limits.max_parts = 2;
  EXPECT_NE(parse_multipart(body, "b", limits).error.find("more than 2"), std::string::npos);
  limits.max_parts = 3;
  EXPECT_TRUE(parse_multipart(body, "b", limits).ok());
  limits.max_part_header_bytes = 10;
  EXPECT_NE(parse_multipart(body, "b", limits).error.find("headers longer"), std::string::npos);
}

TEST(Multipart, BoundaryFromContentType) {
  EXPECT_EQ(multipart_boundary("multipart/form-data; boundary=abc"), "abc");
  EXPECT_EQ(multipart_boundary("Multipart/Form-Data; charset=x; boundary=\"a b\""), "a b");
  EXPECT_FALSE(multipart_boundary("multipart/form-data"));
  EXPECT_FALSE(multipart_boundary("text/plain; boundary=abc"));
  EXPECT_FALSE(multipart_boundary("multipart/form-data; boundary=" + std::string(71, 'x')));
}

TEST(Router, MatchesRoutesAndParameters) {
  auto m = match_route(http::verb::post, "/v1/posts?profile=fanuc-0i");
  ASSERT_NE(m.route, nullptr);
  EXPECT_EQ(m.route->name, "POST /v1/posts");
  EXPECT_EQ(m.route->where, Where::Worker);
  m = match_route(http::verb::put, "/v1/profiles/haas-ngc");
  ASSERT_NE(m.route, nullptr);
  EXPECT_EQ(m.id, "haas-ngc");
  m = match_route(http::verb::get, "/v1/profiles/a/b");
  EXPECT_EQ(m.route, nullptr);
  EXPECT_EQ(m.status, 404u);
  m = match_route(http::verb::post, "/healthz");
  EXPECT_EQ(m.status, 405u);
  EXPECT_EQ(m.allow, "GET");
  m = match_route(http::verb::head, "/healthz");
  EXPECT_NE(m.route, nullptr);
}

TEST(Router, QueryParameters) {
  EXPECT_EQ(query_param("/x?a=1&profile=fanuc%2D0i&b", "profile"), "fanuc-0i");
  EXPECT_EQ(query_param("/x?a=1&b", "b"), "");
  EXPECT_FALSE(query_param("/x?a=1", "profile"));
  EXPECT_FALSE(query_param("/x", "a"));
  EXPECT_EQ(query_param("/x?name=a+b%20c", "name"), "a b c");
}

TEST(Config, ParsesLimitsAndRejectsNonsense) {
  std::vector<std::string_view> args = {
      "--listen", "127.0.0.1:0", "--max-body=1000", "--job-timeout", "0.25", "--workers", "3"};
  auto parsed = parse_args(args);
  ASSERT_TRUE(parsed.config) << parsed.error;
  EXPECT_EQ(parsed.config->port, 0);
  EXPECT_EQ(parsed.config->max_body, 1000u);
  EXPECT_EQ(parsed.config->job_timeout, std::chrono::milliseconds(250));
  EXPECT_EQ(parsed.config->workers, 3u);
  for (std::vector<std::string_view> bad : {std::vector<std::string_view>{},
                                            {"--listen", "nowhere"},
                                            {"--listen", "h:99999"},
                                            {"--listen", "h:1", "--max-body", "-5"},
                                            {"--listen", "h:1", "--frobnicate", "1"},
                                            {"--listen", "h:1", "--read-timeout", "soon"},
                                            {"--listen"}}) {
    EXPECT_FALSE(parse_args(bad).config) << (bad.empty() ? "" : bad.back());
  }
  const Config resolved = resolve_threads(*parsed.config);
  EXPECT_GE(resolved.io_threads, 1u);
  EXPECT_EQ(resolved.workers, 3u);
}

TEST(Problem, Rfc9457ShapeWithDiagnostics) {
  const std::vector<diag::FileDiagnostic> diagnostics = {
      {"up.stp", diag::make(diag::Code::P21DanglingReference, 10, 1, "#12 is not defined")}};
  const Response r = problem(422, "input-rejected", "Rejected", "see diagnostics", diagnostics);
  EXPECT_EQ(r.result_int(), 422u);
  EXPECT_EQ(r[http::field::content_type], "application/problem+json");
  const auto j = nlohmann::json::parse(r.body());
  EXPECT_EQ(j["status"], 422);
  EXPECT_EQ(j["title"], "Rejected");
  EXPECT_EQ(j["type"], "urn:ncpost:problem:input-rejected");
  EXPECT_EQ(j["diagnostics"][0]["code"], "P21-040");
  EXPECT_EQ(j["diagnostics"][0]["line"], 10);
  EXPECT_EQ(j["diagnostics"][0]["column"], 1);
  EXPECT_EQ(j["diagnostics"][0]["severity"], "error");
  EXPECT_EQ(j["diagnostics"][0]["file"], "up.stp");
}

TEST(Problem, ClientTextThatIsNotUtf8IsReplacedNotThrown) {
  // A path or file name may hold any bytes; the JSON library would throw on them.
  const std::vector<diag::FileDiagnostic> diagnostics = {
      {"bad\xff.stp", diag::make(diag::Code::P21DanglingReference, 1, 1, "x")}};
  const Response r = problem(404, "HTTP-009", "Not found", "no route for /\xfe\xff", diagnostics);
  const auto j = nlohmann::json::parse(r.body());
  EXPECT_EQ(j["detail"], "no route for /\xef\xbf\xbd\xef\xbf\xbd");
  EXPECT_EQ(j["diagnostics"][0]["file"], "bad\xef\xbf\xbd.stp");
}

TEST(AccessLog, OneValidJsonObjectWhateverTheClientSent) {
  AccessRecord r;
  r.request_id = "abc-1";
  r.remote = "127.0.0.1:5000";
  r.method = "POST";
  r.path = "/v1/\"q\\\n\x01\x7f/\xc3\xa9/\xe2\x82\xac/\xf0\x9f\x98\x80/\xff\xc0\xaf\xed\xa0\x80";
  r.route = "POST /v1/posts";
  r.profile = "fanuc-0i";
  r.status = 200;
  r.bytes_in = 12;
  r.bytes_out = 3456;
  r.duration_ms = 1.23456;
  r.complete = true;
  const std::string line = access_line(r);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  const auto j = nlohmann::json::parse(line);
  EXPECT_EQ(line.rfind("{\"event\":\"access\",\"request_id\":\"abc-1\"", 0), 0u) << line;
  // Quotes, backslashes and control characters escaped; valid UTF-8 kept (é € 😀); each byte
  // of an invalid sequence (a stray 0xFF, an overlong '/', a surrogate) one U+FFFD.
  EXPECT_EQ(j["path"],
            "/v1/\"q\\\n\x01\x7f/\xc3\xa9/\xe2\x82\xac/\xf0\x9f\x98\x80/"
            "\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd");
  EXPECT_EQ(j["status"], 200);
  EXPECT_EQ(j["bytes_out"], 3456);
  EXPECT_DOUBLE_EQ(j["duration_ms"].get<double>(), 1.235);
  EXPECT_EQ(j["profile"], "fanuc-0i");
  EXPECT_EQ(j["complete"], true);
  r.profile = {};
  r.complete = false;
  const auto k = nlohmann::json::parse(access_line(r));
  EXPECT_FALSE(k.contains("profile"));
  EXPECT_EQ(k["complete"], false);
}

TEST(BodyHash, PublishedXxh64VectorsWholeAndInPieces) {
  // XXH64, seed 0: the published values (also what Debian's libxxhash computes).
  const std::vector<std::pair<std::string, std::uint64_t>> vectors = {
      {"", 0xef46db3751d8e999ULL},
      {"a", 0xd24ec4f1a98c6e5bULL},
      {"ABC", 0xe66ae7354fcfee98ULL},
      {"xxhash", 0x32dd38952c4bc720ULL},
      {"abcdefghijklmnopqrstuvwxyz12345", 0x467605901b01d6f6ULL},
      {"abcdefghijklmnopqrstuvwxyz123456", 0x0022ee3b5a18531bULL},
      {"Nobody inspects the spammish repetition", 0xfbcea83c8a378bf1ULL},
  };
  for (const auto& [text, expected] : vectors) {
    EXPECT_EQ(body_hash(text), expected) << text;
    for (std::size_t piece = 1; piece <= 33; piece += 4) {
      BodyHash h;
      for (std::size_t at = 0; at < text.size(); at += piece)
        h.update(std::string_view(text).substr(at, piece));
      EXPECT_EQ(h.digest(), expected) << text << " in pieces of " << piece;
    }
  }
  std::string long_text;
  for (int i = 0; i < 4; ++i)
    for (int b = 0; b < 256; ++b) long_text += static_cast<char>(b);
  long_text += "tail!";
  EXPECT_EQ(body_hash(long_text), 0x92fd9dccca84e2ebULL);
}

TEST(DiagnosticsTrailer, CountsAllAndListsWhatFitsAsAsciiJson) {
  std::vector<diag::FileDiagnostic> diagnostics;
  EXPECT_EQ(diagnostics_trailer(diagnostics)["Ncpost-Warnings"], "0");
  EXPECT_EQ(diagnostics_trailer(diagnostics)["Ncpost-Diagnostics"], "[]");
  for (int i = 0; i < 200; ++i)
    diagnostics.push_back(
        {"f\xc3\xa9.stp", diag::make(diag::Code::ExpUnknownEntity, i + 1, 1,
                                     "entity \xe2\x82\xac is not in the schema")});
  const http::fields trailer = diagnostics_trailer(diagnostics);
  EXPECT_EQ(trailer["Ncpost-Warnings"], "200");
  const std::string listed(trailer["Ncpost-Diagnostics"]);
  EXPECT_LE(listed.size(), kMaxDiagnosticsTrailer);
  for (const char c : listed) ASSERT_TRUE(c >= 0x20 && c < 0x7f) << "not a plain field value";
  const auto j = nlohmann::json::parse(listed);
  ASSERT_GT(j.size(), 10u);
  EXPECT_LT(j.size(), 200u);
  EXPECT_EQ(j[0]["file"], "f\xc3\xa9.stp");
  EXPECT_EQ(j[0]["code"], "EXP-060");
  EXPECT_EQ(j[0]["severity"], "warning");
  EXPECT_EQ(j[1]["line"], 2);
}

}  // namespace
}  // namespace ncpost::server
