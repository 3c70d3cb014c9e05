// RRF113 semicolon-in-expression: a ';' inside `{…}` still starts a comment and cuts the expression.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF113",
    .name = "semicolon-in-expression",
    .severity = Severity::Error,
    .summary = "A ';' inside an expression starts a comment and cuts the expression short.",
    .docs = R"md(
## What it does
Reports an expression that a `;` cuts short: a `{…}` in a command, or the condition or value of a meta
command (`if`, `while`, `var`, `set`, `echo` …), that is still open at a `;` while its closing bracket comes
later on the line. A `;` inside a quoted string is fine. An expression that is never closed is a syntax error
(RRF100), not this rule.

## Why is this bad?
RRF's standalone parser looks for `;` outside quoted strings only; braces do not protect it. Everything from the
`;` on is a comment, so the expression ends unclosed and RRF rejects the command with an expression error. In
a meta command that error aborts the rest of the file.

## Example
```gcode
G1 X{move.axes[0].max - 5 ; stay off the edge} F3000
echo {"probe " ^ "done"; "ok"}
```

## Use instead
```gcode
G1 X{move.axes[0].max - 5} F3000 ; stay off the edge
echo {"probe " ^ "done"}
```

## References
- rrflint: [Comments](../firmware-behaviour.md#comments), [Expressions](../firmware-behaviour.md#expressions)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`Put()`: the `;` case does not test the brace count)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  for (const Span cut : pf.semicolon_cuts) {
    uint32_t semi = cut.end;
    while (semi < t.size() && lex::is_blank(t[semi])) ++semi;
    // The line of the cut: the last that starts at or before it (lines are in order).
    size_t lo = 0, hi = pf.lines.size();
    while (hi - lo > 1) {
      const size_t mid = lo + (hi - lo) / 2;
      (pf.lines.span(mid).begin <= cut.begin ? lo : hi) = mid;
    }
    const bool meta =
        lo < pf.lines.size() && pf.lines.kind(lo) == LineKind::Meta && pf.lines.span(lo).contains(cut.begin);
    out.report(kMeta, cx.at(Span{semi, semi + 1}),
               fmt::format("';' inside an expression starts a comment: RRF reads only '{}' and fails with an "
                           "expression error{}",
                           clip(pf.text(cut)), meta ? ", which aborts the rest of the file" : ""))
        .note(cx.at(Span{cut.begin, cut.begin + 1}), "the expression opens here");
  }
}

}  // namespace

extern const Rule semicolon_in_expression{.meta = kMeta, .check_file = check};

}  // namespace rrflint
