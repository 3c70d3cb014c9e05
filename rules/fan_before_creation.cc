// RRF208 fan-before-creation: M106 P<n> configures fan n before M950 creates it, and RRF rejects it.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF208",
    .name = "fan-before-creation",
    .severity = Severity::Error,
    .summary = "M106 P<n> names fan n before M950 creates it: RRF rejects the command.",
    .docs = R"md(
## What it does
On RRF 3 targets, reports `M106 P<n>` where fan n does not exist yet: the `M950 F<n>` that creates it comes
later in the boot sequence, or nowhere. A note points at the later `M950`. `M106` without `P` sets the print
cooling fan of the current tool and names no fan: it is not checked.

It stays silent on RRF 2 targets, which have default fans, and where fans may exist that the model cannot see
(an `M950 F{…}`, a macro whose path is an expression, a lone macro).

## Why is this bad?
RRF 3 has no default fans. `M106 P<n>` for a fan not yet created fails with `Fan number n not found`, and
everything on the line is lost: the fan's name, its thermostatic control (`H`, `T`), its minimum and maximum speed,
its blip time and its initial speed. A hot-end fan configured that way never turns on by itself, and the heat
break can creep until the filament jams.

## Example
```gcode
M106 P1 S1 H1 T45
M950 F1 C"out8" Q500
```

## Use instead
```gcode
M950 F1 C"out8" Q500
M106 P1 S1 H1 T45
```

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors)
- Duet3D G-code dictionary: [M950](https://docs.duet3d.com/User_manual/Reference/Gcodes#m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin), [M106](https://docs.duet3d.com/User_manual/Reference/Gcodes#m106-set-fan-speed)
- RepRapFirmware 3.5: [FansManager.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Fans/FansManager.cpp) (`ConfigureFan()`), [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes2.cpp) (M106)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 106)) return;
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || !s.fans_known || s.unknown_baseline || heat::judged_elsewhere(cx)) return;
  auto P = get_int(cx.parsed(), c, 'P');
  if (!P.known() || P.value < 0) return;  // no P: the tool's print cooling fan
  const int n = static_cast<int>(P.value);
  if (s.fans.count(n)) return;
  bool unknown = false;
  const NodeId create = cx.in_boot() ? heat::later_creation(cx, 'F', n, unknown) : kNoNode;
  if (unknown) return;
  const std::string where = create == kNoNode ? fmt::format("no 'M950 F{}' creates it anywhere", n)
                                              : fmt::format("'M950 F{}' creates it only later", n);
  Report rep = out.report(kMeta, cx.at(c.span),
                          fmt::format("{} names fan {}, which does not exist yet ({}): RRF answers 'Fan number {} not "
                                      "found' and sets nothing on this line",
                                      tools::quote(cx.parsed(), c), n, where, n));
  if (create != kNoNode) rep.note(cx.where(create), fmt::format("fan {} is created here", n));
}

}  // namespace

extern const Rule fan_before_creation{.meta = kMeta, .check_node = check, .on = "M106"};

}  // namespace rrflint
