// Phase timing for performance work: with RRFLINT_TRACE set in the environment, trace::mark("what") prints the
// milliseconds since the first mark and the calling thread to stderr. Without it, a mark costs one load.
#pragma once

#include <string_view>

namespace rrflint::trace {

extern const bool kEnabled;  // RRFLINT_TRACE is set
inline bool enabled() { return kEnabled; }
double now_ms();  // since the program started
void mark_slow(const char* what);
/// Prints "took <ms> ms  <what> <detail>" (a time summed elsewhere, such as a node rule's over the forward pass).
void report_ms(const char* what, std::string_view detail, double ms);
inline void mark(const char* what) {
  if (kEnabled) mark_slow(what);
}

/// Prints how long the scope took, as "took <ms> ms  <what> <detail>", when tracing is on (and `what` is not null).
class Scope {
 public:
  Scope(const char* what, std::string_view detail = {}) : what_(what), detail_(detail) {
    if (kEnabled) start_ = now_ms();
  }
  ~Scope() {
    if (kEnabled && what_) report();
  }
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  void report() const;
  const char* what_;
  std::string_view detail_;
  double start_ = 0;
};

}  // namespace rrflint::trace
