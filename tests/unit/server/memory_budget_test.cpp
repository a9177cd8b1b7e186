// The memory budget (server/memory_budget.hpp): admission by bytes, the reserve small requests
// keep, refusals that a retry can or cannot cure, reservations that grow and go back, and the
// default's reasoning on a 24 GB machine.

#include "memory_budget.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "config.hpp"

namespace ncpost::server {
namespace {

using Refusal = MemoryBudget::Refusal;
constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

TEST(MemoryBudget, LargeRequestsStopAtTheReserveSmallOnesUseIt) {
  MemoryBudget budget(300 * kMiB, 40 * kMiB);  // small: at most 2.5 MiB
  EXPECT_EQ(budget.small_max(), 40 * kMiB / 16);
  auto first = budget.open();
  EXPECT_EQ(first.grow(MemoryBudget::need(100 * kMiB, MemoryBudget::kModelFactor)), Refusal::None);
  EXPECT_EQ(budget.in_flight(), 230 * kMiB);
  auto second = budget.open();
  EXPECT_EQ(second.grow(40 * kMiB), Refusal::Busy) << "230 + 40 passes 260 for large requests";
  EXPECT_EQ(second.bytes(), 0u) << "a refusal takes nothing";
  EXPECT_EQ(second.grow(30 * kMiB), Refusal::None) << "exactly up to the reserve";
  std::vector<MemoryBudget::Reservation> small;
  for (int i = 0; i < 16; ++i) {
    small.push_back(budget.open());
    EXPECT_EQ(small.back().grow(2 * kMiB), Refusal::None) << "small request " << i;
  }
  auto one_more = budget.open();
  EXPECT_EQ(one_more.grow(9 * kMiB), Refusal::Busy) << "a large one never takes the reserve";
  EXPECT_EQ(one_more.grow(2 * kMiB), Refusal::None);
  first.release();
  EXPECT_EQ(first.bytes(), 0u);
  EXPECT_EQ(one_more.grow(100 * kMiB), Refusal::None) << "grown past small: the large limit";
}

TEST(MemoryBudget, AloneOverWhatTheBudgetAdmitsIsTooLarge) {
  MemoryBudget budget(300 * kMiB, 40 * kMiB);
  auto r = budget.open();
  EXPECT_EQ(r.grow(MemoryBudget::need(120 * kMiB, MemoryBudget::kModelFactor)), Refusal::TooLarge)
      << "276 MiB can never fit in the 260 large requests may use";
  EXPECT_EQ(r.grow(200 * kMiB), Refusal::None);
  EXPECT_EQ(r.grow(61 * kMiB), Refusal::TooLarge) << "a chunked upload that grows past it";
  EXPECT_EQ(r.bytes(), 200 * kMiB);
  EXPECT_EQ(budget.in_flight(), 200 * kMiB);
}

TEST(MemoryBudget, ReservationsMoveAndGoBackOnce) {
  MemoryBudget budget(100 * kMiB, 10 * kMiB);
  {
    auto a = budget.open();
    ASSERT_EQ(a.grow(50 * kMiB), Refusal::None);
    MemoryBudget::Reservation b = std::move(a);
    EXPECT_EQ(budget.in_flight(), 50 * kMiB);
    MemoryBudget::Reservation c;
    c = std::move(b);
    c.release();
    c.release();
    EXPECT_EQ(budget.in_flight(), 0u);
    ASSERT_EQ(c.grow(kMiB), Refusal::None);
  }
  EXPECT_EQ(budget.in_flight(), 0u) << "the destructor gives back what is left";
  MemoryBudget::Reservation detached;
  EXPECT_EQ(detached.grow(kMiB), Refusal::None) << "a reservation of no budget counts nothing";
}

TEST(MemoryBudget, ExhaustedWhenLessThanTheReserveIsLeftForLargeRequests) {
  MemoryBudget budget(64 * kMiB, 8 * kMiB);
  auto r = budget.open();
  ASSERT_EQ(r.grow(48 * kMiB), Refusal::None);
  EXPECT_FALSE(budget.exhausted()) << "8 MiB left for large requests";
  ASSERT_EQ(r.grow(kMiB), Refusal::None);
  EXPECT_TRUE(budget.exhausted());
  r.release();
  EXPECT_FALSE(budget.exhausted());
}

// Issue 24: 66 admitted jobs of 256 MB (workers + queue on two cores, --max-body) would need
// some 39 GB with their models; the default budget of a 24 GB machine admits what half of it
// holds, and refuses the rest with 503.
TEST(MemoryBudget, DefaultProtectsA24GbMachineFrom66UploadsOf256Mb) {
  const std::uint64_t machine = std::uint64_t{24} << 30;
  const std::uint64_t max_inflight = default_max_inflight(machine);
  EXPECT_EQ(max_inflight, machine / 2);
  MemoryBudget budget(max_inflight, default_inflight_reserve(max_inflight));
  const std::uint64_t upload = std::uint64_t{256} << 20;
  const std::uint64_t need = MemoryBudget::need(upload, MemoryBudget::kModelFactor);
  EXPECT_GT(66 * need, machine) << "without a budget the jobs would not fit";
  std::vector<MemoryBudget::Reservation> admitted;
  int refused = 0;
  for (int job = 0; job < 66; ++job) {
    auto r = budget.open();
    if (r.grow(need) == Refusal::None)
      admitted.push_back(std::move(r));
    else
      ++refused;
  }
  EXPECT_EQ(admitted.size(), (max_inflight - budget.reserve()) / need);
  EXPECT_EQ(refused, 66 - static_cast<int>(admitted.size()));
  EXPECT_LE(budget.in_flight(), max_inflight);
  EXPECT_LT(budget.in_flight() + budget.reserve(), machine / 2 + 1)
      << "the jobs and the reserve stay within half of the machine";
  auto health = budget.open();
  EXPECT_EQ(health.grow(64 * 1024), Refusal::None) << "a small request still gets in";
}

TEST(MemoryBudget, MachineMemoryIsTheSmallerOfMemTotalAndTheCgroupLimit) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("ncpost-budget-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "cgroup" / "memory");
  { std::ofstream(dir / "meminfo") << "MemTotal:       24576000 kB\nMemFree:  1000 kB\n"; }
  EXPECT_EQ(machine_memory(dir / "meminfo", dir / "cgroup"), std::uint64_t{24576000} * 1024);
  std::ofstream(dir / "cgroup" / "memory.max") << "max\n";
  EXPECT_EQ(machine_memory(dir / "meminfo", dir / "cgroup"), std::uint64_t{24576000} * 1024)
      << "cgroup v2 without a limit";
  std::ofstream(dir / "cgroup" / "memory.max") << "4294967296\n";
  EXPECT_EQ(machine_memory(dir / "meminfo", dir / "cgroup"), std::uint64_t{4} << 30);
  std::ofstream(dir / "cgroup" / "memory" / "memory.limit_in_bytes") << "9223372036854771712\n";
  EXPECT_EQ(machine_memory(dir / "meminfo", dir / "cgroup"), std::uint64_t{4} << 30)
      << "cgroup v1's 'no limit'";
  EXPECT_FALSE(machine_memory(dir / "none", dir / "none").has_value());
  EXPECT_EQ(default_max_inflight(std::nullopt), std::uint64_t{1} << 30);
  std::filesystem::remove_all(dir);
}

TEST(MemoryBudgetOptions, ParsedCheckedAndResolved) {
  const auto parse = [](std::vector<std::string_view> args) {
    args.insert(args.begin(), {"--listen", "127.0.0.1:0"});
    return parse_args(args);
  };
  const auto given = parse({"--max-inflight", "314572800", "--inflight-reserve", "1048576"});
  ASSERT_TRUE(given.config) << given.error;
  const Config resolved = resolve_memory(*given.config);
  EXPECT_EQ(resolved.max_inflight, 300 * kMiB);
  EXPECT_EQ(resolved.inflight_reserve, kMiB);
  EXPECT_FALSE(parse({"--max-inflight", "1000"}).config) << "below 1 MiB";
  EXPECT_FALSE(parse({"--max-inflight", "lots"}).config);
  EXPECT_FALSE(parse({"--max-inflight", "8388608", "--inflight-reserve", "8388608"}).config)
      << "the reserve must leave room for large requests";
  const Config defaults = resolve_memory(*parse({}).config);
  ASSERT_TRUE(defaults.max_inflight && defaults.inflight_reserve);
  EXPECT_EQ(*defaults.max_inflight, default_max_inflight(machine_memory()));
  EXPECT_EQ(*defaults.inflight_reserve, *defaults.max_inflight / 8);
  EXPECT_NE(usage().find("--max-inflight BYTES"), std::string_view::npos);
}

}  // namespace
}  // namespace ncpost::server
