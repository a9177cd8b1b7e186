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
#include "server.hpp"

namespace ncpost::server {
namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
using Clock = std::chrono::steady_clock;

// A worker blocks in write() once this much is waiting for the socket: memory per stream stays
// bounded while a slow client reads.
constexpr std::size_t kMaxPending = 1 << 20;
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
  SessionExchange(std::shared_ptr<Session> session, std::shared_ptr<RequestState> state)
      : session_(std::move(session)), state_(std::move(state)) {}
  using Exchange::end_stream;

  void respond(Response response) override {
    {
      std::lock_guard lock(state_->mutex);
      if (state_->answered) return;
      state_->answered = true;
      state_->profile = profile;
    }
    session_->hand_over(state_, std::move(response));
  }

  bool begin_stream(StreamHead head) override {
    {
      std::lock_guard lock(state_->mutex);
      if (state_->answered || state_->gone) return false;
      state_->answered = true;
      state_->streamed = true;
      state_->head = std::move(head);
      state_->profile = profile;
    }
    // Nothing is posted yet: the head goes out with the first write() or end_stream(), whose
    // pump finds it (one hop to the IO thread instead of two).
    return true;
  }

  bool write(std::string_view piece) override {
    bool post = false;
    {
      std::unique_lock lock(state_->mutex);
      state_->drained.wait(lock, [&] {
        return state_->pending.size() < kMaxPending || state_->gone || state_->abandoned;
      });
      if (state_->gone || state_->abandoned) return false;
      state_->pending.append(piece);
      post = !std::exchange(state_->pump_posted, true);
    }
    if (post) session_->post_pump(state_);
    return true;
  }

  void end_stream(bool complete, http::fields trailer) override {
    bool post = false;
    {
      std::lock_guard lock(state_->mutex);
      state_->ended = true;
      state_->complete = complete;
      state_->trailer = std::move(trailer);
      post = !std::exchange(state_->pump_posted, true);
    }
    if (post) session_->post_pump(state_);
  }

  [[nodiscard]] const std::atomic<bool>* cancel_flag() const noexcept override {
    return &state_->cancel;
  }
  [[nodiscard]] bool timed_out() const noexcept override { return state_->timed_out.load(); }

 private:
  std::shared_ptr<Session> session_;
  std::shared_ptr<RequestState> state_;
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
    // Otherwise keep_alive is false for the response in progress (server draining).
  });
}

void Session::force_close() {
  net::post(executor_, [self = shared_from_this()] {
    if (self->phase_ == Phase::Closed) return;
    // A stream under way is cancelled and given a moment to end with the profile's error
    // marker, so that the cut shows in the program text as well as in the transfer. A second
    // force (a second signal) or the end of the moment closes it.
    if (self->streaming_ && self->state_ && !self->forced_) {
      self->forced_ = true;
      self->state_->cancel = true;
      self->arm_timer(std::chrono::duration_cast<std::chrono::milliseconds>(kForcedStreamGrace));
      return;
    }
    if (self->state_) {
      self->state_->cancel = true;
      std::lock_guard lock(self->state_->mutex);
      self->state_->gone = true;
      self->state_->drained.notify_all();
    }
    self->close();
  });
}

// ---- reading --------------------------------------------------------------------------------

void Session::wait_request() {
  if (server_.draining()) return close();
  phase_ = Phase::Idle;
  state_.reset();
  // A fresh connection was opened to send a request: it gets the read limit. A kept-alive one
  // may sit idle for the idle limit.
  arm_timer(first_request_ ? server_.config().read_timeout : server_.config().idle_timeout);
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
  first_request_ = false;
  read_timed_out_ = false;
  started_ = Clock::now();
  bytes_in_ = 0;
  bytes_out_ = 0;
  status_ = 0;
  route_name_ = "unmatched";
  method_.clear();
  path_.clear();
  profile_.clear();
  request_id_ = server_.next_request_id();
  logged_ = false;
  arm_timer(server_.config().read_timeout);
  upload_parser_.reset();
  upload_.reset();
  parser_.emplace();
  parser_->header_limit(server_.config().max_header);
  parser_->body_limit(server_.config().max_body);
  // A header already in the buffer is parsed here: Beast's read would only hand it over through
  // one more queued completion.
  beast::error_code ec;
  const std::size_t used = parse_buffered(*parser_, ec, true);
  if (ec || parser_->is_header_done()) return on_header(ec, used);
  http::async_read_header(socket_, buffer_, *parser_,
                          net::bind_executor(executor_, [self = shared_from_this(), used](
                                                            beast::error_code e, std::size_t n) {
                            self->on_header(e, used + n);
                          }));
}

template <class Parser>
std::size_t Session::parse_buffered(Parser& parser, beast::error_code& ec, bool header_only) {
  std::size_t used = 0;
  while (buffer_.size() > 0 && !parser.is_done() && !(header_only && parser.is_header_done())) {
    const std::size_t n = parser.put(buffer_.data(), ec);
    buffer_.consume(n);
    used += n;
    if (ec == http::error::need_more) ec = {};
    if (ec || n == 0) break;
  }
  return used;
}

void Session::on_header(beast::error_code ec, std::size_t bytes) {
  bytes_in_ += bytes;
  if (ec) return read_failed(ec);
  const auto& header = parser_->get();
  method_ = std::string(header.method_string());
  path_ = std::string(header.target().substr(0, header.target().find('?')));
  if (const auto id = header["X-Request-Id"]; valid_request_id(id)) request_id_ = std::string(id);
  // Made now rather than at dispatch: a slice reading the upload as it arrives already needs
  // the request's cancel flag.
  state_ = std::make_shared<RequestState>();
  if (refused_as_full()) return;
  take_upload_as_it_arrives();
  // curl and browsers wait for 100 Continue before a large body; answer it only once the
  // header passed its checks, so a too-large upload is refused before it is sent.
  if (beast::iequals(header[http::field::expect], "100-continue")) {
    static constexpr std::string_view kContinue = "HTTP/1.1 100 Continue\r\n\r\n";
    net::async_write(socket_, net::buffer(kContinue.data(), kContinue.size()),
                     net::bind_executor(executor_, [self = shared_from_this()](beast::error_code e,
                                                                               std::size_t n) {
                       self->bytes_out_ += n;
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
  route_name_ = match.route->name;
  keep_alive_ = false;
  refuse_as_full(true);
  return true;
}

void Session::refuse_as_full(bool then_linger) {
  server_.services().metrics->rejected_full++;
  state_->answered = true;
  Response r = error_response(503, diag::Code::HttpQueueFull, "Service unavailable",
                              "all workers are busy and the job queue is full; retry later");
  r.set(http::field::retry_after, "1");
  send(std::move(r), then_linger);
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
      std::shared_ptr<const std::atomic<bool>>(state_, &state_->cancel), std::move(slot),
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
  const std::size_t used = parse_buffered(*parser_, ec, false);
  if (ec || parser_->is_done()) return on_body(ec, used);
  http::async_read(socket_, buffer_, *parser_,
                   net::bind_executor(executor_, [self = shared_from_this(), used](
                                                     beast::error_code e, std::size_t n) {
                     self->on_body(e, used + n);
                   }));
}

void Session::on_body(beast::error_code ec, std::size_t bytes) {
  bytes_in_ += bytes;
  if (ec) return read_failed(ec);
  disarm_timer();
  received_ = Clock::now();
  handle_request();
}

void Session::read_failed(beast::error_code ec) {
  if (phase_ == Phase::Closed) return;
  keep_alive_ = false;
  if (upload_) {
    upload_->complete();  // no more slices of an upload that will not be answered
    upload_.reset();
  }
  if (read_timed_out_) {
    status_ = 408;
    return send(error_response(408, diag::Code::HttpReadTimeout, "Request timeout",
                               "the request did not arrive within --read-timeout"),
                true);
  }
  if (ec == http::error::body_limit) {
    return send(error_response(413, diag::Code::HttpBodyTooLarge, "Content too large",
                               "the body exceeds --max-body (" +
                                   std::to_string(server_.config().max_body) + " bytes)"),
                true);
  }
  if (ec == http::error::header_limit) {
    return send(
        error_response(431, diag::Code::HttpHeaderTooLarge, "Request header fields too large",
                       "the request header exceeds --max-header (" +
                           std::to_string(server_.config().max_header) + " bytes)"),
        true);
  }
  if (ec == http::error::end_of_stream || ec == net::error::eof ||
      ec == net::error::connection_reset || ec == net::error::operation_aborted ||
      ec == http::error::partial_message) {
    if (bytes_in_ > 0) finish_request(false);
    return close();
  }
  send(error_response(400, diag::Code::HttpBadRequest, "Bad request",
                      "malformed HTTP request: " + ec.message()),
       true);
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
  keep_alive_ = request_.keep_alive();
  is_head_ = request_.method() == http::verb::head;
  RouteMatch match = match_route(request_.method(), request_.target());
  if (match.route == nullptr) {
    Response r =
        match.status == 405
            ? error_response(405, diag::Code::HttpNotFound, "Method not allowed",
                             "allowed here: " + match.allow)
            : error_response(404, diag::Code::HttpNotFound, "Not found", "no route for " + path_);
    if (match.status == 405) r.set(http::field::allow, match.allow);
    state_->answered = true;
    return send(std::move(r));
  }
  route_name_ = match.route->name;
  if (match.route->where == Where::Inline) {
    phase_ = Phase::Handling;
    SessionExchange exchange(shared_from_this(), state_);
    exchange.path_id = std::move(match.id);
    try {
      match.route->handler(request_, server_.services(), exchange);
    } catch (const std::exception& e) {
      exchange.respond(error_response(500, diag::Code::HttpInternal, "Internal error", e.what()));
    }
    return;  // the handler's respond() started the write
  }
  if (!server_.try_admit()) {
    upload_.reset();
    return refuse_as_full(false);
  }
  dispatch_job(*match.route, std::move(match.id));
}

void Session::dispatch_job(const Route& route, std::string id) {
  phase_ = Phase::Handling;
  job_running_ = true;
  writing_ = false;
  head_written_ = false;
  streaming_ = false;
  auto state = state_;
  auto& metrics = *server_.services().metrics;
  metrics.queued++;
  job_timer_.expires_after(server_.config().job_timeout);
  job_timer_.async_wait(
      net::bind_executor(executor_, [self = shared_from_this(), state](beast::error_code ec) {
        if (!ec) self->on_job_timeout(state);
      }));
  watch_client();
  auto request = std::make_shared<Request>(std::move(request_));
  net::post(server_.pool(), [self = shared_from_this(), state, request, handler = route.handler,
                             id = std::move(id), upload = std::move(upload_), received = received_,
                             &metrics]() mutable {
    metrics.queued--;
    metrics.active++;
    {
      SessionExchange exchange(self, state);
      exchange.path_id = std::move(id);
      exchange.upload = std::move(upload);
      exchange.received = received;
      // A job whose client left (or whose time ran out) while it queued is not started.
      if (!state->cancel.load()) {
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
      bool unended = false;
      {
        std::lock_guard lock(state->mutex);
        unended = state->streamed && !state->ended;
      }
      if (unended) exchange.end_stream(false);
    }
    request.reset();  // free the upload on the worker, not on the IO thread
    metrics.active--;
    self->server_.release();
    self->post_job_finished(state);
  });
}

// While a job runs the connection is otherwise silent; a readable socket then means the client
// hung up (EOF or reset), which cancels the job, or sent its next request early (pipelining).
void Session::watch_client() {
  if (watch_pending_ || phase_ == Phase::Closed) return;
  watch_pending_ = true;
  socket_.async_wait(
      Socket::wait_read,
      net::bind_executor(executor_, [self = shared_from_this()](beast::error_code ec) {
        self->watch_pending_ = false;
        if (!self->job_running_ || self->phase_ == Phase::Closed) return;
        beast::error_code e;
        const std::size_t available = self->socket_.available(e);
        if (ec || e || available == 0) return self->client_gone(self->state_);
        // Pipelined bytes: keep them for the next request, bounded by the header
        // limit.
        if (self->buffer_.size() + available > self->server_.config().max_header)
          return;  // stop watching; the next read enforces the limits
        auto buffers = self->buffer_.prepare(available);
        const std::size_t n = self->socket_.read_some(buffers, e);
        self->buffer_.commit(n);
        if (e) return self->client_gone(self->state_);
        self->watch_client();
      }));
}

void Session::on_job_timeout(const std::shared_ptr<RequestState>& state) {
  if (!current(state) || !job_running_) return;
  state->timed_out = true;
  state->cancel = true;
  bool answer_now = false;
  {
    std::lock_guard lock(state->mutex);
    if (!state->answered) {
      state->answered = true;
      state->abandoned = true;
      answer_now = true;
    }
    state->drained.notify_all();
  }
  // A stream already under way is ended by the worker with the profile's error marker.
  if (answer_now)
    send(error_response(504, diag::Code::HttpJobTimeout, "Job time limit exceeded",
                        "the job ran longer than --job-timeout (" +
                            std::to_string(server_.config().job_timeout.count()) + " ms)"));
}

void Session::post_job_finished(std::shared_ptr<RequestState> state) {
  net::post(executor_, [self = shared_from_this(), state = std::move(state)] {
    {
      std::lock_guard lock(state->mutex);
      state->finished = true;
    }
    if (state != self->state_) return;
    self->job_running_ = false;
    self->job_timer_.cancel();
    if (std::exchange(self->awaiting_job_, false) && self->phase_ != Phase::Closed)
      self->wait_request();
  });
}

// ---- buffered responses ---------------------------------------------------------------------

void Session::hand_over(std::shared_ptr<RequestState> state, Response response) {
  // An inline handler answers on the IO thread already: no hop.
  if (executor_.running_in_this_thread()) return deliver(state, std::move(response));
  net::post(executor_, [self = shared_from_this(), state = std::move(state),
                        response = std::move(response)]() mutable {
    self->deliver(state, std::move(response));
  });
}

void Session::deliver(const std::shared_ptr<RequestState>& state, Response response) {
  if (!current(state) || state->abandoned) return;
  {
    std::lock_guard lock(state->mutex);
    profile_ = state->profile;
  }
  send(std::move(response));
}

void Session::send(Response response, bool then_linger) {
  phase_ = Phase::Writing;
  if (server_.draining()) keep_alive_ = false;
  status_ = response.result_int();
  response.set(http::field::server, "ncpostd");
  response.set("X-Request-Id", request_id_);
  response.keep_alive(keep_alive_);
  response.prepare_payload();
  if (is_head_) {
    const auto length = response.body().size();
    response.body().clear();
    response.content_length(length);
  }
  response_ = std::make_shared<Response>(std::move(response));
  arm_timer(server_.config().write_timeout);
  http::async_write(socket_, *response_,
                    net::bind_executor(executor_, [self = shared_from_this(), then_linger](
                                                      beast::error_code ec, std::size_t n) {
                      self->on_write(ec, n, then_linger);
                    }));
}

void Session::on_write(beast::error_code ec, std::size_t bytes, bool then_linger) {
  bytes_out_ += bytes;
  response_.reset();
  finish_request(!ec);
  if (ec) return close();
  if (then_linger) return linger_close();
  after_response();
}

void Session::after_response() {
  if (!keep_alive_) return close();
  if (job_running_) {
    // A job that outlived its answer (504) may run on for long: no new request on this
    // connection meanwhile.
    if (state_ && state_->abandoned) return linger_close();
    // The handler answered and is returning; the next read starts when it has.
    awaiting_job_ = true;
    phase_ = Phase::Handling;
    return;
  }
  wait_request();
}

// ---- streamed responses ---------------------------------------------------------------------

void Session::post_pump(std::shared_ptr<RequestState> state) {
  net::post(executor_, [self = shared_from_this(), state = std::move(state)] {
    if (!self->streaming_ && self->current(state)) {
      bool head = false;
      {
        std::lock_guard lock(state->mutex);
        head = state->head.has_value();
      }
      if (head) return self->stream_begin(state);
    }
    self->pump(state);
  });
}

void Session::stream_begin(const std::shared_ptr<RequestState>& state) {
  if (!current(state) || state->abandoned) return;
  {
    std::lock_guard lock(state->mutex);
    stream_head_ = std::make_unique<StreamHead>(std::move(*state->head));
    state->head.reset();
    profile_ = state->profile;
  }
  phase_ = Phase::Writing;
  if (server_.draining()) keep_alive_ = false;
  status_ = stream_head_->result_int();
  stream_head_->set(http::field::server, "ncpostd");
  stream_head_->set("X-Request-Id", request_id_);
  stream_head_->keep_alive(keep_alive_);
  stream_head_->chunked(true);
  // The head is not written alone: it goes out with the first chunk (and, for a short program,
  // with the last one too), one write instead of three.
  head_bytes_.clear();
  http::response_serializer<http::empty_body> serializer(*stream_head_);
  serializer.split(true);
  beast::error_code ec;
  while (!serializer.is_header_done() && !ec) {
    serializer.next(ec, [&](beast::error_code& e, const auto& buffers) {
      e = {};
      for (const auto b : beast::buffers_range_ref(buffers))
        head_bytes_.append(static_cast<const char*>(b.data()), b.size());
      serializer.consume(beast::buffer_bytes(buffers));
    });
  }
  head_written_ = false;
  streaming_ = true;
  pump(state);
}

void Session::pump(const std::shared_ptr<RequestState>& state) {
  if (!current(state) || writing_ || !streaming_) {
    // Not yet (a write is in flight, or the head is not here yet) or no longer; the write's
    // completion, or stream_begin, pumps.
    if (state && !current(state)) {
      std::lock_guard lock(state->mutex);
      state->pump_posted = false;
    }
    return;
  }
  bool ended = false;
  bool complete = false;
  {
    std::lock_guard lock(state->mutex);
    state->pump_posted = false;
    out_chunk_.clear();
    out_chunk_.swap(state->pending);
    ended = state->ended;
    complete = state->complete;
    if (ended && complete) out_trailer_ = std::move(state->trailer);
    state->drained.notify_all();
  }
  // One gathered write: the head (first time), the chunk, and the last chunk with its trailer
  // once the job ended complete.
  out_buffers_.clear();
  if (!head_written_) out_buffers_.emplace_back(net::buffer(head_bytes_));
  if (!out_chunk_.empty()) {
    char size[24];
    const int n = std::snprintf(size, sizeof size, "%zx\r\n", out_chunk_.size());
    chunk_size_.assign(size, static_cast<std::size_t>(n));
    out_buffers_.emplace_back(net::buffer(chunk_size_));
    out_buffers_.emplace_back(net::buffer(out_chunk_));
    out_buffers_.emplace_back(net::buffer("\r\n", 2));
  }
  const bool last = ended && complete;
  if (last) {
    last_chunk_ = "0\r\n";
    for (const auto& field : out_trailer_) {
      last_chunk_.append(field.name_string());
      last_chunk_ += ": ";
      last_chunk_.append(field.value());
      last_chunk_ += "\r\n";
    }
    last_chunk_ += "\r\n";
    out_buffers_.emplace_back(net::buffer(last_chunk_));
  }
  if (!out_buffers_.empty()) {
    writing_ = true;
    if (!forced_) arm_timer(server_.config().write_timeout);
    net::async_write(socket_, out_buffers_,
                     net::bind_executor(executor_, [self = shared_from_this(), state, last](
                                                       beast::error_code ec, std::size_t n) {
                       self->on_stream_written(state, ec, n, last);
                     }));
    return;
  }
  if (!ended) return;
  // A failed or cancelled post: the text ends with the error marker and the transfer is cut
  // without its last chunk, so no client can take it for a whole program.
  finish_request(false);
  close();
}

void Session::on_stream_written(const std::shared_ptr<RequestState>& state, beast::error_code ec,
                                std::size_t bytes, bool last) {
  writing_ = false;
  bytes_out_ += bytes;
  if (!current(state)) return;
  if (ec) return client_gone(state);
  head_written_ = true;
  if (last) {
    streaming_ = false;
    stream_head_.reset();
    finish_request(true);
    return after_response();
  }
  pump(state);
}

void Session::client_gone(const std::shared_ptr<RequestState>& state) {
  if (state) {
    state->cancel = true;
    std::lock_guard lock(state->mutex);
    state->gone = true;
    state->drained.notify_all();
  }
  if (status_ == 0) status_ = 499;  // nginx's "client closed request", for the log only
  finish_request(false);
  close();
}

// ---- ending ---------------------------------------------------------------------------------

void Session::finish_request(bool complete) {
  if (logged_) return;
  logged_ = true;
  const auto duration = Clock::now() - started_;
  server_.services().metrics->request(route_name_, status_, duration, bytes_in_, bytes_out_);
  if (!server_.config().access_log) return;
  // Never the body, the query string or the Authorization header.
  AccessRecord record;
  record.request_id = request_id_;
  record.remote = remote_;
  record.method = method_;
  record.path = path_;
  record.route = route_name_;
  record.profile = profile_;
  record.status = status_;
  record.bytes_in = bytes_in_;
  record.bytes_out = bytes_out_;
  record.duration_ms = std::chrono::duration<double, std::milli>(duration).count();
  record.complete = complete;
  server_.log().info(access_line(record));
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
  if (!logged_ && bytes_in_ > 0) finish_request(false);
  phase_ = Phase::Closed;
  beast::error_code ec;
  socket_.shutdown(Socket::shutdown_both, ec);
  socket_.close(ec);
  timer_.cancel();
  job_timer_.cancel();
  if (state_) {
    state_->cancel = true;
    std::lock_guard lock(state_->mutex);
    if (!state_->finished) state_->gone = true;
    state_->drained.notify_all();
  }
}

// The connection's one deadline (read, idle or write, whichever phase it is in) is a time kept
// here; the timer's wait is only moved when it would fire too late. Each request moves the
// deadline three or four times, and moving the wait each time meant cancelling one (a queued
// completion) and a timer queue update: a fifth of a small request's cost. A wait that fires
// before the deadline waits again.
void Session::arm_timer(std::chrono::milliseconds duration) {
  deadline_ = Clock::now() + duration;
  if (timer_waiting_ && timer_.expiry() <= deadline_) return;
  wait_for_deadline();
}

void Session::disarm_timer() {
  deadline_ = Clock::time_point::max();
}

void Session::wait_for_deadline() {
  timer_waiting_ = true;
  timer_.expires_at(deadline_);  // cancels a wait that was later, whose completion is ignored
  timer_.async_wait(net::bind_executor(
      executor_, [self = shared_from_this()](beast::error_code ec) { self->on_timer(ec); }));
}

void Session::on_timer(beast::error_code ec) {
  if (ec == net::error::operation_aborted) return;  // moved earlier, or the connection closed
  timer_waiting_ = false;
  if (phase_ == Phase::Closed) return;
  if (deadline_ == Clock::time_point::max()) return;  // disarmed: the next arm_timer waits
  if (deadline_ > Clock::now()) return wait_for_deadline();
  switch (phase_) {
    case Phase::Reading:
      // The read's completion answers 408.
      read_timed_out_ = true;
      socket_.cancel(ec);
      return;
    case Phase::Writing:  // a client that does not read
      if (state_) return client_gone(state_);
      return close();
    case Phase::Handling:
      return;  // the job timer rules
    case Phase::Idle:
    case Phase::Lingering:
    case Phase::Closed:
      return close();
  }
}

}  // namespace ncpost::server
