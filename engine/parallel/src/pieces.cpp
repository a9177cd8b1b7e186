#include "ncpost/parallel/pieces.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <memory>

namespace ncpost::parallel {
namespace {

// Outlives run_pieces(): a helper's task may still sit in a pool's queue when the caller has
// done every piece, and when it runs at last it finds nothing left to take.
struct Claims {
  Claims(std::size_t count_, const std::function<void(std::size_t)>& piece_)
      : count(count_), piece(&piece_), unfinished(count_) {}

  // The next piece no thread has taken, or `count` once all are taken.
  std::size_t take() { return next.fetch_add(1); }

  void run(std::size_t index) {
    try {
      (*piece)(index);
    } catch (...) {
      const std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    if (--unfinished == 0) all_done.notify_all();
  }

  void run_what_is_left() {
    for (std::size_t index = take(); index < count; index = take()) run(index);
  }

  const std::size_t count;
  std::atomic<std::size_t> next{0};
  // Valid while run_pieces() waits, which is whenever a taken piece is running.
  const std::function<void(std::size_t)>* piece;
  std::mutex mutex;
  std::condition_variable all_done;
  std::size_t unfinished;
  std::exception_ptr error;
};

}  // namespace

void run_pieces(std::size_t count, const std::function<void(std::size_t)>& piece,
                const Helpers* helpers) {
  if (max_pieces(helpers) == 1 || count <= 1) {
    for (std::size_t i = 0; i < count; ++i) piece(i);
    return;
  }
  auto claims = std::make_shared<Claims>(count, piece);
  const std::size_t first = claims->take();  // 0, taken before any helper can start
  const std::size_t helper_tasks = std::min(helpers->threads, count - 1);
  for (std::size_t i = 0; i < helper_tasks; ++i) {
    try {
      helpers->start([claims] { claims->run_what_is_left(); });
    } catch (...) {  // no thread to be had (std::system_error): the caller does more
    }
  }
  claims->run(first);
  claims->run_what_is_left();
  std::unique_lock lock(claims->mutex);
  claims->all_done.wait(lock, [&] { return claims->unfinished == 0; });
  if (claims->error) std::rethrow_exception(claims->error);
}

ThreadGroup::ThreadGroup(std::size_t threads) {
  helpers_.threads = threads;
  helpers_.start = [this](Task task) {
    const std::lock_guard lock(mutex_);
    threads_.emplace_back(std::move(task));
  };
}

ThreadGroup::~ThreadGroup() {
  const std::lock_guard lock(mutex_);
  for (auto& thread : threads_) thread.join();
}

std::size_t spare_cores() {
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 1 ? cores - 1 : 0;
}

}  // namespace ncpost::parallel
