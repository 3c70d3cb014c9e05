// Whether a fix may append to a command or copy its text (the G10 rules' "append 'Z…'", RRF307's M568).
#pragma once

#include <algorithm>
#include <string>
#include <string_view>

#include "lint/base/source.h"
#include "lint/engine/rule.h"
#include "lint/syntax/parser.h"
#include "rules/edit_parses.h"

namespace rrflint::tools {

/// Does the command parse whole: no parse error (an unterminated string or `{`) in it, and no ';' that cuts an
/// expression open in it (`X{a Z1 ; note }`, RRF113)? A fix that copies the text of such a command would copy the
/// broken text: a new syntax error (found by fuzzing).
inline bool parses_whole(const ParsedFile& pf, const Command& c) {
  return !pf.any_error_from(c.span.begin, c.span.end) && !pf.any_cut_from(c.span.begin, c.span.end);
}

/// Would the command read parameter `letter` with the value `value` if " <letter><value>" were appended to it? The
/// edited line is parsed on its own, in the command's mode, as RRF would read it: the appended parameter must be
/// the command's first `letter` (the one RRF's Seen() finds), with exactly that value, and the line may have no
/// more parse errors nor ';' cuts than before. Each way an append can go wrong was first found by fuzzing, as a
/// fix that came back every round: the text joined an unterminated string or `{`, fell after a ';' that cuts an
/// expression open (`X{a ; note`), or fell into a CNC-mode '(' comment no ')' closes (`G10 P0 X1 (left tool`).
/// A line longer than kMaxReparsedLine gets no such fix.
inline bool append_reads(const ParsedFile& pf, const Command& c, char letter, std::string_view value) {
  const Span at{c.span.end, c.span.end};
  if (c.span.begin < pf.lines.span(c.line).begin) return false;
  std::string appended(" ");
  appended += letter;
  appended += value;
  const EditedLine e(pf, c.line, at, appended, c.cnc);
  if (!e.ok()) return false;
  const ParsedFile &p0 = e.before(), &p1 = e.after();
  if (p1.errors.size() > p0.errors.size() || p1.semicolon_cuts.size() > p0.semicolon_cuts.size()) return false;
  for (const Command& d : p1.commands) {
    if (d.span.begin != c.span.begin - e.line_begin()) continue;
    const ParamRef p = p1.find(d, letter);
    return p && p->span.begin == at.begin - e.line_begin() + 1 && p1.text(p->value) == value;
  }
  return false;
}

/// May a fix append 'Z<value>' to the command (append_reads)?
inline bool appendable_z(const NodeContext& cx, std::string_view value) {
  return append_reads(cx.parsed(), cx.command(), 'Z', value);
}

}  // namespace rrflint::tools
