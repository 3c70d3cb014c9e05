// RRF327 m585-at-boot: M585 (probe a tool offset) at boot, where no tool is selected and nothing is homed.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF327",
    .name = "m585-at-boot",
    .severity = Severity::Error,
    .summary = "M585 in config.g or a file it runs at boot, where no tool is selected and no axis is homed.",
    .docs = R"md(
## What it does
Reports `M585` (probe a tool offset) in the boot sequence: config.g and the files it runs. It stays silent
inside `if`/`while` blocks, and when a tool is selected and a `G28` ran earlier in the boot sequence.

## Why is this bad?
`M585` needs a current tool and a homed axis. At boot there is no current tool unless a `T` selected one, and
nothing is homed, so RRF answers `No tool selected!` or `X axis has not been homed` and measures nothing. Tool
offset probing belongs in a macro run after homing; the result is kept with `M500` and loaded with `M501`.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
M585 X10 F600 P1
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
M501    ; load the offsets measured by a probing macro and saved with M500
```

## References
- rrflint: [M585 tool probing](../firmware-behaviour.md#m585-tool-probing)
- Duet3D G-code dictionary: [M585: probe tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m585-probe-tool)
- RepRapFirmware 3.5.3: [GCodes6.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes6.cpp) (`ProbeTool()`, `FindAxisLetter()`)
)md",
};

/// Did a G28 (not inside an if/while) run earlier in the boot sequence?
bool homed_before(const NodeContext& cx) {
  const std::vector<NodeId>& g28s = tools::code_index(cx.machine, cx.graph, 'G', 28).certain;
  return tools::last_before(g28s, cx.segment().begin, cx.id) != kNoNode;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 585) || !cx.certain() || !cx.in_boot()) return;
  const MachineState& s = cx.state;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  if (s.current_tool_known && s.current_tool < 0) {
    out.report(kMeta, cx.at(c.span),
               fmt::format("{} probes a tool offset at boot, but no tool is selected and nothing is homed: RRF "
                           "answers 'No tool selected!' and measures nothing",
                           tools::quote(pf, c)));
    return;
  }
  if (homed_before(cx)) return;
  // The first visible axis letter is the one M585 probes.
  const int axis = m585_axis(pf, c, s);
  const std::string reply = axis < 0 ? "No axis specified" : tools::axis_name(s, axis) + " axis has not been homed";
  Report r = out.report(kMeta, cx.at(c.span),
                        fmt::format("{} probes a tool offset at boot, but nothing is homed yet: RRF answers '{}' and "
                                    "measures nothing",
                                    tools::quote(pf, c), reply));
  if (s.current_tool_set != kNoNode) r.note(cx.where(s.current_tool_set), "the tool is selected here");
}

}  // namespace

extern const Rule m585_at_boot{.meta = kMeta, .check_node = check, .on = "M585"};

}  // namespace rrflint
