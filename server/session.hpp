#pragma once
// One HTTP/1.1 connection. The session does I/O only: it reads a request under the header,
// body and time limits, hands it to its handler (inline, or on the worker pool), and writes
// what the handler produces, streaming chunks as the worker hands them over. Everything runs
// on the one IO thread that owns the connection's io_context; workers reach the session only
// through completions posted there and the request's JobChannel.
//
// Its state is a handful of enums, one per concern (docs/server.md, "Session states", draws
// them): the connection's Phase, what comes After the response, the Job on the pool, the Watch
// on the client's socket while the job runs, and the Shutdown grace of a stream. The stream's
// bytes are the ChunkedWriter's; what the handler and the session share is the JobChannel's.

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "chunked_writer.hpp"
#include "handlers.hpp"
#include "job_channel.hpp"
#include "memory_budget.hpp"
#include "metrics.hpp"
#include "request_head.hpp"

namespace ncpost::server {

class Server;

// The access-log line and metrics of the request in progress: opened when its first byte is
// read, written once (Session::finish_request).
struct RequestRecord {
  std::chrono::steady_clock::time_point started{};
  std::chrono::steady_clock::time_point received{};  // the request's last byte
  std::string request_id;
  std::string_view route = "unmatched";  // the route table's (static) name, or route_label
  std::string route_label;               // a 405's: method and the path's pattern
  std::string method;
  std::string path;
  std::string profile;
  unsigned status = 0;
  std::uint64_t bytes_in = 0;
  std::uint64_t bytes_out = 0;
  bool open = false;  // read, and not yet written to the log
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
  void hand_over(std::shared_ptr<JobChannel> channel, Response response);
  void post_pump(std::shared_ptr<JobChannel> channel);
  void post_job_finished(std::shared_ptr<JobChannel> channel);

 private:
  // What the connection does.
  enum class Phase : std::uint8_t {
    Idle,          // waiting for a request's first byte (read limit when fresh, else idle limit)
    Reading,       // a request's header and body (read limit)
    ReadTimedOut,  // the read limit passed: the read's completion answers 408
    Handling,      // the handler runs and has not answered
    Writing,       // a response or a stream goes out (write limit)
    AwaitingJob,   // answered; the next request is read once the job has returned
    Lingering,     // closing after an error: what the client still sends is read and dropped
    Closed,
  };
  // What follows the response in progress.
  enum class After : std::uint8_t {
    NextRequest,  // keep-alive
    Close,
    Linger,  // close after reading what the client still sends (a body not read)
  };
  // The request's job on the worker pool.
  enum class Job : std::uint8_t {
    None,
    Running,  // queued or running; it has not returned
    Overdue,  // its time limit passed and it has not returned yet
  };
  // A wait for the client's socket while its job runs: EOF means it left, bytes are pipelined.
  enum class Watch : std::uint8_t { Off, Waiting };
  // The shutdown deadline passed while a stream went out: it gets a moment to write its error
  // marker before the connection is cut.
  enum class Shutdown : std::uint8_t { None, StreamGrace };
  // Whether the deadline timer has a wait queued (the deadline itself moves without it).
  enum class Timer : std::uint8_t { Idle, Waiting };

  void wait_request();
  void read_header();
  // Parses what the buffer holds of the header, reading more until it is whole.
  void header_step();
  void on_header(boost::beast::error_code ec, HeadProblem problem);
  [[nodiscard]] bool refused_as_full();
  void refuse_as_full();  // 503 with Retry-After
  // The memory budget: reserves what the request's body will hold (on the header, or as a
  // chunked body arrives); true when it was refused and answered.
  [[nodiscard]] bool refused_by_budget();
  void refuse_for_memory(Metrics::MemoryRefusal reason);  // 503 with Retry-After, or 413
  std::size_t count_chunk(std::string_view piece, boost::beast::error_code& ec);
  void take_upload_as_it_arrives();
  void read_body();
  // Feeds what buffer_ holds to the parser, up to the end of the message, and returns the bytes
  // it took; a short buffer is not an error.
  template <class Parser>
  std::size_t parse_buffered(Parser& parser, boost::beast::error_code& ec);
  void on_body(boost::beast::error_code ec, std::size_t bytes);
  void read_failed(boost::beast::error_code ec);
  void handle_request();
  void dispatch_job(const Route& route, std::string id);
  void watch_client();
  void on_job_timeout(const std::shared_ptr<JobChannel>& channel);
  void deliver(const std::shared_ptr<JobChannel>& channel, Response response);
  void send(Response response);
  void on_write(boost::beast::error_code ec, std::size_t bytes);
  void stream_begin(const std::shared_ptr<JobChannel>& channel);
  void pump(const std::shared_ptr<JobChannel>& channel);
  void on_stream_written(const std::shared_ptr<JobChannel>& channel, boost::beast::error_code ec,
                         std::size_t bytes);
  void client_gone(const std::shared_ptr<JobChannel>& channel);
  void finish_request(bool complete);
  void after_response();
  void linger_close();
  void close();
  void arm_timer(std::chrono::milliseconds duration);
  void disarm_timer();
  void wait_for_deadline();
  void on_timer(boost::beast::error_code ec);
  [[nodiscard]] bool current(const std::shared_ptr<JobChannel>& channel) const {
    return channel && channel == channel_ && phase_ != Phase::Closed;
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
  http::verb verb_ = http::verb::unknown;  // of the request in progress (HEAD: no body)
  std::shared_ptr<JobChannel> channel_;
  // The request's share of --max-inflight: its body (times the model factor for a route that
  // reads a model); moved to its job, which gives it back.
  MemoryBudget::Reservation reservation_;
  double body_factor_ = 1.0;
  MemoryBudget::Refusal memory_refusal_ = MemoryBudget::Refusal::None;
  // Beast keeps a reference to its chunk callback: this one lives as long as the session.
  std::function<std::size_t(std::uint64_t, std::string_view, boost::beast::error_code&)>
      chunk_counter_;
  std::shared_ptr<Response> response_;   // a buffered response being written
  std::optional<ChunkedWriter> stream_;  // a stream under way
  std::string chunk_;                    // what the channel handed over for the next write
  std::string remote_;
  std::uint64_t id_ = 0;
  std::uint64_t requests_ = 0;  // read on this connection
  RequestRecord record_;
  Phase phase_ = Phase::Idle;
  After after_ = After::NextRequest;
  Job job_ = Job::None;
  Watch watch_ = Watch::Off;
  Shutdown shutdown_ = Shutdown::None;
  Timer timer_wait_ = Timer::Idle;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
};

}  // namespace ncpost::server
