// RRF218 leadscrews-not-motors: M671 names a number of leadscrews other than the Z motors of M584.
#include <fmt/format.h>

#include "lint/boot/commands.h"
#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF218",
    .name = "leadscrews-not-motors",
    .severity = Severity::Warning,
    .summary =
        "M671 gives a number of leadscrews other than the Z motors M584 maps: G32 only prints manual "
        "corrections.",
    .docs = R"md(
## What it does
At the end of the boot sequence, reports the `M671` that set the Z leadscrews when Z has two or more motors
(`M584 Z0.2:0.3:0.4`) and the number of leadscrew positions is not the number of motors. A note points at the
`M584` that mapped the motors.

It stays silent when Z has one motor: `M671` then describes bed levelling screws turned by hand, and the manual
corrections are the point. It stays silent too when the motors or the positions are not known (expressions, an
`if`), when a kinematics change dropped the leadscrews (see [leadscrews-before-kinematics](leadscrews-before-kinematics.md)),
for kinematics without leadscrews, and for a lone macro.

## Why is this bad?
`ZLeadscrewKinematics::DoAutoCalibration()` moves the Z motors apart only when the number of Z drivers equals the
number of leadscrews. Otherwise `G32` probes, computes the corrections and prints `Manual corrections required:`
with a number of turns for each screw, and moves nothing. On a machine with independent Z motors that usually means
a motor was added or removed in `M584` and `M671` was not updated, and the gantry stays out of level with no error.

## Example
```gcode
M584 X0 Y1 Z2:3:4 E5
M671 X-10:310 Y150:150 S5
```

## Use instead
```gcode
M584 X0 Y1 Z2:3:4 E5
M671 X-10:150:310 Y-10:300:-10 S5
```

## Fix safety
There is no fix: the positions of the leadscrews are measured on the machine.

## References
- rrflint: [The rest of the machine](../firmware-behaviour.md#the-rest-of-the-machine)
- Duet3D G-code dictionary: [M671](https://docs.duet3d.com/User_manual/Reference/Gcodes#m671-define-positions-of-z-leadscrews-or-bed-levelling-screws)
- RepRapFirmware 3.5: [ZLeadscrewKinematics.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/Kinematics/ZLeadscrewKinematics.cpp) (`DoAutoCalibration()`)
)md",
};

void check(const EndContext& cx, Sink& out) {
  const MachineState& s = cx.end_of_boot;
  if (s.unknown_baseline || !s.axes_known || !s.kinematics_known || !has_leadscrews(s.kinematics)) return;
  const Leadscrews& l = s.leadscrews;
  if (l.set == kNoNode || !l.known || l.dropped != kNoNode) return;
  const int z = s.axis_index('Z');
  if (z < 0) return;
  const Axis& axis = s.axes[static_cast<size_t>(z)];
  const size_t motors = axis.drivers.size(), screws = l.x.size();
  if (axis.maybe || motors < 2 || screws < 2 || screws == motors) return;
  const tools::NodeCommand nc = tools::command_at(cx.machine, cx.graph, l.set);
  Report rep = out.report(
      kMeta, cx.where(l.set),
      fmt::format("{} gives {} leadscrews, but Z has {} motors: RRF moves the Z motors to level only when the two "
                  "numbers agree, so G32 just prints 'Manual corrections required' and levels nothing",
                  tools::quote(*nc.pf, *nc.c), screws, motors));
  if (axis.drivers_set != kNoNode) rep.note(cx.where(axis.drivers_set), fmt::format("Z gets {} motors here", motors));
}

}  // namespace

extern const Rule leadscrews_not_motors{.meta = kMeta, .check_end = check};

}  // namespace rrflint
