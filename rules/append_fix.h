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
  auto inside = [&](const Span& e) { return c.span.begin <= e.begin && e.begin < c.span.end; };
  return std::none_of(pf.errors.begin(), pf.errors.end(), [&](const ParseError& e) { return inside(e.span); }) &&
         std::none_of(pf.semicolon_cuts.begin(), pf.semicolon_cuts.end(), inside);
}

/// Would the command read parameter `letter` with the value `value` if " <letter><value>" were appended to it? The
/// edited line is parsed on its own, in the command's mode, as RRF would read it: the appended parameter must be
/// the command's first `letter` (the one RRF's Seen() finds), with exactly that value, and the line may have no
/// more parse errors nor ';' cuts than before. Each way an append can go wrong was first found by fuzzing, as a
/// fix that came back every round: the text joined an unterminated string or `{`, fell after a ';' that cuts an
/// expression open (`X{a ; note`), or fell into a CNC-mode '(' comment no ')' closes (`G10 P0 X1 (left tool`).
/// A line longer than kMaxReparsedLine gets no such fix.
inline bool append_reads(const ParsedFile& pf, const Command& c, char letter, std::string_view value) {
  const Span ls = pf.lines.span(c.line);
  if (c.span.begin < ls.begin || c.span.end > ls.end || ls.end - ls.begin > kMaxReparsedLine) return false;
  const std::string_view before = pf.source->slice(ls);
  const uint32_t at = c.span.end - ls.begin;
  std::string after(before.substr(0, at));
  after += ' ';
  after += letter;
  after += value;
  after += before.substr(at);
  const SourceFile was(0, "line.g", "/sys/line.g", TextBuffer(std::string(before)));
  const SourceFile now(0, "line.g", "/sys/line.g", TextBuffer(std::move(after)));
  const ParsedFile p0 = parse(was, ParseOptions{.cnc_mode = c.cnc});
  const ParsedFile p1 = parse(now, ParseOptions{.cnc_mode = c.cnc});
  if (p1.errors.size() > p0.errors.size() || p1.semicolon_cuts.size() > p0.semicolon_cuts.size()) return false;
  for (const Command& d : p1.commands) {
    if (d.span.begin != c.span.begin - ls.begin) continue;
    const ParamRef p = p1.find(d, letter);
    return p && p->span.begin == at + 1 && p1.text(p->value) == value;
  }
  return false;
}

/// May a fix append 'Z<value>' to the command (append_reads)?
inline bool appendable_z(const NodeContext& cx, std::string_view value) {
  return append_reads(cx.parsed(), cx.command(), 'Z', value);
}

}  // namespace rrflint::tools
