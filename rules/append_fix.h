// Whether a fix may append parameters to a command (the G10 rules' "append 'Z…'").
#pragma once

#include "lint/engine/rule.h"

namespace rrflint::tools {

/// Is text appended to the command read as parameters? Not when a parse error (an unterminated string or `{`)
/// lies in it: the text would join the string, and a fix that appends would come back every round (found by fuzzing).
inline bool appendable(const NodeContext& cx) {
  const Span s = cx.command().span;
  for (const ParseError& e : cx.parsed().errors)
    if (s.begin <= e.span.begin && e.span.begin < s.end) return false;
  return true;
}

}  // namespace rrflint::tools
