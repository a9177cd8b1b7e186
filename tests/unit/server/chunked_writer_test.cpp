// The chunked writer's bytes, read back with Beast's own response parser: the head once, one
// chunk per piece, the last chunk with the trailer of a complete stream, nothing while a write
// is in flight.

#include "chunked_writer.hpp"

#include <gtest/gtest.h>

#include <boost/asio/buffer.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>
#include <string>

namespace ncpost::server {
namespace {

namespace http = boost::beast::http;

std::string bytes_of(const std::vector<boost::asio::const_buffer>& buffers) {
  std::string out;
  for (const auto& b : buffers) out.append(static_cast<const char*>(b.data()), b.size());
  return out;
}

StreamHead head() {
  StreamHead h{http::status::ok, 11};
  h.set(http::field::content_type, "text/plain");
  h.set(http::field::trailer, "Ncpost-Warnings");
  return h;
}

TEST(ChunkedWriter, HeadGoesOutWithTheFirstChunkAndTheStreamParses) {
  StreamHead h = head();
  ChunkedWriter writer(h);
  EXPECT_EQ(writer.sent(), ChunkedWriter::Sent::Nothing);
  std::string wire;
  std::string piece = "%\nG0 X1\n";
  wire += bytes_of(writer.next(piece, false, {}));
  EXPECT_TRUE(piece.empty()) << "the piece is taken, not copied";
  EXPECT_EQ(writer.write(), ChunkedWriter::Write::InFlight);
  EXPECT_EQ(wire.find("HTTP/1.1 200 OK\r\n"), 0u);
  EXPECT_NE(wire.find("Transfer-Encoding: chunked\r\n"), std::string::npos);
  EXPECT_NE(wire.find("\r\n\r\n8\r\n%\nG0 X1\n\r\n"), std::string::npos) << wire;
  writer.written();
  EXPECT_EQ(writer.sent(), ChunkedWriter::Sent::Head);

  piece = std::string(300, 'x');
  const std::string second = bytes_of(writer.next(piece, false, {}));
  EXPECT_EQ(second.substr(0, 5), "12c\r\n") << "sizes are hex, the head is not repeated";
  wire += second;
  writer.written();

  http::fields trailer;
  trailer.set("Ncpost-Warnings", "2");
  piece = "M30\n";
  wire += bytes_of(writer.next(piece, true, trailer));
  writer.written();
  EXPECT_EQ(writer.sent(), ChunkedWriter::Sent::Everything);
  const std::string ending = "4\r\nM30\n\r\n0\r\nNcpost-Warnings: 2\r\n\r\n";
  EXPECT_EQ(wire.substr(wire.size() - ending.size()), ending) << "the last chunk, its trailer";

  http::response_parser<http::string_body> parser;
  boost::beast::error_code ec;
  std::size_t used = 0;
  while (used < wire.size() && !parser.is_done()) {
    const std::size_t n =
        parser.put(boost::asio::buffer(wire.data() + used, wire.size() - used), ec);
    ASSERT_FALSE(ec && ec != http::error::need_more) << ec.message();
    used += n;
    if (n == 0) break;
  }
  ASSERT_TRUE(parser.is_done());
  EXPECT_EQ(used, wire.size());
  EXPECT_EQ(parser.get().body(), "%\nG0 X1\n" + std::string(300, 'x') + "M30\n");
  EXPECT_EQ(parser.get()["Ncpost-Warnings"], "2") << "Beast adds trailer fields to the message";
}

TEST(ChunkedWriter, NothingToWriteAndNothingWhileAWriteIsInFlight) {
  StreamHead h = head();
  ChunkedWriter writer(h);
  std::string piece;
  EXPECT_EQ(writer.next(piece, false, {}).size(), 1u) << "the head alone";
  piece = "more";
  EXPECT_TRUE(writer.next(piece, false, {}).empty()) << "a write is in flight";
  EXPECT_EQ(piece, "more") << "a piece that was not taken stays with the caller";
  writer.written();
  piece.clear();
  EXPECT_TRUE(writer.next(piece, false, {}).empty()) << "no piece, not the end: nothing";
  EXPECT_EQ(writer.write(), ChunkedWriter::Write::Idle);
}

TEST(ChunkedWriter, ShortProgramIsOneWriteAndAnEmptyChunkIsNeverSent) {
  StreamHead h = head();
  ChunkedWriter writer(h);
  std::string piece;
  const std::string wire = bytes_of(writer.next(piece, true, {}));
  EXPECT_EQ(wire.substr(wire.size() - 9), "\r\n\r\n0\r\n\r\n") << "head, then the last chunk";
  EXPECT_EQ(wire.find("\r\n0\r\n\r\n0\r\n"), std::string::npos);
  writer.written();
  EXPECT_EQ(writer.sent(), ChunkedWriter::Sent::Everything);
  piece = "late";
  EXPECT_TRUE(writer.next(piece, false, {}).empty()) << "nothing after the last chunk";
}

}  // namespace
}  // namespace ncpost::server
