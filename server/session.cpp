#include "session.hpp"

#include <algorithm>
#include <array>
#include <boost/asio/bind_executor.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>
#include <cctype>
#include <functional>

#include "access_log.hpp"
#include "multipart.hpp"
#include "negotiation.hpp"
#include "server.hpp"

namespace ncpost::server {
namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
using Clock = std::chrono::steady_clock;

// How long a connection that is closed after an error keeps reading (and discarding) what the
// client still sends, so that the client sees the response instead of a reset.
constexpr auto kLingerTime = std::chrono::seconds(2);
constexpr std::size_t kLingerBytes = std::size_t{8} << 20;
// At the shutdown deadline, how long a cancelled stream has to write its error marker.
constexpr auto kForcedStreamGrace = std::chrono::seconds(2);
// What an idle connection's read asks for: a small post's header and body in one read.
constexpr std::size_t kFirstRead = 16384;

Response error_response(unsigned status, diag::Code code, std::string_view title,
                        std::string detail) {
  const std::vector<diag::FileDiagnostic> one = {{"request", diag::make(code, 0, 0, detail)}};
  return problem(status, diag::info(code).id, title, detail, one);
}

bool valid_request_id(std::string_view id) {
  if (id.empty() || id.size() > 64) return false;
  for (char c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
      return false;
  return true;
}

// The handler's view of its request, from a worker thread (or inline on the IO thread).
class SessionExchange final : public Exchange {
 public:
  SessionExchange(std::shared_ptr<Session> session, std::shared_ptr<JobChannel> channel,
                  MemoryBudget::Reservation* reservation = nullptr)
      : session_(std::move(session)), channel_(std::move(channel)), reservation_(reservation) {}
  using Exchange::end_stream;

  void respond(Response response) override {
    if (channel_->claim_response(profile)) session_->hand_over(channel_, std::move(response));
  }

  bool begin_stream(StreamHead head) override {
    // Nothing is posted yet: the head goes out with the first write() or end_stream(), whose
    // pump finds it (one hop to the IO thread instead of two).
    return channel_->begin_stream(std::move(head), profile);
  }

  bool write(std::string_view piece) override {
    const JobChannel::Written written = channel_->write(piece);
    if (written == JobChannel::Written::Wake) session_->post_pump(channel_);
    return written != JobChannel::Written::Refused;
  }

  void end_stream(bool complete, http::fields trailer) override {
    if (channel_->end_stream(complete, std::move(trailer))) session_->post_pump(channel_);
  }

  [[nodiscard]] const std::atomic<bool>* cancel_flag() const noexcept override {
    return &channel_->cancel_flag();
  }
  [[nodiscard]] bool timed_out() const noexcept override { return channel_->timed_out(); }

  void release_model() override {
    if (reservation_ != nullptr) reservation_->release();
  }

 private:
  std::shared_ptr<Session> session_;
  std::shared_ptr<JobChannel> channel_;
  MemoryBudget::Reservation* reservation_;  // the job's, on its worker
};

}  // namespace

Session::Session(Socket socket, Server& server)
    : server_(server),
      executor_(socket.get_executor()),
      socket_(std::move(socket)),
      timer_(executor_),
      job_timer_(executor_),
      id_(server.next_session_id()) {
  beast::error_code ec;
  const auto endpoint = socket_.remote_endpoint(ec);
  if (!ec) remote_ = endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
  socket_.set_option(net::ip::tcp::no_delay(true), ec);
  server_.services().metrics->connections++;
  chunk_counter_ = [this](std::uint64_t, std::string_view piece, beast::error_code& e) {
    return count_chunk(piece, e);
  };
}

Session::~Session() {
  server_.remove_session(id_);
}

void Session::start() {
  server_.add_session(id_, shared_from_this());
  net::post(executor_, [self = shared_from_this()] { self->wait_request(); });
}

void Session::drain() {
  net::post(executor_, [self = shared_from_this()] {
    if (self->phase_ == Phase::Idle) self->close();
    // Otherwise the response in progress says Connection: close (the server is draining).
  });
}

void Session::force_close() {
  net::post(executor_, [self = shared_from_this()] {
    if (self->phase_ == Phase::Closed) return;
    // A stream under way is cancelled and given a moment to end with the profile's error
    // marker, so that the cut shows in the program text as well as in the transfer. A second
    // force (a second signal) or the end of the moment closes it.
    if (self->stream_ && self->channel_ && self->shutdown_ == Shutdown::None) {
      self->shutdown_ = Shutdown::StreamGrace;
      self->channel_->cancel();
      self->arm_timer(std::chrono::duration_cast<std::chrono::milliseconds>(kForcedStreamGrace));
      return;
    }
    if (self->channel_) self->channel_->client_gone();
    self->close();
  });
}

// ---- reading --------------------------------------------------------------------------------

void Session::wait_request() {
  if (server_.draining()) return close();
  phase_ = Phase::Idle;
  channel_.reset();
  stream_.reset();
  // A fresh connection was opened to send a request: it gets the read limit. A kept-alive one
  // may sit idle for the idle limit.
  arm_timer(requests_ == 0 ? server_.config().read_timeout : server_.config().idle_timeout);
  if (buffer_.size() > 0) return read_header();
  // A read rather than a wait for readability: the socket tries it at once (the next request
  // is often there already), and a wait would change the socket's epoll registration each time.
  socket_.async_read_some(buffer_.prepare(kFirstRead),
                          net::bind_executor(executor_, [self = shared_from_this()](
                                                            beast::error_code ec, std::size_t n) {
                            if (self->phase_ != Phase::Idle) return;
                            if (ec) return self->close();
                            self->buffer_.commit(n);
                            self->read_header();
                          }));
}

void Session::read_header() {
  phase_ = Phase::Reading;
  ++requests_;
  record_ = RequestRecord{};
  record_.started = Clock::now();
  record_.request_id = server_.next_request_id();
  record_.open = true;
  after_ = After::NextRequest;
  shutdown_ = Shutdown::None;
  reservation_.release();
  memory_refusal_ = MemoryBudget::Refusal::None;
  arm_timer(server_.config().read_timeout);
  upload_parser_.reset();
  upload_.reset();
  parser_.emplace();
  parser_->header_limit(server_.config().max_header);
  parser_->body_limit(server_.config().max_body);
  header_step();
}

// Beast 1.74 holds its header limit on what one put() sees, not on the whole header (fields it
// has taken are not counted again), so the total is counted here; obs-fold, which its parser
// unfolds silently, is found in the bytes it took. A header already in the buffer is parsed
// without a queued completion.
void Session::header_step() {
  beast::error_code ec;
  HeadProblem problem = HeadProblem::None;
  std::size_t used = 0;
  while (buffer_.size() > 0 && !parser_->is_header_done()) {
    const auto bytes = buffer_.data();
    const std::size_t n = parser_->put(bytes, ec);
    if (has_obs_fold({static_cast<const char*>(bytes.data()), n})) problem = HeadProblem::ObsFold;
    buffer_.consume(n);
    used += n;
    if (ec == http::error::need_more) ec = {};
    if (ec || n == 0 || problem != HeadProblem::None) break;
  }
  record_.bytes_in += used;
  const std::size_t unparsed = parser_->is_header_done() ? 0 : buffer_.size();
  if (!ec && record_.bytes_in + unparsed > server_.config().max_header)
    ec = http::error::header_limit;
  if (ec || problem != HeadProblem::None || parser_->is_header_done())
    return on_header(ec, problem);
  socket_.async_read_some(buffer_.prepare(kFirstRead),
                          net::bind_executor(executor_, [self = shared_from_this()](
                                                            beast::error_code e, std::size_t n) {
                            if (e) return self->read_failed(e);
                            self->buffer_.commit(n);
                            self->header_step();
                          }));
}

template <class Parser>
std::size_t Session::parse_buffered(Parser& parser, beast::error_code& ec) {
  std::size_t used = 0;
  while (buffer_.size() > 0 && !parser.is_done()) {
    const std::size_t n = parser.put(buffer_.data(), ec);
    buffer_.consume(n);
    used += n;
    if (ec == http::error::need_more) ec = {};
    if (ec || n == 0) break;
  }
  return used;
}

void Session::on_header(beast::error_code ec, HeadProblem problem) {
  if (ec) return read_failed(ec);
  auto& header = parser_->get();
  if (problem == HeadProblem::None) problem = check_head(header);
  // RFC 9112 §3.2.2: a server accepts the absolute form (a proxy's) and routes its path.
  if (auto origin = origin_form(header.target())) header.target(*origin);
  verb_ = header.method();
  record_.method = std::string(header.method_string());
  record_.path = std::string(header.target().substr(0, header.target().find('?')));
  if (const auto id = header["X-Request-Id"]; valid_request_id(id))
    record_.request_id = std::string(id);
  const bool expects_continue = beast::iequals(header[http::field::expect], "100-continue");
  // Made now rather than at dispatch: a slice reading the upload as it arrives already needs
  // the request's cancel flag.
  channel_ = std::make_shared<JobChannel>();
  if (problem != HeadProblem::None) {
    // The body's framing is unknown or not trusted: nothing after the header is read as a
    // request (no smuggling), and the connection closes.
    after_ = After::Linger;
    (void)channel_->claim_response({});
    const unsigned status = status_of(problem);
    return send(error_response(
        status, status == 501 ? diag::Code::HttpTransferCoding : diag::Code::HttpBadRequest,
        status == 501 ? "Not implemented" : "Bad request", std::string(describe(problem))));
  }
  if (refused_as_full() || refused_by_budget()) return;
  take_upload_as_it_arrives();
  // curl and browsers wait for 100 Continue before a large body; answer it only once the
  // header passed its checks, so a too-large upload is refused before it is sent.
  if (expects_continue) {
    static constexpr std::string_view kContinue = "HTTP/1.1 100 Continue\r\n\r\n";
    net::async_write(socket_, net::buffer(kContinue.data(), kContinue.size()),
                     net::bind_executor(executor_, [self = shared_from_this()](beast::error_code e,
                                                                               std::size_t n) {
                       self->record_.bytes_out += n;
                       if (e) return self->close();
                       self->read_body();
                     }));
    return;
  }
  read_body();
}

// A job while every worker and queue place is taken is refused on its header: the client is
// told 503 before it sends (or this reads) a body of up to --max-body that would be refused
// after all. The connection closes, as the body was not read. handle_request() still admits
// for real: a place may be taken between the header and the body's end.
bool Session::refused_as_full() {
  if (!server_.saturated()) return false;  // the usual case: no route to look up here
  const auto& header = parser_->get();
  const RouteMatch match = match_route(header.method(), header.target());
  if (match.route == nullptr || match.route->where != Where::Worker) return false;
  record_.route = match.route->name;
  after_ = After::Linger;
  refuse_as_full();
  return true;
}

void Session::refuse_as_full() {
  server_.services().metrics->rejected_full++;
  (void)channel_->claim_response({});
  Response r = error_response(503, diag::Code::HttpQueueFull, "Service unavailable",
                              "all workers are busy and the job queue is full; retry later");
  r.set(http::field::retry_after, "1");
  send(std::move(r));
}

// Admission by bytes (docs/server.md, "Memory budget"): a body announced by its Content-Length
// reserves, on the header, what it will hold, so that a request that does not fit is told 503
// before it sends its body (after 100 Continue is not sent); a chunked body reserves as it
// arrives. Requests without a body reserve nothing and are never refused here.
bool Session::refused_by_budget() {
  const bool chunked = parser_->chunked();
  const auto length = parser_->content_length();
  if (!chunked && length.value_or(0) == 0) return false;
  const auto& header = parser_->get();
  const RouteMatch match = match_route(header.method(), header.target());
  body_factor_ =
      match.route != nullptr && match.route->reads_model ? MemoryBudget::kModelFactor : 1.0;
  reservation_ = server_.budget().open();
  if (chunked) {
    parser_->on_chunk_body(chunk_counter_);
    return false;
  }
  memory_refusal_ = reservation_.grow(MemoryBudget::need(*length, body_factor_));
  if (memory_refusal_ == MemoryBudget::Refusal::None) return false;
  if (match.route != nullptr) record_.route = match.route->name;
  refuse_for_memory(Metrics::MemoryRefusal::Header);
  return true;
}

// A piece of a chunked body: kept when its bytes fit the budget, else the read stops and
// read_failed() answers.
std::size_t Session::count_chunk(std::string_view piece, beast::error_code& ec) {
  memory_refusal_ = reservation_.grow(MemoryBudget::need(piece.size(), body_factor_));
  if (memory_refusal_ != MemoryBudget::Refusal::None) {
    ec = http::error::body_limit;
    return 0;
  }
  parser_->get().body().append(piece);
  return piece.size();
}

void Session::refuse_for_memory(Metrics::MemoryRefusal reason) {
  const auto& budget = server_.budget();
  const bool alone = memory_refusal_ == MemoryBudget::Refusal::TooLarge;
  server_.services().metrics->memory_refused(alone ? Metrics::MemoryRefusal::TooLarge : reason);
  after_ = After::Linger;
  reservation_.release();
  (void)channel_->claim_response({});
  if (alone)
    return send(error_response(
        413, diag::Code::HttpMemoryBudget, "Content too large",
        "the request would hold more than the memory budget admits for one request (" +
            std::to_string(budget.budget() - budget.reserve()) + " bytes of --max-inflight " +
            std::to_string(budget.budget()) + "; a model is about 2.3 times its upload)"));
  Response r = error_response(503, diag::Code::HttpMemoryBudget, "Service unavailable",
                              "the memory budget (--max-inflight) is taken by requests in "
                              "flight; retry later");
  r.set(http::field::retry_after, "1");
  send(std::move(r));
}

// A large raw body to a route that reads a model is read as it arrives: hashed and, in slices
// on the worker pool, read as P21, so that little is left when its last byte comes (upload.hpp).
// Smaller bodies, multipart ones and bodies without a Content-Length are read whole as before.
void Session::take_upload_as_it_arrives() {
  const auto& config = server_.config();
  const auto length = parser_->content_length();
  if (config.stream_read_min == 0 || !length || *length < config.stream_read_min ||
      *length > config.max_body)
    return;
  const auto& header = parser_->get();
  if (is_multipart(header[http::field::content_type])) return;
  const RouteMatch match = match_route(header.method(), header.target());
  if (match.route == nullptr || !match.route->reads_model) return;
  auto slot = server_.try_stream_read();
  if (!slot) return;
  // Slices of an eighth of the smallest streamed upload: several per upload, each worth a hop
  // to the pool.
  const auto slice_step =
      std::clamp<std::uint64_t>(config.stream_read_min / 8, 4096, std::uint64_t{1} << 20);
  upload_ = std::make_shared<StreamedUpload>(
      static_cast<std::size_t>(*length), static_cast<std::size_t>(slice_step),
      server_.pool().get_executor(),
      std::shared_ptr<const std::atomic<bool>>(channel_, &channel_->cancel_flag()), std::move(slot),
      &server_.services().helpers);
  upload_parser_.emplace(std::move(*parser_));
  parser_.reset();
  upload_parser_->body_limit(config.max_body);
  upload_parser_->get().body() = upload_;
}

void Session::read_body() {
  if (upload_parser_) {
    return http::async_read(socket_, buffer_, *upload_parser_,
                            net::bind_executor(executor_, [self = shared_from_this()](
                                                              beast::error_code ec, std::size_t n) {
                              self->on_body(ec, n);
                            }));
  }
  // No body, or all of it in the buffer (a small post usually comes in one segment with its
  // header): done here, without a queued completion.
  beast::error_code ec;
  const std::size_t used = parse_buffered(*parser_, ec);
  if (ec || parser_->is_done()) return on_body(ec, used);
  http::async_read(socket_, buffer_, *parser_,
                   net::bind_executor(executor_, [self = shared_from_this(), used](
                                                     beast::error_code e, std::size_t n) {
                     self->on_body(e, used + n);
                   }));
}

void Session::on_body(beast::error_code ec, std::size_t bytes) {
  record_.bytes_in += bytes;
  if (ec) return read_failed(ec);
  disarm_timer();
  record_.received = Clock::now();
  handle_request();
}

void Session::read_failed(beast::error_code ec) {
  if (phase_ == Phase::Closed) return;
  const bool timed_out = phase_ == Phase::ReadTimedOut;
  after_ = After::Linger;
  if (upload_) {
    upload_->complete();  // no more slices of an upload that will not be answered
    upload_.reset();
  }
  if (memory_refusal_ != MemoryBudget::Refusal::None)
    return refuse_for_memory(Metrics::MemoryRefusal::Upload);
  if (timed_out)
    return send(error_response(408, diag::Code::HttpReadTimeout, "Request timeout",
                               "the request did not arrive within --read-timeout"));
  if (ec == http::error::body_limit)
    return send(error_response(
        413, diag::Code::HttpBodyTooLarge, "Content too large",
        "the body exceeds --max-body (" + std::to_string(server_.config().max_body) + " bytes)"));
  if (ec == http::error::header_limit)
    return send(error_response(431, diag::Code::HttpHeaderTooLarge,
                               "Request header fields too large",
                               "the request header exceeds --max-header (" +
                                   std::to_string(server_.config().max_header) + " bytes)"));
  if (ec == http::error::end_of_stream || ec == net::error::eof ||
      ec == net::error::connection_reset || ec == net::error::operation_aborted ||
      ec == http::error::partial_message) {
    if (record_.bytes_in > 0) finish_request(false);
    return close();
  }
  send(error_response(400, diag::Code::HttpBadRequest, "Bad request",
                      "malformed HTTP request: " + ec.message()));
}

// ---- dispatch -------------------------------------------------------------------------------

void Session::handle_request() {
  if (upload_parser_) {
    request_ = Request(std::move(upload_parser_->release().base()));
    upload_parser_.reset();
    upload_->complete();
  } else {
    request_ = parser_->release();
    parser_.reset();
  }
  after_ = request_.keep_alive() ? After::NextRequest : After::Close;
  RouteMatch match = match_route(request_.method(), request_.target());
  if (match.route == nullptr) {
    Response r = match.status == 405
                     ? error_response(405, diag::Code::HttpNotFound, "Method not allowed",
                                      "allowed here: " + match.allow)
                     : error_response(404, diag::Code::HttpNotFound, "Not found",
                                      "no route for " + record_.path);
    if (match.status == 405) {
      r.set(http::field::allow, match.allow);
      record_.route_label = std::string(method_label(verb_)) + " " + std::string(match.pattern);
      record_.route = record_.route_label;
    }
    (void)channel_->claim_response({});
    return send(std::move(r));
  }
  record_.route = match.route->name;
  // One value per parameter: which of two the request meant cannot be guessed.
  if (const std::string repeated = repeated_query_parameter(request_.target()); !repeated.empty()) {
    (void)channel_->claim_response({});
    return send(error_response(400, diag::Code::HttpBadRequest, "Bad request",
                               "the query parameter '" + repeated + "' is given more than once"));
  }
  if (match.route->where == Where::Inline) {
    phase_ = Phase::Handling;
    SessionExchange exchange(shared_from_this(), channel_);
    exchange.path_id = std::move(match.id);
    try {
      match.route->handler(request_, server_.services(), exchange);
    } catch (const std::exception& e) {
      exchange.respond(error_response(500, diag::Code::HttpInternal, "Internal error", e.what()));
    }
    request_ = {};  // its body, whose share of the budget goes back now
    reservation_.release();
    return;  // the handler's respond() started the write
  }
  if (!server_.try_admit()) {
    upload_.reset();
    return refuse_as_full();  // the body was read: the connection may go on
  }
  dispatch_job(*match.route, std::move(match.id));
}

void Session::dispatch_job(const Route& route, std::string id) {
  phase_ = Phase::Handling;
  job_ = Job::Running;
  stream_.reset();
  auto channel = channel_;
  auto& metrics = *server_.services().metrics;
  metrics.queued++;
  job_timer_.expires_after(server_.config().job_timeout);
  job_timer_.async_wait(
      net::bind_executor(executor_, [self = shared_from_this(), channel](beast::error_code ec) {
        if (!ec) self->on_job_timeout(channel);
      }));
  watch_client();
  auto request = std::make_shared<Request>(std::move(request_));
  net::post(
      server_.pool(), [self = shared_from_this(), channel, request, handler = route.handler,
                       id = std::move(id), upload = std::move(upload_), received = record_.received,
                       reservation = std::move(reservation_), &metrics]() mutable {
        metrics.queued--;
        metrics.active++;
        const auto started = Clock::now();
        {
          SessionExchange exchange(self, channel, &reservation);
          exchange.path_id = std::move(id);
          exchange.upload = std::move(upload);
          exchange.received = received;
          // A job whose client left (or whose time ran out) while it queued is not started.
          if (!channel->cancel_flag().load()) {
            try {
              handler(*request, self->server_.services(), exchange);
            } catch (const std::exception& e) {
              exchange.respond(
                  error_response(500, diag::Code::HttpInternal, "Internal error", e.what()));
            }
          }
          exchange.respond(error_response(500, diag::Code::HttpInternal, "Internal error",
                                          "the handler gave no response"));  // dropped if answered
          // A stream the handler began but did not end (it threw) is cut, never left open.
          if (channel->handler_returned()) self->post_pump(channel);
        }
        request.reset();  // free the upload on the worker, not on the IO thread
        reservation.release();
        self->server_.job_returned(Clock::now() - started);
        metrics.active--;
        self->server_.release();
        self->post_job_finished(channel);
      });
}

// While a job runs the connection is otherwise silent; a readable socket then means the client
// hung up (EOF or reset), which cancels the job, or sent its next request early (pipelining).
void Session::watch_client() {
  if (watch_ == Watch::Waiting || phase_ == Phase::Closed) return;
  watch_ = Watch::Waiting;
  socket_.async_wait(
      Socket::wait_read,
      net::bind_executor(executor_, [self = shared_from_this()](beast::error_code ec) {
        self->watch_ = Watch::Off;
        if (self->job_ == Job::None || self->phase_ == Phase::Closed) return;
        beast::error_code e;
        const std::size_t available = self->socket_.available(e);
        if (ec || e || available == 0) return self->client_gone(self->channel_);
        // Pipelined bytes: keep them for the next request, bounded by the header limit.
        if (self->buffer_.size() + available > self->server_.config().max_header)
          return;  // stop watching; the next read enforces the limits
        auto buffers = self->buffer_.prepare(available);
        const std::size_t n = self->socket_.read_some(buffers, e);
        self->buffer_.commit(n);
        if (e) return self->client_gone(self->channel_);
        self->watch_client();
      }));
}

void Session::on_job_timeout(const std::shared_ptr<JobChannel>& channel) {
  if (!current(channel) || job_ != Job::Running) return;
  job_ = Job::Overdue;
  // A stream already under way is ended by the worker with the profile's error marker.
  if (channel->time_out())
    send(error_response(504, diag::Code::HttpJobTimeout, "Job time limit exceeded",
                        "the job ran longer than --job-timeout (" +
                            std::to_string(server_.config().job_timeout.count()) + " ms)"));
}

void Session::post_job_finished(std::shared_ptr<JobChannel> channel) {
  net::post(executor_, [self = shared_from_this(), channel = std::move(channel)] {
    if (channel != self->channel_) return;
    self->job_ = Job::None;
    self->job_timer_.cancel();
    if (self->phase_ == Phase::AwaitingJob) self->wait_request();
  });
}

// ---- buffered responses ---------------------------------------------------------------------

void Session::hand_over(std::shared_ptr<JobChannel> channel, Response response) {
  // An inline handler answers on the IO thread already: no hop.
  if (executor_.running_in_this_thread()) return deliver(channel, std::move(response));
  net::post(executor_, [self = shared_from_this(), channel = std::move(channel),
                        response = std::move(response)]() mutable {
    self->deliver(channel, std::move(response));
  });
}

void Session::deliver(const std::shared_ptr<JobChannel>& channel, Response response) {
  if (!current(channel) || channel->answer() != JobChannel::Answer::Buffered) return;
  record_.profile = channel->profile();
  send(std::move(response));
}

void Session::send(Response response) {
  phase_ = Phase::Writing;
  if (server_.draining() && after_ == After::NextRequest) after_ = After::Close;
  record_.status = response.result_int();
  response.set(http::field::server, "ncpostd");
  response.set("X-Request-Id", record_.request_id);
  response.keep_alive(after_ == After::NextRequest);
  response.prepare_payload();
  if (verb_ == http::verb::head) {
    const auto length = response.body().size();
    response.body().clear();
    response.content_length(length);
  }
  response_ = std::make_shared<Response>(std::move(response));
  arm_timer(server_.config().write_timeout);
  http::async_write(socket_, *response_,
                    net::bind_executor(executor_, [self = shared_from_this()](beast::error_code ec,
                                                                              std::size_t n) {
                      self->on_write(ec, n);
                    }));
}

void Session::on_write(beast::error_code ec, std::size_t bytes) {
  record_.bytes_out += bytes;
  response_.reset();
  finish_request(!ec);
  if (ec) return close();
  switch (after_) {
    case After::Linger:
      return linger_close();
    case After::Close:
      return close();
    case After::NextRequest:
      return after_response();
  }
}

void Session::after_response() {
  if (after_ != After::NextRequest) return close();
  switch (job_) {
    case Job::None:
      return wait_request();
    case Job::Overdue:
      // A job that outlived its answer (504) may run on for long: no new request on this
      // connection meanwhile.
      return linger_close();
    case Job::Running:
      // The handler answered and is returning; the next read starts when it has.
      phase_ = Phase::AwaitingJob;
      return;
  }
}

// ---- streamed responses ---------------------------------------------------------------------

void Session::post_pump(std::shared_ptr<JobChannel> channel) {
  net::post(executor_, [self = shared_from_this(), channel = std::move(channel)] {
    if (!self->stream_ && self->current(channel) && channel->answer() == JobChannel::Answer::Stream)
      return self->stream_begin(channel);
    self->pump(channel);
  });
}

void Session::stream_begin(const std::shared_ptr<JobChannel>& channel) {
  std::optional<StreamHead> head = channel->take_head();
  if (!head) return channel->drop_wakeup();
  record_.profile = channel->profile();
  phase_ = Phase::Writing;
  if (server_.draining() && after_ == After::NextRequest) after_ = After::Close;
  record_.status = head->result_int();
  head->set(http::field::server, "ncpostd");
  head->set("X-Request-Id", record_.request_id);
  head->keep_alive(after_ == After::NextRequest);
  // The head is not written alone: it goes out with the first chunk (and, for a short program,
  // with the last one too), one write instead of three.
  stream_.emplace(*head);
  pump(channel);
}

void Session::pump(const std::shared_ptr<JobChannel>& channel) {
  if (!current(channel) || !stream_) {
    // No longer (or not yet: stream_begin pumps once the head is here).
    if (channel && !current(channel)) channel->drop_wakeup();
    return;
  }
  // A write in flight: its completion pumps again and takes what has come meanwhile.
  if (stream_->write() == ChunkedWriter::Write::InFlight) return;
  const JobChannel::Taken taken = channel->take(chunk_);
  const bool last = taken.end == JobChannel::StreamEnd::Complete;
  const auto& buffers = stream_->next(chunk_, last, taken.trailer);
  if (!buffers.empty()) {
    if (shutdown_ == Shutdown::None) arm_timer(server_.config().write_timeout);
    net::async_write(socket_, buffers,
                     net::bind_executor(executor_, [self = shared_from_this(), channel](
                                                       beast::error_code ec, std::size_t n) {
                       self->on_stream_written(channel, ec, n);
                     }));
    return;
  }
  if (taken.end == JobChannel::StreamEnd::Open) return;
  // A failed or cancelled post: the text ends with the error marker and the transfer is cut
  // without its last chunk, so no client can take it for a whole program.
  finish_request(false);
  close();
}

void Session::on_stream_written(const std::shared_ptr<JobChannel>& channel, beast::error_code ec,
                                std::size_t bytes) {
  record_.bytes_out += bytes;
  if (!current(channel) || !stream_) return;
  if (ec) return client_gone(channel);
  stream_->written();
  if (stream_->sent() == ChunkedWriter::Sent::Everything) {
    stream_.reset();
    finish_request(true);
    return after_response();
  }
  pump(channel);
}

void Session::client_gone(const std::shared_ptr<JobChannel>& channel) {
  if (channel) channel->client_gone();
  if (record_.status == 0) record_.status = 499;  // nginx's "client closed request", logged
  finish_request(false);
  close();
}

// ---- ending ---------------------------------------------------------------------------------

void Session::finish_request(bool complete) {
  if (!record_.open) return;
  record_.open = false;
  const auto duration = Clock::now() - record_.started;
  server_.services().metrics->request(record_.route, record_.status, duration, record_.bytes_in,
                                      record_.bytes_out);
  if (!server_.config().access_log) return;
  // Never the body, the query string or the Authorization header.
  AccessRecord line;
  line.request_id = record_.request_id;
  line.remote = remote_;
  line.method = record_.method;
  line.path = record_.path;
  line.route = record_.route;
  line.profile = record_.profile;
  line.status = record_.status;
  line.bytes_in = record_.bytes_in;
  line.bytes_out = record_.bytes_out;
  line.duration_ms = std::chrono::duration<double, std::milli>(duration).count();
  line.complete = complete;
  server_.log().info(access_line(line));
}

void Session::linger_close() {
  phase_ = Phase::Lingering;
  beast::error_code ec;
  socket_.shutdown(Socket::shutdown_send, ec);
  arm_timer(std::chrono::duration_cast<std::chrono::milliseconds>(kLingerTime));
  auto drain = std::make_shared<std::function<void(std::size_t)>>();
  auto buffer = std::make_shared<std::array<char, 16384>>();
  *drain = [self = shared_from_this(), drain, buffer](std::size_t total) {
    self->socket_.async_read_some(
        net::buffer(*buffer),
        net::bind_executor(
            self->executor_, [self, drain, total](beast::error_code e, std::size_t n) {
              if (e || total + n > kLingerBytes || self->phase_ != Phase::Lingering) {
                self->close();
                *drain = nullptr;  // break the cycle
                return;
              }
              (*drain)(total + n);
            }));
  };
  (*drain)(0);
}

void Session::close() {
  if (phase_ == Phase::Closed) return;
  if (record_.bytes_in > 0) finish_request(false);
  phase_ = Phase::Closed;
  beast::error_code ec;
  socket_.shutdown(Socket::shutdown_both, ec);
  socket_.close(ec);
  timer_.cancel();
  job_timer_.cancel();
  reservation_.release();
  if (channel_) channel_->client_gone();
}

// The connection's one deadline (read, idle or write, whichever phase it is in) is a time kept
// here; the timer's wait is only moved when it would fire too late. Each request moves the
// deadline three or four times, and moving the wait each time meant cancelling one (a queued
// completion) and a timer queue update: a fifth of a small request's cost. A wait that fires
// before the deadline waits again.
void Session::arm_timer(std::chrono::milliseconds duration) {
  deadline_ = Clock::now() + duration;
  if (timer_wait_ == Timer::Waiting && timer_.expiry() <= deadline_) return;
  wait_for_deadline();
}

void Session::disarm_timer() {
  deadline_ = Clock::time_point::max();
}

void Session::wait_for_deadline() {
  timer_wait_ = Timer::Waiting;
  timer_.expires_at(deadline_);  // cancels a wait that was later, whose completion is ignored
  timer_.async_wait(net::bind_executor(
      executor_, [self = shared_from_this()](beast::error_code ec) { self->on_timer(ec); }));
}

void Session::on_timer(beast::error_code ec) {
  if (ec == net::error::operation_aborted) return;  // moved earlier, or the connection closed
  timer_wait_ = Timer::Idle;
  if (phase_ == Phase::Closed) return;
  if (deadline_ == Clock::time_point::max()) return;  // disarmed: the next arm_timer waits
  if (deadline_ > Clock::now()) return wait_for_deadline();
  switch (phase_) {
    case Phase::Reading:
      // The read's completion answers 408.
      phase_ = Phase::ReadTimedOut;
      socket_.cancel(ec);
      return;
    case Phase::Writing:  // a client that does not read
      if (channel_) return client_gone(channel_);
      return close();
    case Phase::Handling:
    case Phase::AwaitingJob:
    case Phase::ReadTimedOut:
      return;  // the job timer rules, or the read is being cancelled
    case Phase::Idle:
    case Phase::Lingering:
    case Phase::Closed:
      return close();
  }
}

}  // namespace ncpost::server
