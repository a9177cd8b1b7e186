#include "memory_budget.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>

namespace ncpost::server {
namespace {

std::optional<std::uint64_t> read_number(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text == "max") return std::nullopt;
  try {
    std::size_t used = 0;
    const std::uint64_t value = std::stoull(text, &used);
    if (used != text.size()) return std::nullopt;
    return value;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

MemoryBudget::MemoryBudget(std::uint64_t budget, std::uint64_t reserve)
    : budget_(budget), reserve_(std::min(reserve, budget)) {}

MemoryBudget::Reservation::Reservation(Reservation&& other) noexcept
    : budget_(other.budget_), bytes_(std::exchange(other.bytes_, 0)) {}

MemoryBudget::Reservation& MemoryBudget::Reservation::operator=(Reservation&& other) noexcept {
  if (this != &other) {
    release();
    budget_ = other.budget_;
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

MemoryBudget::Refusal MemoryBudget::Reservation::grow(std::uint64_t bytes) {
  if (bytes == 0 || budget_ == nullptr) return Refusal::None;
  const Refusal refusal = budget_->take(bytes_, bytes);
  if (refusal == Refusal::None) bytes_ += bytes;
  return refusal;
}

void MemoryBudget::Reservation::release() noexcept {
  if (budget_ != nullptr && bytes_ > 0) budget_->give_back(bytes_);
  bytes_ = 0;
}

std::uint64_t MemoryBudget::need(std::uint64_t bytes, double factor) noexcept {
  return static_cast<std::uint64_t>(std::ceil(static_cast<double>(bytes) * factor));
}

// A small request may use the whole budget, a large one all but the reserve; one that alone
// passes what it may use never fits.
MemoryBudget::Refusal MemoryBudget::take(std::uint64_t held, std::uint64_t more) noexcept {
  const std::uint64_t total = held + more;
  const std::uint64_t limit = total <= small_max() ? budget_ : budget_ - reserve_;
  if (total > limit) return Refusal::TooLarge;
  std::uint64_t now = in_flight_.load();
  do {
    if (now + more > limit) return Refusal::Busy;
  } while (!in_flight_.compare_exchange_weak(now, now + more));
  return Refusal::None;
}

std::optional<std::uint64_t> machine_memory(const std::filesystem::path& meminfo,
                                            const std::filesystem::path& cgroup) {
  std::optional<std::uint64_t> memory;
  std::ifstream in(meminfo);
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit) {
    if (key == "MemTotal:") {
      memory = kib * 1024;
      break;
    }
  }
  for (const auto* limit : {"memory.max", "memory/memory.limit_in_bytes"}) {
    // cgroup v1 says "no limit" with a number near 2^63.
    if (auto bytes = read_number(cgroup / limit); bytes && *bytes < (std::uint64_t{1} << 60))
      memory = memory ? std::min(*memory, *bytes) : *bytes;
  }
  return memory;
}

std::uint64_t default_max_inflight(std::optional<std::uint64_t> memory) noexcept {
  return memory ? *memory / 2 : std::uint64_t{1} << 30;
}

std::uint64_t default_inflight_reserve(std::uint64_t budget) noexcept {
  return budget / 8;
}

}  // namespace ncpost::server
