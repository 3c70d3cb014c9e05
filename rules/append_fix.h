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

/// Does the command end inside a CNC-mode comment that no ')' closes (`G10 P0 X1 (left tool`)? RRF reads such a
/// comment to the end of the line, so text appended to the command would be part of it (found by fuzzing: the
/// append fix came back every round). Quotes and `{…}` outside a comment hide their parentheses, as in RRF.
inline bool ends_in_open_comment(const ParsedFile& pf, const Command& c) {
  if (!c.cnc) return false;
  const std::string_view t = pf.source->text();
  bool quoted = false, comment = false;
  int braces = 0;
  for (uint32_t k = c.span.begin; k < c.span.end; ++k) {
    const char ch = t[k];
    if (comment) comment = ch != ')';
    else if (ch == '"') quoted = !quoted;
    else if (quoted) continue;
    else if (ch == '{') ++braces;
    else if (ch == '}') braces -= braces > 0;
    else if (ch == '(' && braces == 0) comment = true;
  }
  return comment;
}

/// Is text appended to the command read as parameters (parses_whole, and no open CNC comment at its end)?
inline bool appendable(const NodeContext& cx) {
  return parses_whole(cx.parsed(), cx.command()) && !ends_in_open_comment(cx.parsed(), cx.command());
}

}  // namespace rrflint::tools
