#pragma once
// The memory budget (--max-inflight, docs/server.md "Memory budget"): what admitted requests
// hold or will hold, counted in bytes, so that the service answers 503 when it is full instead
// of growing until the kernel's OOM killer ends it with every job in flight. A request reserves
// on its header what it will hold (its upload, and for a route that reads a model the model's
// expected size, about kModelFactor times the text, text included); a chunked upload reserves as
// it arrives. The reservation goes back when the job no longer needs it. A reserve at the top of
// the budget is kept for small requests, so large ones never starve them.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>

namespace ncpost::server {

class MemoryBudget {
 public:
  // A job that reads a model holds about this many times its text at its peak, the text
  // included: the P21 reader's model, its indexes and the text it points into (measured on a
  // 104 MB program: ncpost trace peaks at 244 MB, a post through ncpostd at 241 MB; see
  // docs/benchmarks.md). Routes that read no model hold their body (factor 1).
  static constexpr double kModelFactor = 2.3;

  enum class Refusal : std::uint8_t {
    None,
    Busy,      // it does not fit now: 503 with Retry-After
    TooLarge,  // it alone needs more than the budget admits: 413, a retry cannot help
  };

  // `reserve`: the top of the budget only small requests (at most reserve / 16) may use.
  MemoryBudget(std::uint64_t budget, std::uint64_t reserve);
  MemoryBudget(const MemoryBudget&) = delete;
  MemoryBudget& operator=(const MemoryBudget&) = delete;

  // One request's share; gives it back when it goes. Move-only; one thread at a time.
  class Reservation {
   public:
    Reservation() = default;
    Reservation(Reservation&& other) noexcept;
    Reservation& operator=(Reservation&& other) noexcept;
    Reservation(const Reservation&) = delete;
    Reservation& operator=(const Reservation&) = delete;
    ~Reservation() { release(); }
    // Takes `bytes` more; on a refusal nothing changes.
    [[nodiscard]] Refusal grow(std::uint64_t bytes);
    void release() noexcept;
    [[nodiscard]] std::uint64_t bytes() const noexcept { return bytes_; }

   private:
    friend class MemoryBudget;
    explicit Reservation(MemoryBudget* budget) : budget_(budget) {}
    MemoryBudget* budget_ = nullptr;
    std::uint64_t bytes_ = 0;
  };

  [[nodiscard]] Reservation open() { return Reservation(this); }
  // What a body of `bytes` will hold: `factor` times it, rounded up.
  [[nodiscard]] static std::uint64_t need(std::uint64_t bytes, double factor) noexcept;

  [[nodiscard]] std::uint64_t budget() const noexcept { return budget_; }
  [[nodiscard]] std::uint64_t reserve() const noexcept { return reserve_; }
  // The largest request that may use the reserve.
  [[nodiscard]] std::uint64_t small_max() const noexcept { return reserve_ / 16; }
  [[nodiscard]] std::uint64_t in_flight() const noexcept { return in_flight_.load(); }
  // Less than the reserve's size is left for large requests: most would be refused, so /readyz
  // says not ready and a balancer sends work elsewhere.
  [[nodiscard]] bool exhausted() const noexcept {
    return in_flight() + reserve_ > budget_ - reserve_;
  }

 private:
  [[nodiscard]] Refusal take(std::uint64_t held, std::uint64_t more) noexcept;
  void give_back(std::uint64_t bytes) noexcept { in_flight_.fetch_sub(bytes); }

  std::uint64_t budget_;
  std::uint64_t reserve_;
  std::atomic<std::uint64_t> in_flight_{0};
};

// The memory this process may use: the machine's (MemTotal in `meminfo`) or its cgroup's limit
// (cgroup v2 `memory.max`, v1 `memory.limit_in_bytes`), whichever is smaller; nullopt when none
// can be read. The paths are parameters so that tests can give their own files.
[[nodiscard]] std::optional<std::uint64_t> machine_memory(
    const std::filesystem::path& meminfo = "/proc/meminfo",
    const std::filesystem::path& cgroup = "/sys/fs/cgroup");
// The default --max-inflight for a machine of `memory` bytes: half of it (docs/server.md says
// why), and 1 GiB when the machine's memory is unknown.
[[nodiscard]] std::uint64_t default_max_inflight(std::optional<std::uint64_t> memory) noexcept;
// The default reserve of a budget: an eighth of it.
[[nodiscard]] std::uint64_t default_inflight_reserve(std::uint64_t budget) noexcept;

}  // namespace ncpost::server
