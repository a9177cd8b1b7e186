// parallel::run_pieces: every piece runs exactly once whichever thread claims it, the call
// returns only when all have finished, an exception reaches the caller, and a helper that never
// runs its task (a pool busy with other jobs) costs nothing but the caller's own time.

#include "ncpost/parallel/pieces.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <vector>

namespace ncpost::parallel {
namespace {

TEST(RunPieces, EachPieceRunsOnceWhoeverRunsIt) {
  const ThreadGroup threads(3);
  const Helpers never{[](const Task&) {}, 3};
  const Helpers at_once{[](const Task& task) { task(); }, 3};
  for (const Helpers* helpers :
       {&threads.helpers(), &never, &at_once, static_cast<const Helpers*>(nullptr)})
    for (std::size_t count : {1u, 2u, 4u, 9u}) {
      std::vector<std::atomic<int>> runs(count);
      run_pieces(
          count, [&](std::size_t i) { ++runs[i]; }, helpers);
      for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << i;
    }
}

TEST(RunPieces, ReturnsOnlyWhenAHelpersPieceHasFinished) {
  const ThreadGroup threads(1);
  std::atomic<bool> helper_done{false};
  run_pieces(
      2,
      [&](std::size_t i) {
        if (i == 0) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        helper_done = true;
      },
      &threads.helpers());
  EXPECT_TRUE(helper_done.load());
}

TEST(RunPieces, AnExceptionReachesTheCaller) {
  const ThreadGroup threads(2);
  std::atomic<int> finished{0};
  EXPECT_THROW(run_pieces(
                   3,
                   [&](std::size_t i) {
                     if (i == 2) throw std::runtime_error("piece 2");
                     ++finished;
                   },
                   &threads.helpers()),
               std::runtime_error);
  EXPECT_EQ(finished.load(), 2);
}

TEST(RunPieces, AHelperThatCannotStartLeavesThePieceToTheCaller) {
  const Helpers failing{
      [](const Task&) {
        throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again));
      },
      1};
  int runs = 0;
  run_pieces(
      2, [&](std::size_t) { ++runs; }, &failing);
  EXPECT_EQ(runs, 2);
}

TEST(MaxPieces, CountsTheCallerToo) {
  EXPECT_EQ(max_pieces(nullptr), 1u);
  const Helpers none{};
  EXPECT_EQ(max_pieces(&none), 1u);
  const ThreadGroup threads(3);
  EXPECT_EQ(max_pieces(&threads.helpers()), 4u);
}

}  // namespace
}  // namespace ncpost::parallel
