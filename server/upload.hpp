#pragma once
// A large raw upload to a route that reads a model, taken in as it arrives (docs/server.md,
// "Large uploads"). The session appends each piece the socket gives (UploadBody below, on the
// connection's IO thread); the piece is hashed for the ETag at once, and whenever enough new text
// has come a slice of P21 reading (pipeline::ArrivingText) runs on the worker pool. When the last
// byte arrives the job finds the hash done and most of the file read: only the last piece, the
// reference resolution and the schema check are left.
//
// Threads: append() and complete() on the IO thread; slices on the pool, one at a time; the job
// calls reader() once the body is complete, which waits for a slice still running. The reader's
// cancel flag is the request's, so a client that leaves, or a job out of time, stops a slice
// within a few thousand tokens.

#include <atomic>
#include <boost/asio/thread_pool.hpp>
#include <boost/beast/core/buffers_range.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/optional.hpp>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string_view>

#include "body_hash.hpp"
#include "ncpost/pipeline/job.hpp"

namespace ncpost::server {

class StreamedUpload : public std::enable_shared_from_this<StreamedUpload> {
 public:
  // A slice reads at most this much at a time, so that the job's wait for a running slice at
  // the end stays short.
  static constexpr std::size_t kSliceMax = std::size_t{8} << 20;

  // A slice starts once `slice_step` bytes arrived unread. `slot`: held while the upload lives
  // (the server bounds how many are read this way). `helpers`: lent to read what is left at the
  // end in pieces (outlives the upload).
  StreamedUpload(std::size_t size, std::size_t slice_step,
                 boost::asio::thread_pool::executor_type pool,
                 std::shared_ptr<const std::atomic<bool>> cancel, std::shared_ptr<void> slot,
                 const pipeline::Helpers* helpers);

  [[nodiscard]] std::size_t size() const { return reader_->size(); }

  // ---- the IO thread ----
  // False (nothing stored) beyond the announced size.
  bool append(std::string_view bytes);
  // The last byte arrived: no slice starts after this one.
  void complete();

  // ---- the job, after complete() ----
  // The reader, once no slice runs any more.
  [[nodiscard]] pipeline::ArrivingText& reader();
  [[nodiscard]] std::uint64_t hash() const { return hash_.digest(); }
  // How much of the text had been read when the job took over (after reader()).
  [[nodiscard]] std::size_t read_while_arriving() const { return read_while_arriving_; }

 private:
  void run_slices();
  [[nodiscard]] bool cancelled() const { return cancel_->load(std::memory_order_relaxed); }

  std::size_t slice_step_;
  boost::asio::thread_pool::executor_type pool_;
  std::shared_ptr<const std::atomic<bool>> cancel_;
  std::shared_ptr<void> slot_;
  std::unique_ptr<pipeline::ArrivingText> reader_;
  BodyHash hash_;  // IO thread only until complete()
  std::mutex mutex_;
  std::condition_variable idle_;
  std::size_t arrived_ = 0;  // guarded: bytes appended, as the slices may see them
  std::size_t read_to_ = 0;  // guarded: what the slices have handed to the reader
  bool slicing_ = false;     // guarded: a slice is queued or running
  bool complete_ = false;    // guarded
  bool gave_up_ = false;     // guarded: the reader will read everything at the end
  std::size_t read_while_arriving_ = 0;
};

// A Beast body whose reader appends to a StreamedUpload: the bytes go from the socket's buffer
// straight to where the P21 reader reads them, one copy as with a string body.
struct UploadBody {
  using value_type = std::shared_ptr<StreamedUpload>;

  class reader {
   public:
    template <bool isRequest, class Fields>
    reader(boost::beast::http::header<isRequest, Fields>& /*header*/, value_type& body)
        : body_(body) {}
    void init(const boost::optional<std::uint64_t>& /*length*/, boost::beast::error_code& ec) {
      ec = {};
    }
    template <class ConstBufferSequence>
    std::size_t put(const ConstBufferSequence& buffers, boost::beast::error_code& ec) {
      std::size_t n = 0;
      for (const auto b : boost::beast::buffers_range_ref(buffers)) {
        if (!body_->append({static_cast<const char*>(b.data()), b.size()})) {
          ec = boost::beast::http::error::buffer_overflow;
          return n;
        }
        n += b.size();
      }
      ec = {};
      return n;
    }
    void finish(boost::beast::error_code& ec) { ec = {}; }

   private:
    value_type& body_;
  };
};

}  // namespace ncpost::server
