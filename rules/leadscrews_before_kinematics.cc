// RRF210 leadscrews-before-kinematics: M671 sets the Z leadscrew positions before an M669/M667/M665 that changes
// the kinematics type, which replaces the kinematics object and loses them.
#include <fmt/format.h>

#include <optional>
#include <string>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF210",
    .name = "leadscrews-before-kinematics",
    .severity = Severity::Warning,
    .summary = "M671 sets the Z leadscrews before a later M669/M667 changes the kinematics type, which loses them.",
    .docs = R"md(
## What it does
Reports `M671 X… Y…` when a later command of the boot sequence changes the kinematics *type*: `M669 K<k>` with
a k other than the current one, `M667 S<n>` (up to 3.4; 3.5 rejects M667) that selects another type, or `M665`
with `L` or `D`, which switches to linear delta. A note points at that command.

`M669` without `K`, or with the `K` already in force, only configures the existing kinematics and keeps the
leadscrews: it is not reported. It stays silent when the kinematics type is unknown (an `M669 K{…}`, or one
inside an `if`), when the change may not run (inside an `if`), when an `M671` follows the change (the leadscrews
are set again), inside config-override.g and resurrect.g, and on a lone macro.

## Why is this bad?
The leadscrew positions live in the kinematics object. When the type changes, `Move::SetKinematics()` deletes
that object and creates a new one with no leadscrews, so the `M671` (positions, `S` maximum correction, `P`
screw pitch, `F` correction factor) is gone without a word. With fewer than two leadscrews the kinematics does
not support auto calibration, so `G32` (`G30 S<n>` in bed.g) no longer levels the gantry by driving the Z motors
apart: RRF falls back to tilt compensation.

## Example
```gcode
M671 X-10:310 Y150:150 S5
M669 K1
```

## Use instead
```gcode
M669 K1
M671 X-10:310 Y150:150 S5
```

## Fix safety
There is no fix.

## References
- Duet3D G-code dictionary: [M671](https://docs.duet3d.com/User_manual/Reference/Gcodes#m671-define-positions-of-z-leadscrews-or-bed-levelling-screws), [M669](https://docs.duet3d.com/User_manual/Reference/Gcodes#m669-set-kinematics-type-and-kinematics-parameters)
- RepRapFirmware 3.5: [Move.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/Move.cpp) (`SetKinematics()`), [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes2.cpp) (M665, M667, M669), [ZLeadscrewKinematics.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/Kinematics/ZLeadscrewKinematics.cpp) (`Configure()`, `SupportsAutoCalibration()`)
)md",
};

std::string kinematics_name(int k) {
  switch (k) {
    case 0: return "Cartesian (K0)";
    case 1: return "CoreXY (K1)";
    case 2: return "CoreXZ (K2)";
    case 3: return "linear delta (K3)";
    case 4: return "SCARA (K4)";
    case 5: return "CoreXYU (K5)";
    case 11: return "Markforged (K11)";
    default: return fmt::format("K{}", k);
  }
}

bool is_kinematics_code(const CommandTable::Code& code) {
  return code.letter == 'M' && code.fraction < 0 && (code.number == 669 || code.number == 667 || code.number == 665);
}

/// Does an M671 that sets leadscrews run after node `from` in this segment?
bool m671_later(const NodeContext& cx, NodeId from) {
  return cx.graph.nodes.find_if(from + 1, cx.segment().end, [&](NodeId, const Node& n) {
    const tools::NodeCommand nc = tools::command_at(cx.machine, n);
    return nc.is('M', 671) && (nc.pf->find(*nc.c, 'X') || nc.pf->find(*nc.c, 'Y'));
  }) != kNoNode;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 671)) return;
  const Command& c = cx.command();
  const ParsedFile& pf = cx.parsed();
  const MachineState& s = cx.state;
  if (!s.kinematics_known || s.unknown_baseline || heat::judged_elsewhere(cx)) return;
  if (!pf.find(c, 'X') && !pf.find(c, 'Y')) return;  // reports only
  int current = s.kinematics, to = -1;
  bool silent = false;
  bool superseded = false;  // a later M671 sets the leadscrews again before any change: it is judged instead
  const NodeId change = cx.graph.nodes.find_if(cx.id + 1, cx.segment().end, [&](NodeId, const Node& n) {
    if (n.kind != NodeKind::Command) return false;
    const ParsedFile& npf = cx.machine.unit(n.unit).parsed;
    const CommandTable::Code code = npf.commands.code(n.index);
    if (code.is('M', 671) && !n.maybe) {
      const Command nc = npf.commands[n.index];
      if (npf.find(nc, 'X') || npf.find(nc, 'Y')) return superseded = true;
    }
    if (!is_kinematics_code(code)) return false;
    const std::optional<int> k = kinematics_set_by(npf, npf.commands[n.index], s.firmware);
    if (!k || *k == current) return false;
    if (*k < 0 || n.maybe) return silent = true;  // the type may change, or become anything
    to = *k;
    return true;
  });
  if (change == kNoNode || silent || superseded || m671_later(cx, change)) return;
  const tools::NodeCommand nc = tools::command_at(cx.machine, cx.graph, change);
  Report rep = out.report(
      kMeta, cx.at(c.span),
      fmt::format("{} sets the Z leadscrews, but the later {} changes the kinematics from {} to {}: RRF replaces the "
                  "kinematics object and the leadscrew positions are lost, so G32 no longer levels with the Z "
                  "motors; put the M671 after it",
                  tools::quote(pf, c), tools::quote(*nc.pf, *nc.c), kinematics_name(current), kinematics_name(to)));
  rep.note(cx.where(change), "the kinematics type changes here");
}

}  // namespace

extern const Rule leadscrews_before_kinematics{.meta = kMeta, .check_node = check, .on = "M671"};

}  // namespace rrflint
