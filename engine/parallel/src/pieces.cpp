#include "ncpost/parallel/pieces.hpp"

#include <atomic>
#include <condition_variable>
#include <exception>
#include <memory>

namespace ncpost::parallel {
namespace {

// Outlives run_pieces(): a task the caller claimed first may still sit in a pool's queue, and
// when it runs at last it only finds its piece taken.
struct Claims {
  explicit Claims(std::size_t count)
      : claimed(std::make_unique<std::atomic<bool>[]>(count)), unfinished(count) {}

  // True for exactly one caller per piece.
  bool claim(std::size_t index) { return !claimed[index].exchange(true); }

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

  std::unique_ptr<std::atomic<bool>[]> claimed;
  // Valid while run_pieces() waits, which is whenever a claimed piece is running.
  const std::function<void(std::size_t)>* piece = nullptr;
  std::mutex mutex;
  std::condition_variable all_done;
  std::size_t unfinished;
  std::exception_ptr error;
};

}  // namespace

void run_pieces(std::size_t count, const std::function<void(std::size_t)>& piece,
                const Helpers* helpers) {
  if (count == 0) return;
  if (max_pieces(helpers) == 1 || count == 1) {
    for (std::size_t i = 0; i < count; ++i) piece(i);
    return;
  }
  auto claims = std::make_shared<Claims>(count);
  claims->piece = &piece;
  for (std::size_t i = 1; i < count; ++i) {
    try {
      helpers->start([claims, i] {
        if (claims->claim(i)) claims->run(i);
      });
    } catch (...) {  // no thread to be had (std::system_error): the piece is done here
    }
  }
  (void)claims->claim(0);
  claims->run(0);
  // What no helper has started yet is done here; the helpers' pieces are already running.
  for (std::size_t i = 1; i < count; ++i)
    if (claims->claim(i)) claims->run(i);
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
