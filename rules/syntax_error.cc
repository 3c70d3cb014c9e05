// RRF100 syntax-error: a line RRF cannot parse.
#include "../lint/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF100",
    .name = "syntax-error",
    .severity = Severity::Error,
    .summary = "A line RRF cannot parse.",
    .docs = R"md(
## What it does
Reports lines that RepRapFirmware rejects while reading them: unterminated strings or `{…}` expressions, a
line that does not start with `G`, `M` or `T` (`Bad command`), `else`/`elif` without an `if` at the same
indentation, `break`/`continue` outside a loop, malformed `var`/`global`/`set`, NUL and 0x7F bytes.
An expression that a `;` cuts short (`X{a ; b}`) is reported once, by RRF113 semicolon-in-expression.

## Why is this bad?
RRF reports the error on the live board and skips the line; for a meta command (`if`, `var`, `else` …) it
aborts the rest of config.g and every macro it is running, leaving the machine half configured.

## Example
```gcode
M550 P"Printer ; unterminated string
IF sensors.probes[0].value[0] > 500
```

## Use instead
```gcode
M550 P"Printer"
if sensors.probes[0].value[0] > 500
```

## References
- rrf-semantics §1 (StringParser.cpp: `Put()`, `CheckMetaCommand()`, `ProcessConditionalGCode()`)
- https://docs.duet3d.com/User_manual/Reference/Gcode_meta_commands
)md",
};

void check(const FileContext& cx, Sink& out) {
  for (const ParseError& e : cx.parsed().errors) out.report(kMeta, cx.at(e.span), e.message);
}

}  // namespace

extern const Rule syntax_error{.meta = kMeta, .check_file = check};

}  // namespace rrflint
