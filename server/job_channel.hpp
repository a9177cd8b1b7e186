#pragma once
// What a request's handler (on a worker, or inline on the IO thread) and its session (on the IO
// thread) share: how the request was answered, the stream's bytes waiting for the socket, how the
// stream ended, whether the client is still there, whether the handler has returned, and the
// cancel flag the engine polls. Each concern is one enum; every change happens under one mutex
// in one of the methods below, so the transitions are the ones docs/server.md draws
// ("Session states") and tests/unit/server/job_channel_test.cpp checks.

#include <atomic>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/fields.hpp>
#include <boost/beast/http/message.hpp>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace ncpost::server {

using StreamHead = boost::beast::http::response<boost::beast::http::empty_body>;

class JobChannel {
 public:
  // How the request was answered; set once.
  enum class Answer : std::uint8_t {
    None,      // not yet
    Buffered,  // respond(): one buffered response
    Stream,    // begin_stream(): a chunked stream
    TimedOut,  // the session answered 504 itself; whatever the handler sends is dropped
  };
  // How a stream ended (Answer::Stream only).
  enum class StreamEnd : std::uint8_t { Open, Complete, Cut };
  enum class Client : std::uint8_t { Present, Gone };
  enum class Handler : std::uint8_t { Running, Returned };
  // Whether a hop to the IO thread is already queued to take what is waiting.
  enum class Wakeup : std::uint8_t { Idle, Queued };

  // A writer blocks once this much waits for the socket: memory per stream stays bounded while a
  // slow client reads.
  static constexpr std::size_t kMaxPending = std::size_t{1} << 20;

  explicit JobChannel(std::size_t max_pending = kMaxPending) : max_pending_(max_pending) {}
  JobChannel(const JobChannel&) = delete;
  JobChannel& operator=(const JobChannel&) = delete;

  // ---- the handler's side (any thread) ----
  // None → Response; false when already answered (the response is dropped).
  [[nodiscard]] bool claim_response(std::string_view profile);
  // None → Stream, keeping the head for the session; false when answered or the client is gone.
  [[nodiscard]] bool begin_stream(StreamHead head, std::string_view profile);
  enum class Written : std::uint8_t {
    Refused,  // the client is gone or the session answered 504: stop
    Queued,   // appended; a wake-up is already on its way
    Wake,     // appended; the caller must wake the session (post a hop)
  };
  // Appends a piece of the stream; blocks while max_pending bytes wait and the client reads.
  [[nodiscard]] Written write(std::string_view piece);
  // Open → Complete or Cut. True: the caller must wake the session.
  [[nodiscard]] bool end_stream(bool complete, boost::beast::http::fields trailer);
  // Running → Returned; a stream begun and never ended is cut (true: wake the session).
  [[nodiscard]] bool handler_returned();

  // ---- the session's side (the IO thread) ----
  // The job's time ran out: sets the cancel flag; None → TimedOut. True when the session must
  // answer 504 now (nothing was sent); a stream under way is cut by its handler instead.
  [[nodiscard]] bool time_out();
  // The client went away (or the connection is closed): cancels the job and wakes a writer.
  void client_gone();
  // Cancels the job without giving up its stream (shutdown: its error marker may still go out).
  void cancel() noexcept { cancel_.store(true); }
  // The head begin_stream() left, once.
  [[nodiscard]] std::optional<StreamHead> take_head();
  struct Taken {
    StreamEnd end = StreamEnd::Open;
    boost::beast::http::fields trailer;  // of a Complete stream
  };
  // Swaps what waits into `bytes` (which should be empty), wakes a blocked writer and clears
  // the wake-up, so that the next write() asks for a new one.
  [[nodiscard]] Taken take(std::string& bytes);
  // A wake-up that reached a session no longer serving this request: the next write asks anew.
  void drop_wakeup();

  // ---- either side ----
  [[nodiscard]] const std::atomic<bool>& cancel_flag() const noexcept { return cancel_; }
  [[nodiscard]] bool timed_out() const noexcept { return timed_out_.load(); }
  [[nodiscard]] Answer answer() const;
  [[nodiscard]] Client client() const;
  [[nodiscard]] Handler handler() const;
  [[nodiscard]] std::string profile() const;

 private:
  std::atomic<bool> cancel_{false};
  std::atomic<bool> timed_out_{false};
  std::size_t max_pending_;
  mutable std::mutex mutex_;
  std::condition_variable drained_;  // pending shrank, or the writer should stop
  Answer answer_ = Answer::None;
  StreamEnd end_ = StreamEnd::Open;
  Client client_ = Client::Present;
  Handler handler_ = Handler::Running;
  Wakeup wakeup_ = Wakeup::Idle;
  std::string pending_;             // stream bytes not yet taken by the session
  std::optional<StreamHead> head_;  // from begin_stream() until take_head()
  boost::beast::http::fields trailer_;
  std::string profile_;  // for the access log
};

}  // namespace ncpost::server
