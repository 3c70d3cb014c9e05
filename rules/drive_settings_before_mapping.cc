// RRF203 drive-settings-before-mapping: M350 or a motor current sent before an M584 adds drivers that never get it.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"
#include "rules/motion_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF203",
    .name = "drive-settings-before-mapping",
    .severity = Severity::Warning,
    .summary =
        "M350 or a motor current is set before an M584 adds drivers to the axis, and those drivers never get it.",
    .docs = R"md(
## What it does
Reports, for an axis or extruder that exists already, a setting that RRF sends to the drivers mapped at that
moment and that a later `M584` then gives more drivers:
- an `M350` with a microstepping other than RRF's default (x16 with interpolation, `I1`) when the later `M584`
  adds **local** drivers (main board, `n` or `0.n`) to the axis or extruder: the new drivers stay at x16;
- an `M906`, `M913` or `M917` when the later `M584` adds **CAN-connected** drivers (`1.0`, `20.1`): those never
  receive the current.

A note points at the `M584`. Driver sets are compared with `0.n` and `n` the same driver, so an `M584` that
restates the mapping is silent. It stays silent for current on local drivers (RRF applies each axis's current to
its drivers whenever it enables them, so it follows the new mapping), for microstepping on CAN drivers (`M584`
sends them the axis's microstepping itself), for values and drivers given as expressions, for commands inside
`if`/`while` and a conditional `M584`, and when the same setting is sent again after the `M584` (a later
`M350`/`M906`… for that axis, or a macro that runs before and after it). An axis that the `M584` creates is
[axis-before-creation](axis-before-creation.md)'s; E values before the first `M584 E` on RRF 3.3 and later are
[extruder-before-creation](extruder-before-creation.md)'s. When two or more earlier commands lose effect
because of one `M584`, they are notes of [m584-after-dependents](m584-after-dependents.md)'s single finding there.

## Why is this bad?
`M350` programs the microstepping into the drivers mapped when it runs; `M584` only records the new drivers, and
a local driver added later keeps the power-on x16 with interpolation. The axis then moves with two motors at
different microstepping: one of them travels a different distance per step. `M906`/`M913`/`M917` send the
current to a CAN expansion board only when they run, so a CAN driver mapped later never gets it and runs at its
board's default. RRF says nothing in either case.

## Example
```gcode
M350 X16 Y16 Z32 I1
M584 X0 Y1 Z2:3
```

```gcode
M906 X800 Y800 Z800
M584 X0:1.0 Y1 Z2
```

## Use instead
```gcode
M584 X0:1.0 Y1 Z2:3
M350 X16 Y16 Z32 I1
M906 X800 Y800 Z800
```

## References
- rrflint: [Axes and M584](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M584: set drive mapping](https://docs.duet3d.com/User_manual/Reference/Gcodes#m584-set-drive-mapping) ("after using M584 you must set the motor current using M906 and the microstepping using M350")
- RepRapFirmware 3.5: [Move.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/Move.cpp) (`SetMicrostepping()` programs the drivers mapped then; `EnableDrivers()` applies the current at enable; `SetAxisDriversConfig()`), [CanInterface.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/CAN/CanInterface.cpp) (remote drivers get only a state change at enable), [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes3.cpp) (`DoDriveMapping()` sends remote drivers their microstepping)
)md",
};

std::string driver_list(const std::vector<DriverId>& ds) {
  std::string out;
  for (DriverId d : ds) out += (out.empty() ? "" : ", ") + d.str();
  return out;
}

void report(const NodeContext& cx, Sink& out, const Param& p, char L, NodeId m, const std::vector<DriverId>& lost) {
  const ParsedFile& pf = cx.parsed();
  const Command c = cx.command();
  const std::string who = L == 'E' ? std::string("the extruders") : fmt::format("axis {}", tools::axis_name(L));
  const std::string drivers = fmt::format("{} {}", lost.size() == 1 ? "driver" : "drivers", driver_list(lost));
  const std::string what =
      c.number == 350
          ? fmt::format("{} stay{} at RRF's default x16 with interpolation", drivers, lost.size() == 1 ? "s" : "")
          : fmt::format("CAN-connected {} never receive{} this current", drivers, lost.size() == 1 ? "s" : "");
  out.report(kMeta, cx.at(p.span),
             fmt::format("'{}' sets {} before a later 'M584' adds {} to {}: RRF sends '{}' only to the drivers mapped "
                         "now, so {} (send it after the M584)",
                         pf.text(c.word), who, drivers, L == 'E' ? "them" : "it", clip(pf.text(p.span)), what))
      .note(cx.where(m), fmt::format("{} {} {} here", who, L == 'E' ? "get" : "gets", drivers));
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command() || !cx.certain()) return;
  const Command c = cx.command();
  if (c.letter != 'M' || c.fraction >= 0 || (c.number != 350 && !motion::is_current_code(c.number))) return;
  const MachineState& s = cx.state;
  if (s.unknown_baseline || !s.axes_known) return;
  const ParsedFile& pf = cx.parsed();
  const motion::DriveMap at = motion::drive_map(s);
  const tools::NodeCommand self = tools::command_at(cx.machine, cx.graph, cx.id);
  for (const Param& p : pf.params(c)) {
    const char L = p.letter;
    if (L == 0 || !pf.find(c, L).is(p)) continue;
    const motion::DriveMap::Entry* e = L == 'E' ? nullptr : at.axis(L);
    if (L != 'E' && (!e || e->maybe)) continue;  // not an axis (I, S…), a missing axis (RRF201), a maybe axis
    const NodeId m = motion::next_m584(cx, cx.id, L);
    if (m == kNoNode) continue;
    const std::vector<DriverId> lost =
        motion::lost_setting(cx, self, m, L, e ? e->drivers : std::vector<DriverId>{}, at);
    if (lost.empty() || motion::summarised(cx, m)) continue;
    report(cx, out, p, L, m, lost);
  }
}

}  // namespace

extern const Rule drive_settings_before_mapping{.meta = kMeta, .check_node = check, .on = "M350 M906 M913 M917"};

}  // namespace rrflint
