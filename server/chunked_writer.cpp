#include "chunked_writer.hpp"

#include <boost/beast/core/buffers_range.hpp>
#include <boost/beast/http/serializer.hpp>
#include <cstdio>

namespace ncpost::server {

namespace http = boost::beast::http;

ChunkedWriter::ChunkedWriter(StreamHead& head) {
  head.chunked(true);
  http::response_serializer<http::empty_body> serializer(head);
  serializer.split(true);
  boost::beast::error_code ec;
  while (!serializer.is_header_done() && !ec) {
    serializer.next(ec, [&](boost::beast::error_code& e, const auto& buffers) {
      e = {};
      for (const auto b : boost::beast::buffers_range_ref(buffers))
        head_.append(static_cast<const char*>(b.data()), b.size());
      serializer.consume(boost::beast::buffer_bytes(buffers));
    });
  }
}

const std::vector<boost::asio::const_buffer>& ChunkedWriter::next(std::string& piece, bool last,
                                                                  const http::fields& trailer) {
  buffers_.clear();
  if (sent_ == Sent::Everything || write_ == Write::InFlight) return buffers_;
  if (sent_ == Sent::Nothing) buffers_.emplace_back(boost::asio::buffer(head_));
  chunk_.clear();
  chunk_.swap(piece);
  if (!chunk_.empty()) {
    char size[24];
    const int n = std::snprintf(size, sizeof size, "%zx\r\n", chunk_.size());
    size_line_.assign(size, static_cast<std::size_t>(n));
    buffers_.emplace_back(boost::asio::buffer(size_line_));
    buffers_.emplace_back(boost::asio::buffer(chunk_));
    buffers_.emplace_back(boost::asio::buffer("\r\n", 2));
  }
  if (last) {
    last_chunk_ = "0\r\n";
    for (const auto& field : trailer) {
      last_chunk_.append(field.name_string());
      last_chunk_ += ": ";
      last_chunk_.append(field.value());
      last_chunk_ += "\r\n";
    }
    last_chunk_ += "\r\n";
    buffers_.emplace_back(boost::asio::buffer(last_chunk_));
  }
  after_write_ = last ? Sent::Everything : Sent::Head;
  if (!buffers_.empty()) write_ = Write::InFlight;
  return buffers_;
}

void ChunkedWriter::written() {
  write_ = Write::Idle;
  sent_ = after_write_;
}

}  // namespace ncpost::server
