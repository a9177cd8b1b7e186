// The checks of a request's head beyond Beast's parser (server/request_head.hpp), case by case.

#include "request_head.hpp"

#include <gtest/gtest.h>

#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>
#include <string>

namespace ncpost::server {
namespace {

namespace http = boost::beast::http;

// The header Beast makes of `head` (which ends with the blank line).
HeadProblem problem_of(const std::string& head) {
  http::request_parser<http::string_body> parser;
  boost::beast::error_code ec;
  parser.put(boost::asio::buffer(head), ec);
  EXPECT_TRUE(parser.is_header_done()) << head << ": " << ec.message();
  return check_head(parser.get());
}

TEST(RequestHead, TransferEncodingMustEndInChunked) {
  const std::string start = "POST /v1/posts HTTP/1.1\r\nHost: x\r\n";
  EXPECT_EQ(problem_of(start + "Transfer-Encoding: chunked\r\n\r\n"), HeadProblem::None);
  EXPECT_EQ(problem_of(start + "Transfer-Encoding: CHUNKED\r\n\r\n"), HeadProblem::None);
  for (const char* coding : {"gzip", "deflate", "chunked, identity", "identity"})
    EXPECT_EQ(problem_of(start + "Transfer-Encoding: " + coding + "\r\n\r\n"),
              HeadProblem::TransferEncodingNotChunked)
        << coding;
  EXPECT_EQ(problem_of(start + "Transfer-Encoding: gzip, chunked\r\n\r\n"),
            HeadProblem::TransferCodingNotImplemented);
  EXPECT_EQ(problem_of(start + "Transfer-Encoding: gzip\r\nTransfer-Encoding: chunked\r\n\r\n"),
            HeadProblem::TransferCodingNotImplemented)
      << "codings of several fields are one list";
  EXPECT_EQ(problem_of("POST / HTTP/1.0\r\nTransfer-Encoding: chunked\r\n\r\n"),
            HeadProblem::TransferEncodingNotChunked)
      << "HTTP/1.0 has no chunked coding";
  EXPECT_EQ(status_of(HeadProblem::TransferEncodingNotChunked), 400u);
  EXPECT_EQ(status_of(HeadProblem::TransferCodingNotImplemented), 501u);
}

TEST(RequestHead, HostOncePerHttp11Request) {
  EXPECT_EQ(problem_of("GET / HTTP/1.1\r\n\r\n"), HeadProblem::HostMissing);
  EXPECT_EQ(problem_of("GET / HTTP/1.1\r\nHost: a\r\nHost: a\r\n\r\n"), HeadProblem::HostRepeated);
  EXPECT_EQ(problem_of("GET / HTTP/1.0\r\n\r\n"), HeadProblem::None);
  EXPECT_EQ(problem_of("GET / HTTP/1.1\r\nhost: a\r\n\r\n"), HeadProblem::None);
  EXPECT_FALSE(describe(HeadProblem::HostMissing).empty());
}

TEST(RequestHead, ObsFoldIsFoundInTheBytes) {
  EXPECT_TRUE(has_obs_fold("GET / HTTP/1.1\r\nX: a\r\n b\r\n\r\n"));
  EXPECT_TRUE(has_obs_fold("X: a\r\n\tb\r\n"));
  EXPECT_FALSE(has_obs_fold("GET / HTTP/1.1\r\nX: a b\r\nY:\tc\r\n\r\n"));
  EXPECT_FALSE(has_obs_fold("X: a\r\n")) << "a line's end, the next not yet here";
}

TEST(RequestHead, AbsoluteFormBecomesOriginForm) {
  EXPECT_EQ(origin_form("http://127.0.0.1:8080/v1/posts?profile=a"), "/v1/posts?profile=a");
  EXPECT_EQ(origin_form("HTTPS://host/healthz"), "/healthz");
  EXPECT_EQ(origin_form("http://host"), "/");
  EXPECT_EQ(origin_form("http://host?x=1"), "/?x=1");
  EXPECT_FALSE(origin_form("/v1/posts").has_value());
  EXPECT_FALSE(origin_form("*").has_value());
  EXPECT_FALSE(origin_form("ftp://host/x").has_value());
}

TEST(RequestHead, MethodLabelsAreFromAFixedSet) {
  EXPECT_EQ(method_label(http::verb::delete_), "DELETE");
  EXPECT_EQ(method_label(http::verb::unknown), "OTHER");
}

}  // namespace
}  // namespace ncpost::server
