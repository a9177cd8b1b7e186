#include "metrics.hpp"

#include <cstdio>

#include "memory_budget.hpp"

namespace ncpost::server {
namespace {

std::string number(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

}  // namespace

void Histogram::observe(std::chrono::nanoseconds duration) noexcept {
  const double seconds = std::chrono::duration<double>(duration).count();
  std::size_t i = 0;
  while (i < kBounds.size() && seconds > kBounds[i]) ++i;
  buckets_[i].fetch_add(1, std::memory_order_relaxed);
  count_.fetch_add(1, std::memory_order_relaxed);
  sum_ns_.fetch_add(static_cast<std::uint64_t>(duration.count()), std::memory_order_relaxed);
}

void Histogram::render(std::string& out, std::string_view name, std::string_view labels) const {
  std::uint64_t cumulative = 0;
  const std::string sep = labels.empty() ? "" : ",";
  for (std::size_t i = 0; i <= kBounds.size(); ++i) {
    cumulative += buckets_[i].load(std::memory_order_relaxed);
    const std::string le = i < kBounds.size() ? number(kBounds[i]) : "+Inf";
    out += std::string(name) + "_bucket{" + std::string(labels) + sep + "le=\"" + le + "\"} " +
           std::to_string(cumulative) + "\n";
  }
  const std::string braces = labels.empty() ? "" : "{" + std::string(labels) + "}";
  out += std::string(name) + "_sum" + braces + " " +
         number(static_cast<double>(sum_ns_.load(std::memory_order_relaxed)) / 1e9) + "\n";
  out += std::string(name) + "_count" + braces + " " +
         std::to_string(count_.load(std::memory_order_relaxed)) + "\n";
}

void Metrics::request(std::string_view route, unsigned status, std::chrono::nanoseconds duration,
                      std::uint64_t bytes_in, std::uint64_t bytes_out) {
  bytes_in_.fetch_add(bytes_in, std::memory_order_relaxed);
  bytes_out_.fetch_add(bytes_out, std::memory_order_relaxed);
  Histogram* histogram = nullptr;
  {
    std::lock_guard lock(mutex_);
    if (status == 0 || status == kClientClosed) {
      auto closed = client_closed_.find(route);
      if (closed == client_closed_.end())
        closed = client_closed_.try_emplace(std::string(route)).first;
      ++closed->second;
      return;
    }
    const auto key = std::pair<std::string_view, unsigned>(route, status);
    auto counter = requests_.find(key);
    if (counter == requests_.end())
      counter = requests_.emplace(std::pair<std::string, unsigned>(route, status), 0).first;
    ++counter->second;
    auto it = latency_.find(route);
    if (it == latency_.end()) it = latency_.try_emplace(std::string(route)).first;
    histogram = &it->second;
  }
  // std::map nodes never move, so the histogram can be updated outside the lock.
  histogram->observe(duration);
}

void Metrics::memory_refused(MemoryRefusal reason) noexcept {
  memory_refusals_[static_cast<std::size_t>(reason)].fetch_add(1, std::memory_order_relaxed);
}

void Metrics::stage(std::string_view stage, std::chrono::nanoseconds duration) {
  Histogram* histogram = nullptr;
  {
    std::lock_guard lock(mutex_);
    auto it = stages_.find(stage);
    if (it == stages_.end()) it = stages_.try_emplace(std::string(stage)).first;
    histogram = &it->second;
  }
  histogram->observe(duration);
}

std::string Metrics::render(const CacheCounters& cache) const {
  std::string out;
  out.reserve(8192);
  std::lock_guard lock(mutex_);
  out += "# HELP ncpost_http_requests_total HTTP requests by route and status.\n";
  out += "# TYPE ncpost_http_requests_total counter\n";
  for (const auto& [key, count] : requests_)
    out += "ncpost_http_requests_total{route=\"" + key.first + "\",status=\"" +
           std::to_string(key.second) + "\"} " + std::to_string(count) + "\n";
  out +=
      "# HELP ncpost_http_client_closed_total Requests whose client left before it was answered "
      "(logged with status 499, or 0 when the request itself was not read whole), by route.\n"
      "# TYPE ncpost_http_client_closed_total counter\n";
  for (const auto& [route, count] : client_closed_)
    out +=
        "ncpost_http_client_closed_total{route=\"" + route + "\"} " + std::to_string(count) + "\n";
  out +=
      "# HELP ncpost_http_request_duration_seconds Time from the request's arrival to the end "
      "of its response, by route.\n";
  out += "# TYPE ncpost_http_request_duration_seconds histogram\n";
  for (const auto& [route, histogram] : latency_)
    histogram.render(out, "ncpost_http_request_duration_seconds", "route=\"" + route + "\"");
  out += "# HELP ncpost_stage_duration_seconds Time spent in each pipeline stage.\n";
  out += "# TYPE ncpost_stage_duration_seconds histogram\n";
  for (const auto& [stage, histogram] : stages_)
    histogram.render(out, "ncpost_stage_duration_seconds", "stage=\"" + stage + "\"");
  out +=
      "# HELP ncpost_stylesheet_cache_hits_total Profile loads served by the compiled-"
      "stylesheet cache.\n# TYPE ncpost_stylesheet_cache_hits_total counter\n";
  out += "ncpost_stylesheet_cache_hits_total " + std::to_string(cache.hits) + "\n";
  out +=
      "# HELP ncpost_stylesheet_cache_misses_total Profile loads that compiled a "
      "stylesheet.\n# TYPE ncpost_stylesheet_cache_misses_total counter\n";
  out += "ncpost_stylesheet_cache_misses_total " + std::to_string(cache.misses) + "\n";
  out +=
      "# HELP ncpost_jobs_queued Jobs admitted and waiting for a worker.\n"
      "# TYPE ncpost_jobs_queued gauge\n";
  out += "ncpost_jobs_queued " + std::to_string(queued.load()) + "\n";
  out += "# HELP ncpost_jobs_active Jobs running on a worker.\n# TYPE ncpost_jobs_active gauge\n";
  out += "ncpost_jobs_active " + std::to_string(active.load()) + "\n";
  out +=
      "# HELP ncpost_jobs_rejected_total Jobs answered 503 because the queue was full.\n"
      "# TYPE ncpost_jobs_rejected_total counter\n";
  out += "ncpost_jobs_rejected_total " + std::to_string(rejected_full.load()) + "\n";
  if (budget != nullptr) {
    out +=
        "# HELP ncpost_inflight_bytes Bytes admitted requests hold or will hold (uploads, and "
        "the expected size of the models read from them).\n# TYPE ncpost_inflight_bytes gauge\n";
    out += "ncpost_inflight_bytes " + std::to_string(budget->in_flight()) + "\n";
    out +=
        "# HELP ncpost_inflight_budget_bytes The memory budget (--max-inflight).\n"
        "# TYPE ncpost_inflight_budget_bytes gauge\n";
    out += "ncpost_inflight_budget_bytes " + std::to_string(budget->budget()) + "\n";
    out +=
        "# HELP ncpost_inflight_reserve_bytes The part of the budget only small requests may "
        "use (--inflight-reserve).\n# TYPE ncpost_inflight_reserve_bytes gauge\n";
    out += "ncpost_inflight_reserve_bytes " + std::to_string(budget->reserve()) + "\n";
  }
  out +=
      "# HELP ncpost_inflight_refusals_total Requests the memory budget refused: 503 on the "
      "header, 503 while a chunked upload grew, 413 alone over the budget.\n"
      "# TYPE ncpost_inflight_refusals_total counter\n";
  static constexpr const char* kReasons[] = {"header", "upload", "too_large"};
  for (std::size_t i = 0; i < memory_refusals_.size(); ++i)
    out += std::string("ncpost_inflight_refusals_total{reason=\"") + kReasons[i] + "\"} " +
           std::to_string(memory_refusals_[i].load()) + "\n";
  out +=
      "# HELP ncpost_http_connections_total Connections accepted.\n"
      "# TYPE ncpost_http_connections_total counter\n";
  out += "ncpost_http_connections_total " + std::to_string(connections.load()) + "\n";
  out +=
      "# HELP ncpost_http_bytes_received_total Request bytes (headers and bodies).\n"
      "# TYPE ncpost_http_bytes_received_total counter\n";
  out += "ncpost_http_bytes_received_total " + std::to_string(bytes_in_.load()) + "\n";
  out +=
      "# HELP ncpost_http_bytes_sent_total Response bytes (headers and bodies).\n"
      "# TYPE ncpost_http_bytes_sent_total counter\n";
  out += "ncpost_http_bytes_sent_total " + std::to_string(bytes_out_.load()) + "\n";
  return out;
}

}  // namespace ncpost::server
