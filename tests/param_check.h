// Parameters are lexed twice: while parsing (for errors, counts and flags) and again on demand
// (ParsedFile::params / find). Shared by the parser test and the fuzz target: both must see the same parameters.
#pragma once

#include <string>

#include "lint/parser.h"

namespace rrflint::test {

/// Why the parameters lexed on demand for `c` disagree with what the parse recorded; empty when they agree.
inline std::string param_mismatch(const ParsedFile& pf, const Command& c) {
  uint32_t n = 0;
  bool exponent = false, colon = false;
  for (const Param& p : pf.params(c)) {
    ++n;
    exponent = exponent || p.exponent_letter;
    colon = colon || p.blank_before_colon;
    if (p.span.begin < c.span.begin || p.span.end > c.span.end) return "a parameter lies outside its command";
  }
  if (n != c.param_count)
    return "lexed " + std::to_string(n) + " parameters, the parse counted " + std::to_string(c.param_count);
  if (exponent != c.any_exponent) return "the exponent flag differs";
  if (colon != c.any_blank_before_colon) return "the blank-before-colon flag differs";
  return "";
}

}  // namespace rrflint::test
