#pragma once
// One job's work in pieces, on threads the caller lends.
//
// The engine keeps no thread pool: whoever runs the job says how to start a task elsewhere
// (`Helpers`): the CLI gives each task a thread of its own (ThreadGroup), ncpostd posts it to its
// worker pool. The pieces are taken in order from one counter by the caller and by whichever
// helpers have started, so the caller never waits for a piece that no thread has started: on a
// busy pool, where the helpers' tasks wait in the queue behind other jobs, the caller does every
// piece itself, and a helper that starts after the last piece was taken finds nothing to do.

#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace ncpost::parallel {

using Task = std::function<void()>;

struct Helpers {
  // Starts `task` on another thread, now or later. It may also never run it (a pool that is
  // shutting down); the caller's piece is then done by the caller.
  std::function<void(Task)> start;
  // How many helper threads may run at once; a job splits into at most threads + 1 pieces.
  std::size_t threads = 0;
};

// How many pieces `helpers` can take a job to (1 without helpers).
[[nodiscard]] inline std::size_t max_pieces(const Helpers* helpers) {
  return helpers == nullptr || !helpers->start ? 1 : helpers->threads + 1;
}

// Runs piece(0) .. piece(count - 1), each exactly once, and returns when every one has finished.
// Piece 0 runs on the calling thread; the others are taken in index order by the calling thread
// and by up to helpers->threads helpers (null: all run here, in order). There may be more pieces
// than threads. An exception from any piece is rethrown here once all have finished.
void run_pieces(std::size_t count, const std::function<void(std::size_t)>& piece,
                const Helpers* helpers);

// Helpers for a command-line job: each task gets a thread of its own, and the group joins them
// when it goes out of scope. Keep the group alive for as long as the job may start tasks.
class ThreadGroup {
 public:
  explicit ThreadGroup(std::size_t threads);
  ~ThreadGroup();
  ThreadGroup(const ThreadGroup&) = delete;
  ThreadGroup& operator=(const ThreadGroup&) = delete;

  [[nodiscard]] const Helpers& helpers() const { return helpers_; }

 private:
  std::mutex mutex_;
  std::vector<std::thread> threads_;
  Helpers helpers_;
};

// The helper threads worth lending on this machine: one fewer than its cores.
[[nodiscard]] std::size_t spare_cores();

}  // namespace ncpost::parallel
