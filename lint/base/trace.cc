#include "lint/base/trace.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <thread>
#include <utility>

namespace rrflint::trace {

namespace {
const auto start = std::chrono::steady_clock::now();
}  // namespace

const bool kEnabled = std::getenv("RRFLINT_TRACE") != nullptr;

double now_ms() { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(); }

void report_ms(const char* what, std::string_view detail, double ms) {
  std::fprintf(stderr, "took  %8.2f ms  %s %.*s\n", ms, what, static_cast<int>(detail.size()), detail.data());
}

void Scope::report() const { report_ms(what_, detail_, now_ms() - start_); }

namespace {
// Resident memory now and at its peak so far, in MiB (Linux; 0 elsewhere): where in the pipeline the peak falls.
std::pair<long, long> rss_mib() {
  long now = 0, peak = 0;
#ifdef __linux__
  if (FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, f)) {
      std::sscanf(line, "VmRSS: %ld", &now);
      std::sscanf(line, "VmHWM: %ld", &peak);
    }
    std::fclose(f);
  }
#endif
  return {now / 1024, peak / 1024};
}
}  // namespace

void mark_slow(const char* what) {
  const double ms = now_ms();
  const size_t tid = std::hash<std::thread::id>{}(std::this_thread::get_id()) % 1000;
  const auto [rss, peak] = rss_mib();
  std::fprintf(stderr, "trace %8.2f ms  [%03zu] %-20s rss %5ld MiB, peak %5ld MiB\n", ms, tid, what, rss, peak);
}

}  // namespace rrflint::trace
