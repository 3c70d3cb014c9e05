// RRF100 syntax-error: a line RRF cannot parse.
#include <algorithm>

#include "lint/engine/rule.h"

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
Expressions are read the way RRF's expression parser reads them, with its messages: a missing operand
(`X{1 + }`: `expected an expression`), a bracket closed by the wrong one (`X{(1 + 2}`: `expected ')'`), text
after a complete condition (`if true false`: `Unexpected characters after expression`) and `echo` arguments
without commas (`echo 1 2`: `expected ','`). An expression that a `;` cuts short (`X{a ; b}`) is reported once,
by RRF113 semicolon-in-expression.

In CNC and laser mode (after `M453` or `M452`) a line of axis words such as `X5 F300` repeats the last
`G0`-`G3` move and is not reported; a file that never sets the mode is given the benefit of the doubt when
another file of the machine selects one of these modes.

## Why is this bad?
RRF reports the error on the live board and skips the line; for a meta command (`if`, `var`, `else` …) it
aborts the rest of config.g and every macro it is running, leaving the machine half configured.

## Example
```gcode
M550 P"Printer ; unterminated string
IF sensors.probes[0].value[0] > 500
G1 X{(move.axes[0].max - 5} F6000
echo "probe value" sensors.probes[0].value[0]
```

## Use instead
```gcode
M550 P"Printer"
if sensors.probes[0].value[0] > 500
G1 X{(move.axes[0].max - 5)} F6000
echo "probe value", sensors.probes[0].value[0]
```

## References
- rrflint: [Meta commands](../firmware-behaviour.md#meta-commands), [Expressions](../firmware-behaviour.md#expressions), [Errors and aborts](../firmware-behaviour.md#errors-and-aborts)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`Put()`, `CheckMetaCommand()`, `ProcessConditionalGCode()`)
- https://github.com/Duet3D/RepRapFirmware/blob/3.6-dev/src/GCodes/GCodeBuffer/ExpressionParser.cpp
  (`ParseInternal()`, `ParseExpectKet()`, `CheckForExtraCharacters()`)
- https://github.com/Duet3D/RepRapFirmware/blob/3.6-dev/src/GCodes/GCodeBuffer/StringParser.cpp
  (`ProcessEchoCommand()`, `DecodeCommand()` for axis words in CNC and laser mode)
- https://docs.duet3d.com/User_manual/Reference/Gcode_meta_commands
)md",
};

// May the file run in CNC or laser mode? Only when it never sets the mode itself (the parser follows a switch in
// the file) and another file of the machine selects one (the mode is global: a macro runs in its caller's).
bool may_run_in_cnc_or_laser_mode(const FileContext& cx) {
  const ParsedFile& pf = cx.parsed();
  for (int n : {451, 452, 453})
    for (const uint32_t i : pf.with_code('M', n))
      if (pf.commands.code(i).fraction < 0) return false;
  return cx.machine.uses_code('M', 453) || cx.machine.uses_code('M', 452);
}

void check(const FileContext& cx, Sink& out) {
  const auto& errors = cx.parsed().errors;
  const bool axis_lines_ok =
      std::any_of(errors.begin(), errors.end(), [](const ParseError& e) { return e.axis_repeat; }) &&
      may_run_in_cnc_or_laser_mode(cx);
  for (const ParseError& e : errors)
    if (!(e.axis_repeat && axis_lines_ok)) out.report(kMeta, cx.at(e.span), e.message);
}

}  // namespace

extern const Rule syntax_error{.meta = kMeta, .check_file = check, .whole_card = true};

}  // namespace rrflint
