// Work split across threads inside one lint: used only for large inputs (LintOptions::part_bytes), where a
// thread's start-up (tens of microseconds) is lost in the work. Results never depend on the thread count: every
// task writes to its own slot and the caller merges the slots in task order.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rrflint {

/// Runs `task(i)` for i in [0, n) on up to `threads` threads, the calling thread included. `first()` runs on the
/// calling thread before it takes tasks (work that must stay on one thread, overlapped with the tasks). The first
/// exception thrown by any of them is rethrown here once every thread has stopped.
template <class Task, class First>
void run_tasks(size_t n, unsigned threads, First&& first, Task&& task) {
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
  for (unsigned k = 1; k < threads && k <= n; ++k) pool.emplace_back(work);
  guarded(first);
  work();
  for (std::thread& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

template <class Task>
void run_tasks(size_t n, unsigned threads, Task&& task) {
  run_tasks(n, threads, [] {}, std::forward<Task>(task));
}

}  // namespace rrflint
