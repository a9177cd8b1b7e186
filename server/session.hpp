#pragma once
// One HTTP/1.1 connection. The session does I/O only: it reads a request under the header,
// body and time limits, hands it to its handler (inline, or on the worker pool), and writes
// what the handler produces, streaming chunks as the worker hands them over. Everything runs
// on the one IO thread that owns the connection's io_context; workers reach the session only
// through completions posted there and the mutex-guarded RequestState.

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "handlers.hpp"

namespace ncpost::server {

class Server;

// What a request's handler and its session share across threads.
struct RequestState {
  std::atomic<bool> cancel{false};
  std::atomic<bool> timed_out{false};
  std::mutex mutex;
  std::condition_variable drained;  // pending shrank, or the client is gone
  bool answered = false;            // respond() or begin_stream() happened, or a 504 went out
  bool streamed = false;            // begin_stream() happened
  bool abandoned = false;           // the session answered (504): ignore the handler's output
  bool gone = false;                // the client went away
  bool finished = false;            // the handler returned
  bool ended = false;               // end_stream() was called
  bool complete = false;            // its argument
  bool pump_posted = false;
  std::string pending;             // stream bytes not yet handed to the socket
  std::optional<StreamHead> head;  // from begin_stream() until the IO thread takes it
  http::fields trailer;            // after the last chunk of a complete stream
  std::string profile;             // for the access log, copied when the answer is handed over
};

class Session : public std::enable_shared_from_this<Session> {
 public:
  // The socket's executor: the io_context of one IO thread (Server gives each IO thread its
  // own), so the connection's handlers never run concurrently without a strand. A strand put
  // one more queued hop in front of every completion, and the type-erased any_io_executor
  // indirect calls and copies: together half of what a /healthz request cost.
  using Executor = boost::asio::io_context::executor_type;
  using Socket = boost::asio::basic_stream_socket<boost::asio::ip::tcp, Executor>;
  Session(Socket socket, Server& server);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session();

  void start();
  // Graceful shutdown: close now if idle, else after the response in progress.
  void drain();
  // Shutdown deadline passed: cancel the job and close.
  void force_close();

  // ---- called by SessionExchange, from a worker or from the IO thread ----
  void hand_over(std::shared_ptr<RequestState> state, Response response);
  void post_pump(std::shared_ptr<RequestState> state);
  void post_job_finished(std::shared_ptr<RequestState> state);

 private:
  enum class Phase : std::uint8_t { Idle, Reading, Handling, Writing, Lingering, Closed };

  void wait_request();
  void read_header();
  void on_header(boost::beast::error_code ec, std::size_t bytes);
  [[nodiscard]] bool refused_as_full();
  void refuse_as_full(bool then_linger);  // 503 with Retry-After
  void take_upload_as_it_arrives();
  void read_body();
  // Feeds what buffer_ holds to the parser (up to the end of the header, or of the message) and
  // returns the bytes it took; a short buffer is not an error.
  template <class Parser>
  std::size_t parse_buffered(Parser& parser, boost::beast::error_code& ec, bool header_only);
  void on_body(boost::beast::error_code ec, std::size_t bytes);
  void read_failed(boost::beast::error_code ec);
  void handle_request();
  void dispatch_job(const Route& route, std::string id);
  void watch_client();
  void on_job_timeout(const std::shared_ptr<RequestState>& state);
  void deliver(const std::shared_ptr<RequestState>& state, Response response);
  void send(Response response, bool then_linger = false);
  void on_write(boost::beast::error_code ec, std::size_t bytes, bool then_linger);
  void stream_begin(const std::shared_ptr<RequestState>& state);
  void pump(const std::shared_ptr<RequestState>& state);
  void on_stream_written(const std::shared_ptr<RequestState>& state, boost::beast::error_code ec,
                         std::size_t bytes, bool last);
  void client_gone(const std::shared_ptr<RequestState>& state);
  void finish_request(bool complete);
  void after_response();
  void linger_close();
  void close();
  void arm_timer(std::chrono::milliseconds duration);
  void disarm_timer();
  void wait_for_deadline();
  void on_timer(boost::beast::error_code ec);
  [[nodiscard]] bool current(const std::shared_ptr<RequestState>& state) const {
    return state && state == state_ && phase_ != Phase::Closed;
  }

  Server& server_;
  Executor executor_;
  Socket socket_;
  boost::asio::steady_timer timer_;
  boost::asio::steady_timer job_timer_;
  boost::beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  // A large raw upload to a model route is read through this parser instead (upload.hpp).
  std::optional<http::request_parser<UploadBody>> upload_parser_;
  std::shared_ptr<StreamedUpload> upload_;
  Request request_;
  std::shared_ptr<RequestState> state_;
  std::shared_ptr<Response> response_;
  std::unique_ptr<StreamHead> stream_head_;
  // What one gathered write of a stream holds: the head's bytes (until written), a chunk, the
  // last chunk with the trailer.
  std::string head_bytes_;
  std::string chunk_size_;
  std::string out_chunk_;
  std::string last_chunk_;
  http::fields out_trailer_;
  std::vector<boost::asio::const_buffer> out_buffers_;
  std::string remote_;
  std::uint64_t id_ = 0;
  Phase phase_ = Phase::Idle;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
  bool timer_waiting_ = false;
  bool first_request_ = true;
  bool read_timed_out_ = false;
  bool keep_alive_ = true;
  bool is_head_ = false;
  bool writing_ = false;
  bool head_written_ = false;
  bool streaming_ = false;  // stream_begin ran for the request in progress
  bool forced_ = false;     // the shutdown deadline passed while it streamed
  bool watch_pending_ = false;
  bool job_running_ = false;
  bool awaiting_job_ = false;  // answered; the next read waits for the job to return
  bool logged_ = true;
  // For the access log and metrics of the request in progress.
  std::chrono::steady_clock::time_point started_{};
  std::chrono::steady_clock::time_point received_{};  // the request's last byte
  std::string request_id_;
  std::string_view route_name_;  // the route table's (static) name, or "unmatched"
  std::string method_;
  std::string path_;
  std::string profile_;
  unsigned status_ = 0;
  std::uint64_t bytes_in_ = 0;
  std::uint64_t bytes_out_ = 0;
};

}  // namespace ncpost::server
