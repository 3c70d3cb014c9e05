// RRF201 axis-before-creation: an axis letter used before the M584 that creates the axis.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/motion_helpers.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF201",
    .name = "axis-before-creation",
    .severity = Severity::Warning,
    .tag = RuleTag::Unnecessary,
    .summary = "An axis letter is used before the M584 that creates the axis, so its value is silently ignored.",
    .docs = R"md(
## What it does
Reports an axis letter other than X, Y and Z in `M92`, `M201`, `M203`, `M205`, `M206`, `M208`, `M350`, `M566`,
`M574`, `M906`, `M913`, `M915`, `M917` or `G31` at a point where no axis with that letter exists yet. A note points
at the later `M584` that creates the axis, if there is one. Hidden axes (`M584 P`) are accepted by these commands,
so they are not findings here. An `M208` or `G31` line of config-override.g that the M501 runs before a later
`M584` creates the axis is a note of [m501-too-early](m501-too-early.md)'s finding instead. When two or more
earlier commands lose effect because of one `M584`, they are notes of
[m584-after-dependents](m584-after-dependents.md)'s single finding at that `M584` instead. A line that runs
again after that `M584` (a macro called before and after it) sets the axis then, and is not reported.

`G31 C` gets its own message: up to RRF 3.2 `C` was the probe's temperature coefficient; from 3.3 it is the C axis
offset (the coefficient is `T`).

## Why is this bad?
These commands loop over the axes that exist. A letter of an axis that does not exist yet is skipped without any
message: the U steps/mm, the U current or the U endstop are simply never set, and the axis later runs with defaults.

## Example
```gcode
M92 X80 Y80 Z400 U80
M584 X0 Y1 Z2 U3
```

## Use instead
```gcode
M584 X0 Y1 Z2 U3
M92 X80 Y80 Z400 U80
```

## References
- rrflint: [Other ordering rules](../firmware-behaviour.md#other-ordering-rules), [Axes and M584](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M584: set drive mapping](https://docs.duet3d.com/User_manual/Reference/Gcodes#m584-set-drive-mapping) (order dependency), [Command Order](https://docs.duet3d.com/User_manual/Reference/Gcodes#command-order), [G31](https://docs.duet3d.com/User_manual/Reference/Gcodes#g31-set-or-report-current-probe-status) (`C` and axis offsets)
- RepRapFirmware 3.5.3: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (M92/M350/M906 loop over the existing axes), [ZProbe.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Endstops/ZProbe.cpp) (G31 axis offsets); [3.2.2 ZProbe.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.2.2/src/Endstops/ZProbe.cpp) (G31 `C` is the temperature coefficient)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command()) return;
  const Command& c = cx.command();
  if (!motion::is_axis_command(c)) return;
  const MachineState& s = cx.state;
  if (!s.axes_known || s.unknown_baseline) return;
  const ParsedFile& pf = cx.parsed();
  for (const Param& p : pf.params(c)) {
    const char L = p.letter;
    // Not X/Y/Z/E, the command's own letters, a pin (`C"nil"`) or a duplicate letter; and the axis is missing.
    if (!motion::is_axis_value(pf, c, p) || s.axis_index(L) >= 0) continue;
    const std::string axis = L >= 'a' ? fmt::format("'{}", L) : std::string(1, L);
    if (c.letter == 'G' && L == 'C') {
      const bool old = s.firmware < kRrf3_3;
      if (old) continue;  // the temperature coefficient: correct up to 3.2
      out.report(kMeta, cx.at(p.span),
                 fmt::format("'G31 C' is no longer the temperature coefficient (it is 'T' since RRF 3.3): on RRF {} "
                             "it is the C axis offset, and no C axis exists here, so it is ignored",
                             s.firmware.str()));
      continue;
    }
    const NodeId later = tools::later_m584_for(cx, L);
    const std::string code = clip(pf.text(c.word));
    if (later != kNoNode && (c.is('M', 208) || c.is('G', 31)) && !cx.graph.nodes[later].maybe &&
        tools::inside_m501(cx.graph, cx.id))
      continue;  // a line M500 wrote, run by an M501 before the M584: a note of m501-too-early's finding
    if (motion::summarised(cx, later)) continue;  // a note of m584-after-dependents' finding at that M584
    if (later != kNoNode && tools::runs_again(cx, later)) continue;  // the line runs again once the axis exists
    if (later != kNoNode) {
      out.report(kMeta, cx.at(p.span),
                 fmt::format("'{}' sets axis {} before 'M584' creates it: RRF ignores '{}' without a message", code,
                             axis, clip(pf.text(p.span))))
          .note(cx.where(later), fmt::format("axis {} is created here", axis));
    } else {
      out.report(kMeta, cx.at(p.span),
                 fmt::format("'{}' sets axis {}, but no M584 creates axis {}: RRF ignores '{}' without a message", code,
                             axis, axis, clip(pf.text(p.span))));
    }
  }
}

}  // namespace

extern const Rule axis_before_creation{
    .meta = kMeta, .check_node = check, .on = "G31 M92 M201 M203 M205 M206 M208 M350 M566 M574 M906 M913 M915 M917"};

}  // namespace rrflint
