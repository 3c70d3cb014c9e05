// Work split across threads inside one lint: used only for large inputs (LintOptions::part_bytes), where a
// thread's start-up (tens of microseconds) is lost in the work. Results never depend on the thread count: every
// task writes to its own slot and the caller merges the slots in task order.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rrflint {

namespace detail {

// Runs `first()` and then tasks on the calling thread, and tasks on `extra` new threads.
template <class Task, class First>
void run_pool(size_t n, size_t extra, First&& first, Task&& task) {
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto guarded = [&](auto&& f) {
    try {
      f();
    } catch (...) {
      std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      next = n;  // the others stop taking tasks
    }
  };
  auto work = [&] {
    guarded([&] {
      for (size_t i; (i = next++) < n;) task(i);
    });
  };
  std::vector<std::thread> pool;
  for (size_t k = 0; k < extra; ++k) pool.emplace_back(work);
  guarded(first);
  work();
  for (std::thread& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace detail

/// Runs `task(i)` for i in [0, n) on up to `threads` threads, the calling thread included. `first()` runs on the
/// calling thread before it takes tasks (work that must stay on one thread, overlapped with the tasks). The first
/// exception thrown by any of them is rethrown here once every thread has stopped.
template <class Task, class First>
void run_tasks(size_t n, unsigned threads, First&& first, Task&& task) {
  // The calling thread starts with first(): up to one new thread per task.
  detail::run_pool(n, std::min<size_t>(threads > 1 ? threads - 1 : 0, n), first, task);
}

/// Runs `task(i)` for i in [0, n) on up to `threads` threads, the calling thread included.
template <class Task>
void run_tasks(size_t n, unsigned threads, Task&& task) {
  // The calling thread takes tasks at once: one new thread fewer than tasks.
  detail::run_pool(
      n, std::min<size_t>(threads > 1 ? threads - 1 : 0, n > 0 ? n - 1 : 0), [] {}, task);
}

}  // namespace rrflint
