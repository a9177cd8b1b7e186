#pragma once
// The bytes of one streamed response (RFC 9112 §7.1 chunked transfer coding): the head once,
// each piece of text as one chunk, and, for a stream that ends complete, the last chunk with the
// trailer fields. Each write is one gathered write: the head goes out with the first chunk (and
// a short program's last chunk with it), so a small stream costs one system call. The writer
// owns the bytes of the write in flight until written(), so the session passes its buffers to
// the socket as they are. No I/O here: tests/unit/server/chunked_writer_test.cpp reads what it
// makes with Beast's parser.

#include <boost/asio/buffer.hpp>
#include <boost/beast/http/fields.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "job_channel.hpp"

namespace ncpost::server {

class ChunkedWriter {
 public:
  // What of the stream has gone out.
  enum class Sent : std::uint8_t { Nothing, Head, Everything };
  // Whether buffers from next() are still being written.
  enum class Write : std::uint8_t { Idle, InFlight };

  // `head` gets `Transfer-Encoding: chunked`; its bytes are kept for the first write.
  explicit ChunkedWriter(StreamHead& head);

  // The buffers of the next write: the head (until it is sent), `piece` as one chunk (none when
  // empty; `piece` is swapped in, not copied), and when `last`, the last chunk with `trailer`.
  // Empty when there is nothing to write. Only while no write is in flight.
  [[nodiscard]] const std::vector<boost::asio::const_buffer>& next(
      std::string& piece, bool last, const boost::beast::http::fields& trailer);
  // The write of the buffers from next() completed.
  void written();

  [[nodiscard]] Sent sent() const noexcept { return sent_; }
  [[nodiscard]] Write write() const noexcept { return write_; }

 private:
  std::string head_;
  std::string size_line_;
  std::string chunk_;
  std::string last_chunk_;
  std::vector<boost::asio::const_buffer> buffers_;
  Sent after_write_ = Sent::Head;  // what has gone out once the write in flight completes
  Sent sent_ = Sent::Nothing;
  Write write_ = Write::Idle;
};

}  // namespace ncpost::server
