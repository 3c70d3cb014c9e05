#include "lint/base/trace.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <thread>

namespace rrflint::trace {

namespace {
const auto start = std::chrono::steady_clock::now();
}  // namespace

const bool kEnabled = std::getenv("RRFLINT_TRACE") != nullptr;

double now_ms() { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(); }

void Scope::report() const {
  std::fprintf(stderr, "took  %8.2f ms  %s %.*s\n", now_ms() - start_, what_, static_cast<int>(detail_.size()),
               detail_.data());
}

void mark_slow(const char* what) {
  const double ms = now_ms();
  const size_t tid = std::hash<std::thread::id>{}(std::this_thread::get_id()) % 1000;
  std::fprintf(stderr, "trace %8.2f ms  [%03zu] %s\n", ms, tid, what);
}

}  // namespace rrflint::trace
