// Helpers shared by the RRF1xx lexical rules (rules/unquoted_string.cc … rules/duplicate_parameter.cc).
#pragma once

#include <string>
#include <string_view>

#include "lint/base/strings.h"
#include "lint/syntax/parser.h"

namespace rrflint::lex {

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
inline bool is_lower(char c) { return c >= 'a' && c <= 'z'; }
inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// The command word as written: "M584", "t0", "G59.3".
inline std::string_view word(const ParsedFile& pf, const Command& c) { return pf.text(c.word); }

/// Is `p` unquoted text that runs to the end of the line (`M117 Hello`, `M550 PName`, `M98 Pfile.g`)? RRF copies
/// such text as it is: quotes, apostrophes and parentheses in it mean nothing.
inline bool is_raw_text(const Command& c, const Param& p) {
  if (p.kind != ValueKind::Text || !takes_rest_of_line(c.letter, c.number)) return false;
  return takes_unlettered_string(c.letter, c.number) ? p.letter == 0 : p.letter == 'P';
}

/// Does span `s` of `t` hold the byte `c`?
inline bool contains(std::string_view t, Span s, char c) { return span_has(t, s, c); }

/// The blanks and tabs that indent a line.
inline Span indentation(const ParsedFile& pf, const Line& line) {
  const std::string_view t = pf.source->text();
  uint32_t e = line.span.begin;
  while (e < line.span.end && is_blank(t[e])) ++e;
  return Span{line.span.begin, e};
}

/// What a fix writes before text it puts on a line of its own after `line`: the line's own line ending (at the end
/// of a file without one, the file's usual one), then the line's indentation.
inline std::string new_line_after(const ParsedFile& pf, const Line& line) {
  const SourceFile& src = *pf.source;
  return std::string(src.line_ending(src.line_of(line.span.begin))) + std::string(pf.text(indentation(pf, line)));
}

/// Calls `f(offset)` for every character of `s` that is outside quoted strings and `{…}` expressions, the way
/// RRF's Seen() walks a command. `f` returns false to stop.
template <class F>
void for_each_plain(std::string_view t, Span s, F f) {
  bool quoted = false;
  int braces = 0;
  for (uint32_t k = s.begin; k < s.end; ++k) {
    const char c = t[k];
    if (c == '"') {
      quoted = !quoted;  // a doubled "" inside a string toggles twice: same result
      continue;
    }
    if (quoted) continue;
    if (c == '{') {
      ++braces;
      continue;
    }
    if (c == '}') {
      if (braces > 0) --braces;
      continue;
    }
    if (braces > 0) continue;
    if (!f(k)) return;
  }
}

}  // namespace rrflint::lex
