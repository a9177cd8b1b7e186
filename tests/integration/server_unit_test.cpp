// The pure parts of ncpostd, without a process: the multipart parser, the router, query
// parameters, the block → workingstep map, the command line and problem details.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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

TEST(BlockMap, BlocksBelongToTheWorkingstepWhoseTextTheyAreIn) {
  const std::string text = "%\nO0001\nN10 G0 X0\nN20 G1 X1\n(comment)\nN30 G1 X2\nN40 M30\n%\n";
  // Workingstep 7 starts at "N10", workingstep 9 at "N30"; the end marker before "N40".
  const std::vector<WorkingstepMark> marks = {
      {text.find("N10"), 7, "ROUGH"},
      {text.find("(comment)"), 0, {}},
      {text.find("N30"), 9, "FINISH"},
      {text.find("N40"), 0, {}},
  };
  const auto j = block_map(text, marks);
  EXPECT_EQ(j["blocks"].dump(), R"({"10":7,"20":7,"30":9})");
  ASSERT_EQ(j["workingsteps"].size(), 2u);
  EXPECT_EQ(j["workingsteps"][0]["first_line"], 3);
  EXPECT_EQ(j["workingsteps"][0]["last_line"], 4);
  EXPECT_EQ(j["workingsteps"][1]["name"], "FINISH");
  const auto unnumbered = block_map("G0 X0\nG1 X1\n", {{0, 5, "W"}});
  EXPECT_EQ(unnumbered["blocks"].dump(), R"({"L1":5,"L2":5})");
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
  const std::vector<xslt::FileDiagnostic> diagnostics = {
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

}  // namespace
}  // namespace ncpost::server
