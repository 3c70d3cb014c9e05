// The pool of helper threads behind run_tasks (parallel.h).
#include "lint/base/parallel.h"

#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace rrflint::detail {

namespace {

// One call of run_batch, on its caller's stack. `seats` and `active` are guarded by the pool's mutex.
struct Batch {
  size_t n;
  FunctionRef<void(size_t)> task;
  std::atomic<size_t> next{0};
  size_t seats;       // helpers that may still join
  size_t active = 0;  // helpers taking its tasks now
  std::condition_variable all_left;
  std::mutex error_mutex;
  std::exception_ptr error;

  Batch(size_t count, FunctionRef<void(size_t)> t, size_t helpers) : n(count), task(t), seats(helpers) {}
  void fail() {
    std::lock_guard lock(error_mutex);
    if (!error) error = std::current_exception();
    next = n;  // the others stop taking tasks
  }
  // Takes tasks until none is left.
  void drain() {
    try {
      for (size_t i; (i = next++) < n;) task(i);
    } catch (...) {
      fail();
    }
  }
};

class Pool {
 public:
  // Never destroyed: its threads wait in it until the process ends, and a static destructor would have to join
  // threads that an exit() from inside a task leaves running.
  static Pool& get() {
    static Pool* const pool = new Pool;
    return *pool;
  }

  // Offers the batch's seats to the threads that wait, starting threads for the seats they cannot fill.
  void open(Batch& b) {
    std::lock_guard lock(m_);
    open_.push_back(&b);
    while (idle_ < b.seats && threads_ < kMaxThreads) {
      try {
        std::thread([this] { work(); }).detach();
      } catch (const std::system_error&) {  // no thread to be had: the caller takes the tasks
        break;
      }
      ++threads_;
      ++idle_;  // counted as idle from its start (under the lock it waits for), so that a batch opened before it
                // runs starts no other
    }
    wake_.notify_all();
  }

  size_t threads() {
    std::lock_guard lock(m_);
    return threads_;
  }

  // No helper joins the batch any more; returns once those inside have left it.
  void close(Batch& b) {
    std::unique_lock lock(m_);
    std::erase(open_, &b);
    b.all_left.wait(lock, [&] { return b.active == 0; });
  }

 private:
  // Tasks that wait for each other (the file rules wait for the graph that the caller builds) may hold threads, so
  // there is no fixed size: a bound only against a runaway.
  static constexpr size_t kMaxThreads = 256;

  void work() {  // idle_ counts this thread already
    std::unique_lock lock(m_);
    for (;;) {
      wake_.wait(lock, [&] { return !open_.empty(); });
      --idle_;
      Batch& b = *open_.front();
      ++b.active;
      if (--b.seats == 0) open_.erase(open_.begin());
      lock.unlock();
      b.drain();
      lock.lock();
      if (--b.active == 0) b.all_left.notify_all();
      ++idle_;
    }
  }

  std::mutex m_;
  std::condition_variable wake_;
  std::vector<Batch*> open_;  // batches with seats left, oldest first
  size_t idle_ = 0;           // threads waiting for a batch
  size_t threads_ = 0;
};

}  // namespace

size_t pool_threads() { return Pool::get().threads(); }

void run_batch(size_t n, size_t helpers, FunctionRef<void()> first, FunctionRef<void(size_t)> task) {
  Batch b(n, task, helpers);
  if (helpers > 0) Pool::get().open(b);
  try {
    first();
  } catch (...) {
    b.fail();
  }
  b.drain();
  if (helpers > 0) Pool::get().close(b);
  if (b.error) std::rethrow_exception(b.error);
}

}  // namespace rrflint::detail
