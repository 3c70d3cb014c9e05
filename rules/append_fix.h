// Whether a fix may append parameters to a command (the G10 rules' "append 'Z…'").
#pragma once

#include <algorithm>

#include "lint/engine/rule.h"

namespace rrflint::tools {

/// Is text appended to the command read as parameters? Not when a parse error (an unterminated string or `{`)
/// lies in it, nor when a ';' cuts an expression open in it (`X{a Z1 ; note`, RRF113): the text would join the
/// string or the expression, and a fix that appends would come back every round (both found by fuzzing).
inline bool appendable(const NodeContext& cx) {
  const Span s = cx.command().span;
  auto inside = [&](const Span& e) { return s.begin <= e.begin && e.begin < s.end; };
  const ParsedFile& pf = cx.parsed();
  return std::none_of(pf.errors.begin(), pf.errors.end(), [&](const ParseError& e) { return inside(e.span); }) &&
         std::none_of(pf.semicolon_cuts.begin(), pf.semicolon_cuts.end(), inside);
}

}  // namespace rrflint::tools
