// RRF312 g10-temperature-without-heater: temperatures for a tool that has no heaters are silently ignored.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF312",
    .name = "g10-temperature-without-heater",
    .severity = Severity::Warning,
    .summary = "G10/M568 sets temperatures for a tool defined without heaters.",
    .docs = R"md(
## What it does
Reports a tool-form `G10`, or an `M568` (RRF 3.3+), with `R` or `S` for a tool whose `M563` has no `H`
parameter (or `H-1`). It stays silent when every temperature given is 0 or lower (nothing meant to heat), when
the tool or the values are unknown (expressions, `param.*`, conditional definitions), and for a tool that names
a heater that was never created: that is the heater order rules' concern.

## Why is this bad?
RRF only sets temperatures for the heaters a tool has. For a tool with none, `R` and `S` are silently ignored
(the command just reports the tool). Usually the `H` parameter is missing from the `M563`, and the hot end will
not heat when the tool is selected.

## Example
```gcode
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M563 P0 D0
M568 P0 R150 S210
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M563 P0 D0 H1
M568 P0 R150 S210
```

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms)
- Duet3D G-code dictionary: [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool), [G10: tool temperature setting](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-tool-temperature-setting)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`SetOrReportOffsets()`: temperatures only when the tool has heaters)
)md",
};

/// Do R and S hold only known values of 0 or lower (meaning "off")? Unknown values count as not-off.
bool only_off_values(const ParsedFile& pf, const Command& c, bool& known) {
  known = true;
  bool off = true;
  for (char L : {'R', 'S'}) {
    auto v = get_float_list(pf, c, L);
    if (v.absent()) continue;
    if (!v.known()) {
      known = false;
      continue;
    }
    for (double t : v.value) off = off && t <= 0;
  }
  return off;
}

void check(const NodeContext& cx, Sink& out) {
  const Tool* tool = tools::temperature_tool(cx);
  if (!tool) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const int n = tool->number;
  if (!tools::real_heaters(*tool).empty() || tool->spindle) return;
  bool values_known = true;
  if (only_off_values(pf, c, values_known) || !values_known) return;
  out.report(kMeta, cx.at(c.span),
             fmt::format("{} sets temperatures for tool {}, which has no heaters: RRF silently ignores 'R' and 'S'",
                         tools::quote(pf, c), n))
      .note(cx.where(tool->created), fmt::format("tool {} is created here without a heater ('H')", n));
}

}  // namespace

extern const Rule g10_temperature_without_heater{.meta = kMeta, .check_node = check, .on = "G10 M568"};

}  // namespace rrflint
