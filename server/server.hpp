#pragma once
// The process's server object: the io_context and its threads, the worker pool, the listener,
// the live sessions (for graceful shutdown), signals, and the Services the handlers use. It is
// the only mutable state of ncpostd that outlives a request.

#include <spdlog/logger.h>

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/thread_pool.hpp>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "config.hpp"
#include "handlers.hpp"
#include "metrics.hpp"

namespace ncpost::server {

class Session;

class Server {
 public:
  // Binds the listening socket (throws boost::system::system_error when it cannot).
  Server(Config config, pipeline::Profiles& profiles, std::optional<std::string> admin_token,
         std::shared_ptr<spdlog::logger> log);
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;
  ~Server();

  // Runs until SIGTERM/SIGINT and the drain that follows; returns the exit status.
  int run();

  // ---- for sessions ----
  [[nodiscard]] Services& services() noexcept { return services_; }
  [[nodiscard]] const Config& config() const noexcept { return services_.config; }
  [[nodiscard]] boost::asio::thread_pool& pool() noexcept { return pool_; }
  [[nodiscard]] spdlog::logger& log() noexcept { return *log_; }
  // Admission to the bounded job queue: false when workers + queue jobs are already in.
  [[nodiscard]] bool try_admit() noexcept;
  void release() noexcept;
  [[nodiscard]] bool saturated() const noexcept;
  // A slot for reading an upload while it arrives (at most one per worker at a time); null when
  // none is free. Released when the last holder lets go.
  [[nodiscard]] std::shared_ptr<void> try_stream_read();
  [[nodiscard]] bool draining() const noexcept { return draining_.load(); }
  [[nodiscard]] std::string next_request_id();
  void add_session(std::uint64_t id, const std::shared_ptr<Session>& session);
  void remove_session(std::uint64_t id);
  [[nodiscard]] std::uint64_t next_session_id() noexcept { return next_session_++; }

 private:
  void accept();
  [[nodiscard]] boost::asio::io_context& next_context();
  void on_signal(int signal);
  void begin_shutdown();
  void force_close_all();
  void watch_reload();
  void reload_profiles();

  Metrics metrics_;
  pipeline::Schemas schemas_;
  Services services_;
  std::shared_ptr<spdlog::logger> log_;
  // Before ioc_: handlers that ioc_ destroys may still end sessions, which unregister here.
  std::mutex sessions_mutex_;
  std::unordered_map<std::uint64_t, std::weak_ptr<Session>> sessions_;
  bool shutdown_armed_ = false;  // guarded by sessions_mutex_
  // Before pool_: pool tasks hold stream-read slots until they end.
  std::atomic<unsigned> stream_reads_{0};
  // The listener, signals and timers, and the first IO thread's connections.
  boost::asio::io_context ioc_{1};
  // One more io_context per further IO thread: a connection lives on one of them (round robin)
  // and so needs no strand.
  std::vector<std::unique_ptr<boost::asio::io_context>> more_contexts_;
  std::size_t next_context_ = 0;  // the acceptor's handler only
  boost::asio::thread_pool pool_;
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::signal_set stop_signals_;
  boost::asio::signal_set hup_signal_;
  boost::asio::steady_timer shutdown_timer_;
  boost::asio::steady_timer reload_timer_;
  std::atomic<std::int64_t> in_system_{0};
  std::atomic<bool> draining_{false};
  std::atomic<std::uint64_t> next_request_{1};
  std::atomic<std::uint64_t> next_session_{1};
  std::uint32_t request_prefix_ = 0;
};

}  // namespace ncpost::server
