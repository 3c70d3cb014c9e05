// RRF117 text-after-closing-quote: a word right after a closing quote, where a quote inside the string was meant.
#include <string>

#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF117",
    .name = "text-after-closing-quote",
    .severity = Severity::Warning,
    .summary =
        "A word follows a closing quote with no blank: RRF ends the string there and reads the rest as parameters.",
    .docs = R"md(
## What it does
Reports a quoted string in a G/M/T command that is followed at once, with no blank, by a word of two or more
letters (`P"Press"Cancel" to abort"`). A `""` inside a string is a quote and does not end it; a single parameter
letter with its value straight after a string (`P"x"S3`) is a parameter as written and is not reported.
Unquoted text (`M117 Say "hi"there`) is copied as written and not checked; expressions in meta commands and
`{…}` are checked by RRF100 syntax-error.

## Why is this bad?
A quote inside a string must be written `""`. A single `"` ends the string: RRF keeps the text before it and
reads the letters after it as more parameters of the command (`C`, `A`, `N`, `E`, `L` for `Cancel`), which the
command may act on or silently ignore; a `G` or `M` among them starts another command. For commands whose string
takes the rest of the line (`M117`), the text after the quote is dropped. No error is shown: the message is cut
short and the command may do something else.

## Example
```gcode
M291 P"Press "Cancel" to abort" S3
```

## Use instead
```gcode
M291 P"Press ""Cancel"" to abort" S3
```

## References
- rrflint: [Strings](../firmware-behaviour.md#strings)
- https://github.com/Duet3D/RepRapFirmware/blob/3.6-dev/src/GCodes/GCodeBuffer/StringParser.cpp
  (`FindParameters()` and `Seen()` toggle on each `"`; `InternalGetQuotedString()` ends the string at a `"` not
  followed by another)
- https://docs.duet3d.com/User_manual/Reference/Gcodes (quoted strings: `""` for a quote)
)md",
};

// Reports the string value `v` of command `c` when a word follows its closing quote. `params` are the command's
// parameters and `i` the index of this one: the letters RRF reads are those of the parameters glued after it.
void check_string(const FileContext& cx, const Command& c, const std::vector<Param>& params, size_t i, Sink& out) {
  const std::string_view t = cx.source().text();
  const Span v = params[i].value;
  if (v.size() < 2 || t[v.end - 1] != '"' || v.end + 1 >= c.span.end) return;
  if (!lex::is_alpha(t[v.end]) || !lex::is_alpha(t[v.end + 1])) return;
  uint32_t word_end = v.end;
  while (word_end < c.span.end && lex::is_alpha(t[word_end])) ++word_end;
  const Span at{v.end - 1, word_end};
  if (params[i].letter == 0) {  // M117 "…"…: the string is the command's one argument
    out.report(kMeta, cx.at(at),
               fmt::format("text right after the closing quote: RRF ends the string at this quote and ignores the rest "
                           "('{}'); write \"\" for a quote inside a string",
                           clip(t.substr(v.end, c.span.end - v.end))));
    return;
  }
  // The parameters glued to the string (no blank before them) are the text RRF reads after it.
  std::string letters;
  uint32_t glued_end = v.end;
  for (size_t k = i + 1; k < params.size(); ++k) {
    const Param& p = params[k];
    if (p.span.begin != glued_end) break;
    if (p.letter != 0) {
      const char l = p.letter >= 'a' ? static_cast<char>(p.letter - 32) : p.letter;
      if (letters.find(l) == std::string::npos) letters += l;
    }
    glued_end = p.span.end;
  }
  std::string list;
  for (char l : letters) list += list.empty() ? fmt::format("{}", l) : fmt::format(", {}", l);
  out.report(
      kMeta, cx.at(at),
      fmt::format("text right after the closing quote: RRF ends the string {} at this quote and reads '{}' as "
                  "{}; write \"\" for a quote inside a string",
                  clip(t.substr(v.begin, v.size())), clip(t.substr(v.end, glued_end - v.end)),
                  list.empty() ? "more text" : fmt::format("parameter{} {}", letters.size() > 1 ? "s" : "", list)));
}

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  std::vector<Param> params;
  for (const uint32_t li : pf.prefilters.word_after_quote_lines) {
    if (pf.lines.kind(li) != LineKind::Commands || !lex::contains(t, pf.lines.code(li), '"')) continue;
    const Line& line = pf.lines[li];
    for (uint32_t i = line.first_command; i < line.first_command + line.command_count; ++i) {
      const Command& c = pf.commands[i];
      if (!lex::contains(t, c.span, '"')) continue;
      params.clear();
      for (const Param& p : pf.params(c)) params.push_back(p);
      for (size_t k = 0; k < params.size(); ++k) {
        const Param& p = params[k];
        if (lex::is_raw_text(c, p)) continue;
        if (p.kind == ValueKind::String || p.kind == ValueKind::List) check_string(cx, c, params, k, out);
      }
    }
  }
}

}  // namespace

extern const Rule text_after_closing_quote{.meta = kMeta, .check_file = check};

}  // namespace rrflint
