// RRF309 g10-l20-at-boot: G10 L20 at boot sets a workplace origin relative to a position nobody knows yet.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF309",
    .name = "g10-l20-at-boot",
    .severity = Severity::Warning,
    .summary = "G10 L20 in config.g or a file it runs at boot, where the current position is unknown.",
    .docs = R"md(
## What it does
Reports `G10 L20` in the boot sequence: config.g and every file it runs (M98 macros, config-override.g,
tool-change macros). It stays silent when a `G92` or `G28` ran earlier in the boot sequence, and for a `G10 L20`
inside an `if`/`while` block.

## Why is this bad?
`G10 L20` sets the workplace origin so that the *current* position gets the given coordinates. At boot nothing
is homed: the position is whatever the firmware assumed at power-on, so the origin ends up somewhere arbitrary.
`G10 L2` sets the origin itself and is what a configuration file wants; `L20` belongs in a macro that runs
after homing (for example a probing macro).

## Example
```gcode
G10 L20 P1 X0 Y0
```

## Use instead
```gcode
G10 L2 P1 X0 Y0
```

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset)
- RepRapFirmware 3.5.3: [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes3.cpp) (`GetSetWorkplaceCoordinates()`, `compute` for L20)
)md",
};

/// Did a G92 or G28 run earlier in the boot sequence? Then the position may be known.
bool position_set_before(const NodeContext& cx) {
  const auto any = [](NodeId, const tools::NodeCommand&) { return true; };
  const NodeId begin = cx.segment().begin;
  return tools::each_code_node(cx, begin, cx.id, 'G', 92, any) != kNoNode ||
         tools::each_code_node(cx, begin, cx.id, 'G', 28, any) != kNoNode;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('G', 10) || !cx.certain() || !cx.in_boot()) return;
  auto L = get_int(cx.parsed(), cx.command(), 'L');
  if (!L.known() || L.value != 20) return;
  if (position_set_before(cx)) return;
  out.report(kMeta, cx.at(cx.command().span),
             fmt::format("{} sets a workplace origin relative to the current position, but at boot nothing is "
                         "homed and the position is unknown: use 'G10 L2' to set the origin itself",
                         tools::quote(cx.parsed(), cx.command())));
}

}  // namespace

extern const Rule g10_l20_at_boot{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
