// run_tasks (lint/base/parallel.h) and the pool of threads behind it: every task runs once, a task may run a batch
// of its own, tasks may wait for first(), the first exception is rethrown, and the pool's threads are reused.
#include <catch2/catch.hpp>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "lint/base/parallel.h"

using namespace rrflint;

TEST_CASE("parallel: every task runs once, on up to the threads asked for", "[parallel]") {
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    for (size_t n : {size_t{0}, size_t{1}, size_t{5}, size_t{1000}}) {
      INFO(threads << " threads, " << n << " tasks");
      std::vector<std::atomic<int>> runs(n);
      std::mutex m;
      std::set<std::thread::id> ids;
      run_tasks(n, threads, [&](size_t i) {
        ++runs[i];
        std::lock_guard lock(m);
        ids.insert(std::this_thread::get_id());
      });
      for (size_t i = 0; i < n; ++i) CHECK(runs[i] == 1);
      CHECK(ids.size() <= threads);
    }
  }
}

TEST_CASE("parallel: tasks that wait for first() and batches inside tasks finish", "[parallel]") {
  // The file rules wait for the graph that first() builds on the calling thread; first() itself may parse a large
  // file in parts (a batch of its own) while every helper waits.
  for (int round = 0; round < 50; ++round) {
    std::atomic<bool> built{false};
    std::atomic<int> inner{0}, waited{0};
    run_tasks(
        4, 4,
        [&] {
          run_tasks(16, 3, [&](size_t) { ++inner; });
          built = true;
          built.notify_all();
        },
        [&](size_t i) {
          built.wait(false);
          ++waited;
          run_tasks(8, 2, [&](size_t) { ++inner; });  // a batch inside a task
          (void)i;
        });
    CHECK(waited == 4);
    CHECK(inner == 16 + 4 * 8);
  }
}

TEST_CASE("parallel: the first exception is rethrown and the other tasks stop", "[parallel]") {
  for (unsigned threads : {1u, 4u}) {
    INFO(threads << " threads");
    std::atomic<int> ran{0};
    CHECK_THROWS_WITH(run_tasks(10'000, threads,
                                [&](size_t i) {
                                  ++ran;
                                  if (i == 3) throw std::runtime_error("task 3");
                                }),
                      "task 3");
    // On one thread no task runs after the one that threw. Helpers stop as soon as they see it, but how soon is
    // up to the scheduler: on several threads only the exception is checked.
    if (threads == 1) CHECK(ran == 4);
  }
  CHECK_THROWS_WITH(run_tasks(
                        10, 3, [] { throw std::runtime_error("first"); }, [](size_t) {}),
                    "first");
  // The pool still works afterwards.
  std::atomic<int> after{0};
  run_tasks(100, 4, [&](size_t) { ++after; });
  CHECK(after == 100);
}

TEST_CASE("parallel: the pool's threads are reused from batch to batch", "[parallel]") {
  std::atomic<int> ran{0};
  run_tasks(8, 3, [&](size_t) { ++ran; });  // the pool has its helpers now
  const size_t started = detail::pool_threads();
  CHECK(started >= 2);
  for (int round = 0; round < 200; ++round)
    run_tasks(8, 3, [&](size_t) {
      std::this_thread::yield();
      ++ran;
    });
  CHECK(ran == 201 * 8);
  CHECK(detail::pool_threads() == started);  // started afresh, two helpers a batch would be 400 more
}
