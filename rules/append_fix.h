// Whether a fix may append to a command or copy its text (the G10 rules' "append 'Z…'", RRF307's M568).
#pragma once

#include <algorithm>

#include "lint/engine/rule.h"

namespace rrflint::tools {

/// Does the command parse whole: no parse error (an unterminated string or `{`) in it, and no ';' that cuts an
/// expression open in it (`X{a Z1 ; note }`, RRF113)? A fix that appends to such a command, or copies its text,
/// would join the string or the expression or copy the broken text: a new syntax error, or a fix that comes back
/// every round (each found by fuzzing).
inline bool parses_whole(const ParsedFile& pf, const Command& c) {
  auto inside = [&](const Span& e) { return c.span.begin <= e.begin && e.begin < c.span.end; };
  return std::none_of(pf.errors.begin(), pf.errors.end(), [&](const ParseError& e) { return inside(e.span); }) &&
         std::none_of(pf.semicolon_cuts.begin(), pf.semicolon_cuts.end(), inside);
}

/// Is text appended to the command read as parameters (parses_whole)?
inline bool appendable(const NodeContext& cx) { return parses_whole(cx.parsed(), cx.command()); }

}  // namespace rrflint::tools
