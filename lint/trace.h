// Phase timing for performance work: with RRFLINT_TRACE set in the environment, trace::mark("what") prints the
// milliseconds since the first mark and the calling thread to stderr. Without it, a mark costs one load.
#pragma once

#include <string_view>

namespace rrflint::trace {

bool enabled();
void mark_slow(const char* what);
inline void mark(const char* what) {
  if (enabled()) mark_slow(what);
}

/// Prints how long the scope took, as "took <ms> ms  <what> <detail>", when tracing is on.
class Scope {
 public:
  Scope(const char* what, std::string_view detail = {});
  ~Scope();
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  const char* what_;
  std::string_view detail_;
  double start_ = 0;
};

}  // namespace rrflint::trace
