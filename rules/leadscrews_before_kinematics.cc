// RRF210 leadscrews-before-kinematics: M671 sets the Z leadscrew positions before an M669/M667/M665 that changes
// the kinematics type, which replaces the kinematics object and loses them.
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lint/boot/commands.h"
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
are set again), inside config-override.g and resurrect.g, and on a lone macro. An `M671` that RRF refuses (lists
of different lengths, or more than four positions: `leadscrew-coordinates` reports it) sets nothing: it is
neither reported here nor taken as setting the leadscrews again.

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

/// Does this M671 set the leadscrew positions? Not when it only reports (no X or Y), nor when RRF refuses it (lists
/// of different lengths or longer than four: leadscrew-coordinates reports those), which sets nothing.
bool sets_leadscrews(const ParsedFile& pf, const Command& c) {
  const M671Form form = m671_read(pf, c).form;
  return form == M671Form::Set || form == M671Form::Unknown;
}

/// The commands that set a kinematics type (M669 K, M667 S, M665 L/D) and the M671s that set leadscrews, in node
/// order; built once per graph and firmware. Each M671 used to walk every later node: a config of thousands of
/// M671s inside `if` blocks and no change of type asked them all for each.
struct KinematicsIndex {
  std::vector<NodeId> ids;                 // the commands that set a type
  std::vector<int> type;                   // the type each sets, -1 when unknown
  std::vector<bool> maybe;                 // inside an if/while
  std::vector<size_t> next_other;          // the next entry that sets another type (ids.size() when none)
  std::vector<NodeId> m671, m671_certain;  // the M671s with X or Y; those not inside an if/while
};

const KinematicsIndex& kinematics_index(const NodeContext& cx) {
  const Version fw = cx.state.firmware;
  return cx.graph.derived<KinematicsIndex>(fmt::format("leadscrews.kinematics.{}", fw.str()), [&] {
    KinematicsIndex out;
    std::vector<std::pair<NodeId, std::pair<int, bool>>> sets;
    for (const int code : {669, 667, 665})
      tools::each_code_command(cx.machine, cx.graph, 'M', code,
                               [&](NodeId id, const Node& n, const ParsedFile& pf, const Command& c) {
                                 if (const std::optional<int> k = kinematics_set_by(pf, c, fw))
                                   sets.push_back({id, {*k, n.maybe}});
                               });
    std::sort(sets.begin(), sets.end());
    for (const auto& [id, set] : sets) {
      out.ids.push_back(id);
      out.type.push_back(set.first);
      out.maybe.push_back(set.second);
    }
    out.next_other.assign(out.ids.size(), out.ids.size());
    for (size_t i = out.ids.size(); i-- > 1;)
      out.next_other[i - 1] = out.type[i] != out.type[i - 1] ? i : out.next_other[i];
    tools::each_code_command(cx.machine, cx.graph, 'M', 671,
                             [&](NodeId id, const Node& n, const ParsedFile& pf, const Command& c) {
                               if (!sets_leadscrews(pf, c)) return;
                               out.m671.push_back(id);
                               if (!n.maybe) out.m671_certain.push_back(id);
                             });
    return out;
  });
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 671)) return;
  const Command& c = cx.command();
  const ParsedFile& pf = cx.parsed();
  const MachineState& s = cx.state;
  if (!s.kinematics_known || s.unknown_baseline || heat::judged_elsewhere(cx)) return;
  if (!sets_leadscrews(pf, c)) return;  // reports only, or refused (leadscrew-coordinates)
  const int current = s.kinematics;
  const KinematicsIndex& kin = kinematics_index(cx);
  const NodeId end = cx.segment().end;
  // The first later command that changes the type (one that sets the current type changes nothing), unless a later
  // M671 (not in an if/while, not refused) sets the leadscrews again before it: that one is judged instead.
  size_t at = static_cast<size_t>(std::upper_bound(kin.ids.begin(), kin.ids.end(), cx.id) - kin.ids.begin());
  if (at < kin.ids.size() && kin.type[at] == current) at = kin.next_other[at];
  const NodeId change = at < kin.ids.size() && kin.ids[at] < end ? kin.ids[at] : kNoNode;
  if (change == kNoNode || tools::first_after(kin.m671_certain, cx.id, end) < change) return;
  const bool silent = kin.type[at] < 0 || kin.maybe[at];  // the type may change, or become anything
  const int to = kin.type[at];
  if (silent || tools::first_after(kin.m671, change, end) != kNoNode) return;
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
