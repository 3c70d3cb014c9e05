// RRF104 apostrophe-in-string: `'` before a letter inside a quoted string is dropped and lower-cases the letter.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "lint/syntax/values.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF104",
    .name = "apostrophe-in-string",
    .severity = Severity::Warning,
    .fix = FixAvailability::Always,
    .summary = "An apostrophe before a letter inside a quoted string is dropped and lower-cases the letter.",
    .docs = R"md(
## What it does
Reports a `'` followed by a letter inside a double-quoted string, in commands and in meta-command
expressions (`echo`, `var`, `set` …). Unquoted text (`M117 Don't`, `M550 PBob's`) is copied as written and is
not checked.

## Why is this bad?
Inside quotes, RRF treats `'` as a case escape: it drops the apostrophe and forces the next letter to lower
case. `M550 P"Bob's printer"` names the machine `Bobs printer`, and `M291 P"Press 'OK'"` shows `Press oK'`.
Two apostrophes, `''`, give one.

## Example
```gcode
M550 P"Bob's printer"
M291 P"Don't touch the bed" S1
```

## Use instead
```gcode
M550 P"Bob''s printer"
M291 P"Don''t touch the bed" S1
```

## Fix safety
The fix doubles the apostrophe, which keeps it in the text as written. It is safe: a case escape in front of a
letter that is already lower case changes nothing else, and nobody writes one on purpose in a message.

## References
- rrflint: [Strings](../firmware-behaviour.md#strings)
- Duet3D G-code dictionary: [Quoted strings](https://docs.duet3d.com/User_manual/Reference/Gcodes#quoted-strings)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`InternalGetQuotedString()`), [ExpressionParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/ExpressionParser.cpp) (`ParseQuotedString()`)
)md",
};

// Reports the quoted strings in `s` that hold an apostrophe before a letter: one finding per string.
void scan(const FileContext& cx, Span s, Sink& out) {
  const std::string_view t = cx.source().text();
  for (uint32_t k = s.begin; k < s.end; ++k) {
    if (t[k] == '\'' && k + 2 < s.end && t[k + 2] == '\'') {  // a character literal such as '"' (3.5+)
      k += 2;
      continue;
    }
    if (t[k] != '"') continue;
    const uint32_t open = k++;
    std::vector<uint32_t> escapes;  // apostrophes before a letter
    for (; k < s.end; ++k) {
      const char c = t[k];
      if (c == '"') {
        if (k + 1 < s.end && t[k + 1] == '"') {
          ++k;
          continue;
        }
        break;
      }
      if (c != '\'' || k + 1 >= s.end) continue;
      if (t[k + 1] == '\'') ++k;
      else if (lex::is_alpha(t[k + 1])) escapes.push_back(k++);
    }
    if (escapes.empty()) continue;
    const uint32_t close = k < s.end ? k + 1 : s.end;
    Fix fix = Fix::safe(escapes.size() == 1 ? "double the apostrophe" : "double the apostrophes");
    for (uint32_t at : escapes) fix.edits.push_back(Edit::insert(cx.at(Span{at, at}), "'"));
    const uint32_t first = escapes.front();
    // Show the word around the apostrophe, as written and as RRF reads it.
    uint32_t wb = first, we = first + 2;
    while (wb > open + 1 && !lex::is_blank(t[wb - 1]) && t[wb - 1] != '"') --wb;
    while (we < close && we < s.end && !lex::is_blank(t[we]) && t[we] != '"') ++we;
    const std::string_view word = t.substr(wb, we - wb);
    out.report(kMeta, cx.at(Span{first, first + 2}),
               fmt::format("apostrophe before '{}' in a quoted string: RRF drops it and lower-cases the letter, so "
                           "\"{}\" reads as \"{}\" (write '''' for an apostrophe)",
                           t[first + 1], clip(word), clip(unquote(fmt::format("\"{}\"", word)))))
        .fix(std::move(fix));
  }
}

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  for (const uint32_t li : pf.prefilters.apostrophe_lines) {
    // No string on this line: read from its record, without decoding the line.
    if (!lex::contains(t, pf.lines.code(li), '"')) continue;
    const Line& line = pf.lines[li];
    if (line.kind == LineKind::Meta) {
      scan(cx, line.code, out);
      continue;
    }
    if (line.kind != LineKind::Commands) continue;
    for (uint32_t i = line.first_command; i < line.first_command + line.command_count; ++i) {
      const Command& c = pf.commands[i];
      for (const Param& p : pf.params(c))
        if (!lex::is_raw_text(c, p)) scan(cx, p.value, out);
    }
  }
}

}  // namespace

extern const Rule apostrophe_in_string{.meta = kMeta, .check_file = check};

}  // namespace rrflint
