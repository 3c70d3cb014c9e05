// RRF310 g10-no-tool-selected: a tool-form G10 or an M568 without P at boot, where no tool is selected.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF310",
    .name = "g10-no-tool-selected",
    .severity = Severity::Error,
    .summary = "A tool-form G10 or an M568 without P, where no tool is selected.",
    .docs = R"md(
## What it does
Reports a `G10` in tool form (`L1`, or no `L` with `R`, `S` or a visible axis letter) and an `M568` (RRF 3.3+)
that have no `P`, where the machine model says no tool is selected: in config.g and the files it runs before
any `T` command, and in `tpre<n>.g`, where no tool is selected (the old one is already deselected, tool n not
yet). Without `P` both commands address the current tool. Other macros run after boot are not checked: when
they run, the user may have selected a tool; in `tfree<n>.g` and `tpost<n>.g` tool n is the current one.

On RRF 3.3 `M568` requires `P` whether a tool is selected or not; the rule reports that too.

## Why is this bad?
RRF answers `No tool number given and no current tool` (3.4+; `No tool selected` on 3.3) and sets nothing:
the offsets or temperatures meant for the tool are lost.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
G10 X0 Y0 Z0
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
G10 P0 X0 Y0 Z0
```

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms), [M568 tool settings](../firmware-behaviour.md#m568-tool-settings)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset), [M568: set tool settings](https://docs.duet3d.com/User_manual/Reference/Gcodes#m568-set-tool-settings)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`GetSpecifiedOrCurrentTool()`)
)md",
};

std::string no_tool_reply(Version fw) {
  if (fw >= kRrf3_4) return "No tool number given and no current tool";
  if (fw >= kRrf3_3) return "No tool selected";
  return "Attempt to set/report offsets and temperatures for no selected tool";
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command() || !cx.certain()) return;
  // At boot, and in a tpre<n>.g run after it, where no tool is ever selected.
  const bool tpre = file_role(cx.unit().sd_path) == FileRole::ToolPre;
  if (!cx.in_boot() && !tpre) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  const Version fw = s.firmware;
  const bool m568 = c.is('M', 568);
  if (!m568 && !c.is('G', 10)) return;
  if (cx.param('P')) return;
  if (m568 && fw < kRrf3_3) return;  // M568 does nothing there (RRF328)
  if (!m568 && !is_tool_form(cx.g10_form())) return;
  if (m568 && fw < kRrf3_4) {
    out.report(kMeta, cx.at(c.span),
               fmt::format("{} has no 'P': RRF 3.3 requires the tool number in M568 and answers 'missing parameter "
                           "'P''",
                           tools::quote(pf, c)));
    return;
  }
  if (!s.current_tool_known || s.current_tool >= 0 || s.unknown_baseline) return;
  out.report(
      kMeta, cx.at(c.span),
      fmt::format("{} has no 'P' and no tool is selected {}: RRF answers '{}' and sets nothing", tools::quote(pf, c),
                  tpre ? "inside a tpre macro (the old tool is deselected, the new one not yet selected)"
                       : "at this point of the boot sequence",
                  no_tool_reply(fw)));
}

}  // namespace

extern const Rule g10_no_tool_selected{.meta = kMeta, .check_node = check, .on = "G10 M568"};

}  // namespace rrflint
