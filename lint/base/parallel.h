// Work split across threads inside one lint: used only for large inputs (LintOptions::part_bytes), where handing
// work to another thread is lost in the work. Results never depend on the thread count: every task writes to its
// own slot and the caller merges the slots in task order.
//
// The threads that help are kept in a pool and reused: a lint on several threads used to start and join about ten
// threads, which under the sanitizers of the fuzz build cost more system time than the lint itself.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>

namespace rrflint {

namespace detail {

/// A non-owning reference to a callable, for the pool's one entry point (no allocation, unlike std::function).
template <class Sig>
class FunctionRef;
template <class R, class... A>
class FunctionRef<R(A...)> {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, FunctionRef>>>
  FunctionRef(F& f)  // NOLINT(google-explicit-constructor): a parameter type, like std::function_ref
      : obj_(static_cast<void*>(std::addressof(f))),
        call_([](void* o, A... a) -> R { return (*static_cast<F*>(o))(std::forward<A>(a)...); }) {}
  R operator()(A... a) const { return call_(obj_, std::forward<A>(a)...); }

 private:
  void* obj_;
  R (*call_)(void*, A...);
};

/// Runs `first()` and then tasks [0, n) on the calling thread, with up to `helpers` threads of the pool taking
/// tasks beside it. Returns once every task has run (or stopped early: the first exception thrown by first() or a
/// task stops the taking of tasks and is rethrown here). The calling thread takes every task no helper took, so a
/// batch never waits for a thread to become free, and a task may itself run a batch (helpers the pool lacks are
/// started; blocked helpers are not counted as free).
void run_batch(size_t n, size_t helpers, FunctionRef<void()> first, FunctionRef<void(size_t)> task);

/// How many threads the pool has started so far (they are never stopped).
size_t pool_threads();

}  // namespace detail

/// Runs `task(i)` for i in [0, n) on up to `threads` threads, the calling thread included. `first()` runs on the
/// calling thread before it takes tasks (work that must stay on one thread, overlapped with the tasks). The first
/// exception thrown by any of them is rethrown here once every thread has stopped.
template <class Task, class First>
void run_tasks(size_t n, unsigned threads, First&& first, Task&& task) {
  // The calling thread starts with first(): up to one helper per task.
  detail::run_batch(n, std::min<size_t>(threads > 1 ? threads - 1 : 0, n), first, task);
}

/// Runs `task(i)` for i in [0, n) on up to `threads` threads, the calling thread included.
template <class Task>
void run_tasks(size_t n, unsigned threads, Task&& task) {
  // The calling thread takes tasks at once: one helper fewer than tasks.
  auto none = [] {};
  detail::run_batch(n, std::min<size_t>(threads > 1 ? threads - 1 : 0, n > 0 ? n - 1 : 0), none, task);
}

}  // namespace rrflint
