#pragma once
// The numbers /metrics exposes (Prometheus text format 0.0.4). Counters are atomics or guarded
// by one small mutex per family, because every request updates them from several IO threads.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>

namespace ncpost::server {

// Fixed buckets (seconds), cumulative in the output as Prometheus wants.
class Histogram {
 public:
  static constexpr std::array<double, 14> kBounds = {
      0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 10, 60};
  void observe(std::chrono::nanoseconds duration) noexcept;
  void render(std::string& out, std::string_view name, std::string_view labels) const;

 private:
  std::array<std::atomic<std::uint64_t>, kBounds.size() + 1> buckets_{};
  std::atomic<std::uint64_t> count_{0};
  std::atomic<std::uint64_t> sum_ns_{0};
};

struct CacheCounters {
  std::uint64_t hits = 0;
  std::uint64_t misses = 0;
};

class MemoryBudget;

class Metrics {
 public:
  // Why the memory budget refused a request (ncpost_inflight_refusals_total{reason}).
  enum class MemoryRefusal : std::uint8_t {
    Header,    // 503 on the header: its upload and model do not fit now
    Upload,    // 503 while a chunked upload grew past what is free
    TooLarge,  // 413: it alone needs more than the budget admits
  };
  void memory_refused(MemoryRefusal reason) noexcept;
  // The budget whose gauges /metrics shows (set once by the server; null: none shown).
  const MemoryBudget* budget = nullptr;

  // The status nginx logs for a client that left before its answer: the access log writes it,
  // but it was never sent, so /metrics counts such requests apart (client_closed), as it does
  // those that left before they were read whole (status 0).
  static constexpr unsigned kClientClosed = 499;

  void request(std::string_view route, unsigned status, std::chrono::nanoseconds duration,
               std::uint64_t bytes_in, std::uint64_t bytes_out);
  void stage(std::string_view stage, std::chrono::nanoseconds duration);

  std::atomic<std::int64_t> queued{0};  // admitted jobs waiting for a worker
  std::atomic<std::int64_t> active{0};  // jobs running on a worker
  std::atomic<std::uint64_t> rejected_full{0};
  std::atomic<std::uint64_t> connections{0};

  // `cache` comes from the profile store at scrape time.
  [[nodiscard]] std::string render(const CacheCounters& cache) const;

 private:
  mutable std::mutex mutex_;
  // Looked up by (route, status) views, so that counting a request allocates nothing.
  struct RouteStatusLess {
    using is_transparent = void;
    template <class A, class B>
    bool operator()(const A& a, const B& b) const {
      const std::string_view ar = a.first;
      const std::string_view br = b.first;
      return ar < br || (ar == br && a.second < b.second);
    }
  };
  std::map<std::pair<std::string, unsigned>, std::uint64_t, RouteStatusLess> requests_;
  std::map<std::string, Histogram, std::less<>> latency_;
  std::map<std::string, Histogram, std::less<>> stages_;
  std::map<std::string, std::uint64_t, std::less<>> client_closed_;
  std::array<std::atomic<std::uint64_t>, 3> memory_refusals_{};
  std::atomic<std::uint64_t> bytes_in_{0};
  std::atomic<std::uint64_t> bytes_out_{0};
};

}  // namespace ncpost::server
