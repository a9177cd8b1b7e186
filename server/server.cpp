#include "server.hpp"

#include <boost/asio/bind_executor.hpp>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/post.hpp>
#include <csignal>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>
#include <vector>

#include "session.hpp"

#ifndef NCPOST_VERSION
#define NCPOST_VERSION "0"
#endif

namespace ncpost::server {
namespace {

namespace net = boost::asio;
using tcp = net::ip::tcp;

constexpr auto kReloadPoll = std::chrono::seconds(2);

}  // namespace

Server::Server(Config config, pipeline::Profiles& profiles, std::optional<std::string> admin_token,
               std::shared_ptr<spdlog::logger> log)
    : log_(std::move(log)),
      pool_(config.workers),
      acceptor_(ioc_),
      stop_signals_(ioc_, SIGTERM, SIGINT),
      hup_signal_(ioc_, SIGHUP),
      shutdown_timer_(ioc_),
      reload_timer_(ioc_) {
  services_.config = std::move(config);
  services_.profiles = &profiles;
  services_.schemas = &schemas_;
  services_.metrics = &metrics_;
  services_.admin_token = std::move(admin_token);
  services_.engine_version = NCPOST_VERSION;
  services_.saturated = [this] { return saturated(); };
  services_.helpers.start = [pool = pool_.get_executor()](pipeline::Task task) {
    net::post(pool, std::move(task));
  };
  services_.helpers.threads = services_.config.workers > 1 ? services_.config.workers - 1 : 0;
  const Config& c = services_.config;
  services_.web_root = c.web_root.value_or(std::filesystem::path(NCPOST_SOURCE_DIR) / "web");
  services_.openapi_file =
      c.openapi_file.value_or(std::filesystem::path(NCPOST_SOURCE_DIR) / "openapi/openapi.yaml");
  request_prefix_ = std::random_device{}();
  for (unsigned i = 1; i < c.io_threads; ++i)
    more_contexts_.push_back(std::make_unique<net::io_context>(1));

  const tcp::endpoint endpoint(net::ip::make_address(c.host), c.port);
  acceptor_.open(endpoint.protocol());
  acceptor_.set_option(net::socket_base::reuse_address(true));
  acceptor_.bind(endpoint);
  acceptor_.listen(net::socket_base::max_listen_connections);
}

Server::~Server() = default;

int Server::run() {
  const auto bound = acceptor_.local_endpoint();
  nlohmann::json line;
  line["event"] = "start";
  line["listening"] = bound.address().to_string() + ":" + std::to_string(bound.port());
  line["version"] = services_.engine_version;
  line["profiles"] = services_.profiles->directory().string();
  line["writable"] = services_.profiles->writable();
  line["io_threads"] = config().io_threads;
  line["workers"] = config().workers;
  line["queue"] = config().queue;
  line["max_body"] = config().max_body;
  line["admin_token"] = services_.admin_token.has_value();  // whether one is set, never which
  log_->info(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  log_->flush();

  stop_signals_.async_wait([this](boost::system::error_code ec, int sig) {
    if (!ec) on_signal(sig);
  });
  auto wait_hup = std::make_shared<std::function<void()>>();
  *wait_hup = [this, wait_hup] {
    hup_signal_.async_wait([this, wait_hup](boost::system::error_code ec, int) {
      if (ec) {
        *wait_hup = nullptr;
        return;
      }
      reload_profiles();
      (*wait_hup)();
    });
  };
  (*wait_hup)();
  watch_reload();
  accept();

  // The other IO threads wait for connections until the listener's context is done (the drain
  // ended); then each finishes what its own connections still do.
  std::vector<net::executor_work_guard<net::io_context::executor_type>> keep_running;
  std::vector<std::thread> threads;
  for (auto& context : more_contexts_) {
    keep_running.push_back(net::make_work_guard(*context));
    threads.emplace_back([&context = *context] { context.run(); });
  }
  ioc_.run();
  keep_running.clear();
  for (auto& t : threads) t.join();
  // Jobs that outlived the drain deadline were cancelled; wait for them to notice.
  pool_.join();
  nlohmann::json stopped;
  stopped["event"] = "stopped";
  log_->info(stopped.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  log_->flush();
  return 0;
}

net::io_context& Server::next_context() {
  const auto i = next_context_++ % (more_contexts_.size() + 1);
  return i == 0 ? ioc_ : *more_contexts_[i - 1];
}

void Server::accept() {
  acceptor_.async_accept(
      next_context(), [this](boost::system::error_code ec, Session::Socket socket) {
        if (ec == net::error::operation_aborted || !acceptor_.is_open()) return;
        if (ec) {
          // Out of descriptors, say: log, wait a little, go on accepting.
          nlohmann::json line;
          line["event"] = "accept_error";
          line["error"] = ec.message();
          log_->warn(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
          auto timer = std::make_shared<net::steady_timer>(ioc_, std::chrono::milliseconds(50));
          timer->async_wait([this, timer](boost::system::error_code) {
            if (acceptor_.is_open()) accept();
          });
          return;
        }
        std::make_shared<Session>(std::move(socket), *this)->start();
        accept();
      });
}

void Server::on_signal(int sig) {
  nlohmann::json line;
  line["event"] = "signal";
  line["signal"] = sig == SIGTERM ? "SIGTERM" : "SIGINT";
  if (draining_) {
    // A second signal: do not wait for the deadline.
    line["action"] = "force";
    log_->info(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    force_close_all();
    return;
  }
  line["action"] = "drain";
  log_->info(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  // Armed before begin_shutdown(), which cancels it when nothing is left to drain.
  stop_signals_.async_wait([this](boost::system::error_code ec, int s) {
    if (!ec) on_signal(s);
  });
  begin_shutdown();
}

void Server::begin_shutdown() {
  draining_ = true;
  boost::system::error_code ec;
  acceptor_.close(ec);
  hup_signal_.cancel(ec);
  reload_timer_.cancel();
  std::vector<std::shared_ptr<Session>> live;
  {
    std::lock_guard lock(sessions_mutex_);
    for (auto& [id, weak] : sessions_)
      if (auto s = weak.lock()) live.push_back(std::move(s));
    shutdown_armed_ = !live.empty();
  }
  for (auto& s : live) s->drain();
  if (live.empty()) {
    stop_signals_.cancel(ec);
    return;
  }
  shutdown_timer_.expires_after(config().shutdown_timeout);
  shutdown_timer_.async_wait([this](boost::system::error_code e) {
    if (e) return;
    nlohmann::json line;
    line["event"] = "shutdown_deadline";
    log_->warn(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    force_close_all();
  });
}

void Server::force_close_all() {
  std::vector<std::shared_ptr<Session>> live;
  {
    std::lock_guard lock(sessions_mutex_);
    for (auto& [id, weak] : sessions_)
      if (auto s = weak.lock()) live.push_back(std::move(s));
  }
  for (auto& s : live) s->force_close();
  boost::system::error_code ec;
  stop_signals_.cancel(ec);
  shutdown_timer_.cancel();
}

void Server::add_session(std::uint64_t id, const std::shared_ptr<Session>& session) {
  std::lock_guard lock(sessions_mutex_);
  sessions_.emplace(id, session);
}

void Server::remove_session(std::uint64_t id) {
  std::lock_guard lock(sessions_mutex_);
  sessions_.erase(id);
  // The last connection of a drain is gone: nothing is left to wait for.
  if (draining_ && sessions_.empty() && shutdown_armed_) {
    shutdown_armed_ = false;
    net::post(ioc_, [this] {
      boost::system::error_code ec;
      shutdown_timer_.cancel();
      stop_signals_.cancel(ec);
    });
  }
}

std::shared_ptr<void> Server::try_stream_read() {
  if (stream_reads_.fetch_add(1) >= config().workers) {
    stream_reads_.fetch_sub(1);
    return nullptr;
  }
  return std::shared_ptr<void>(static_cast<void*>(&stream_reads_),
                               [this](void*) { stream_reads_.fetch_sub(1); });
}

bool Server::try_admit() noexcept {
  const std::int64_t limit = std::int64_t{config().workers} + config().queue;
  std::int64_t now = in_system_.load();
  do {
    if (now >= limit) return false;
  } while (!in_system_.compare_exchange_weak(now, now + 1));
  return true;
}

void Server::release() noexcept {
  in_system_--;
}

bool Server::saturated() const noexcept {
  return in_system_.load() >= std::int64_t{config().workers} + config().queue;
}

std::string Server::next_request_id() {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%08x-%08llx", request_prefix_,
                static_cast<unsigned long long>(next_request_++));
  return buffer;
}

void Server::watch_reload() {
  reload_timer_.expires_after(kReloadPoll);
  reload_timer_.async_wait([this](boost::system::error_code ec) {
    if (ec || draining_) return;
    if (services_.profiles->changed_since_last_scan()) reload_profiles();
    watch_reload();
  });
}

void Server::reload_profiles() {
  // A stat of every profile file: cheap, but not IO-thread work.
  net::post(pool_, [this] {
    services_.profiles->reload();
    nlohmann::json line;
    line["event"] = "profiles_reloaded";
    log_->info(line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  });
}

}  // namespace ncpost::server
