// RRF311 g10-report-only: `G10 P<n>` with nothing to set only prints the tool's settings.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF311",
    .name = "g10-report-only",
    .severity = Severity::Info,
    .tag = RuleTag::Unnecessary,
    .summary = "G10 P<n> with no axis and no R/S only reports the tool's settings.",
    .docs = R"md(
## What it does
Reports a `G10 P<n>` (optionally with `L1`) that has no other parameter, in config.g and the files it runs
at boot. Such a command sets nothing: RRF prints the tool's offsets and temperatures, which nobody reads while
the machine boots. Standalone macros are not checked, since printing the settings may be their purpose.

## Why is this bad?
The line does nothing at boot. Usually it is what is left of an edit: the offsets were meant to be on it
(`G10 P0 X0 Y0 Z0`), or they were moved to config-override.g and the line was forgotten.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
G10 P0
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
G10 P0 X0 Y0 Z0
```

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`SetOrReportOffsets()`: with only P the tool is reported)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('G', 10) || !cx.in_boot()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  auto P = get_int(pf, c, 'P');
  if (P.absent() || cx.g10_form() != G10Form::Report) return;
  const std::string tool = P.known() ? fmt::format("tool {}", P.value) : "the tool";
  out.report(kMeta, cx.at(c.span),
             fmt::format("{} sets nothing: with no axis letter and no 'R' or 'S' it only reports {}'s offsets and "
                         "temperatures, which nobody reads at boot",
                         tools::quote(pf, c), tool));
}

}  // namespace

extern const Rule g10_report_only{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
