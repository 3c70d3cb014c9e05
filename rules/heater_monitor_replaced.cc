// RRF214 heater-monitor-replaced: a second M143 for the same heater and monitor slot replaces the first with a
// different monitor (an omitted A, C or T goes back to its default).
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF214",
    .name = "heater-monitor-replaced",
    .severity = Severity::Warning,
    .summary = "A second M143 for the same heater and monitor slot replaces the first with a different monitor.",
    .docs = R"md(
## What it does
On targets from RRF 3.1, reports an `M143` that sets a monitor (it has `S`, `A`, `C` or `T`) of a heater and
slot that an earlier `M143` set (no `H` means heater 1, no `P` slot 0), when the monitor it leaves differs from
the earlier one: another limit, action, condition or sensor. A note points at the earlier `M143`.

The effect is worked out as RRF does: an omitted `S` keeps the slot's limit, while an omitted `A` (action) goes
back to 0 (raise a heater fault), an omitted `C` (condition) to 0 (temperature exceeded) and an omitted `T` to
the heater's own sensor. So `M143 H1 S280 A2` followed by `M143 H1 S285` also changes the action.

It stays silent when the second `M143` leaves the same monitor (`M143 H1 S280` twice, or `M143 H1 S280` then
`M143 H1 A0`); on values it cannot know (`{…}`, an omitted limit on both); when either `M143` is inside an
`if` or a loop, or in a tool-change macro; when an `M950`, `M563`, `M140` or `M141` for the heater comes between
(a new heater has new monitors); in a macro linted on its own and in config-override.g; and on RRF 2 and 3.0,
where `M143` configured heater protection items whose omitted parameters kept their values.

## Why is this bad?
Each heater has three monitor slots (`P0`…`P2`). `M143` writes the whole slot: the second line wins and the first
is gone, which is rarely meant when the two differ. Usually the second was meant for another slot (a second
monitor on another sensor, a low-temperature check), or it was added later and silently drops the action of the
first: `A2` (switch the heater off for a while) becomes a heater fault again.

## Example
```gcode
; rrflint-options: --firmware 3.5
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M308 S3 P"temp3" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M143 H1 S280 A2
M143 H1 T3 S60 A1
```

## Use instead
```gcode
; rrflint-options: --firmware 3.5
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M308 S3 P"temp3" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M143 H1 S280 A2
M143 H1 P1 T3 S60 A1
M143 H1 P1 T3 A1
```

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors)
- Duet3D G-code dictionary: [M143](https://docs.duet3d.com/User_manual/Reference/Gcodes#m143-maximum-heater-temperature)
- RepRapFirmware 3.5: [Heater.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/Heater.cpp) (`ConfigureMonitor()`), [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/Heat.cpp) (`HandleM143()`); 3.0 [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.0/src/Heating/Heat.cpp) (`SetHeaterProtection()`)
)md",
};

/// What one M143 writes into its slot. `limit` is nullopt when S is omitted (the slot keeps its limit), `sensor`
/// when T is omitted and the heater's own sensor is not known.
struct Monitor {
  enum class Kind { Report, Unknown, Set } kind = Kind::Report;
  int heater = -1, slot = 0;
  bool heater_known = false;
  std::optional<int> sensor;
  int action = 0, trigger = 0;
  std::optional<double> limit;
  bool sensor_given = false, action_given = false, trigger_given = false;
};

/// What an M143 does to its slot: reports it, sets it from values rrflint cannot know, or sets it to this.
Monitor monitor_of(const ParsedFile& pf, const Command& c, int own_sensor) {
  Monitor m;
  const heat::DeviceRef h = heat::heater_named(pf, c);
  m.heater = h.number;
  m.heater_known = h.known;
  const auto P = get_int(pf, c, 'P'), T = get_int(pf, c, 'T'), A = get_int(pf, c, 'A'), C = get_int(pf, c, 'C');
  const auto S = get_float(pf, c, 'S');
  if (T.absent() && A.absent() && C.absent() && S.absent()) return m;  // a report
  m.kind = Monitor::Kind::Unknown;
  if (!h.known || T.unknown() || A.unknown() || C.unknown() || S.unknown() || P.unknown()) return m;
  m.kind = Monitor::Kind::Set;
  m.slot = P.known() ? static_cast<int>(P.value) : 0;
  if (T.known()) m.sensor = static_cast<int>(T.value);
  else if (own_sensor >= 0) m.sensor = own_sensor;
  m.action = A.known() ? static_cast<int>(A.value) : 0;
  m.trigger = C.known() ? static_cast<int>(C.value) : 0;
  if (S.known()) m.limit = S.value;
  m.sensor_given = T.known();
  m.action_given = A.known();
  m.trigger_given = C.known();
  return m;
}

std::string action_name(int a) {
  switch (a) {
    case 0: return "0 (heater fault)";
    case 1: return "1 (switch off for good)";
    case 2: return "2 (switch off for a while)";
    case 3: return "3 (shut down)";
    default: return std::to_string(a);
  }
}

std::string trigger_name(int t) {
  return t == -1 ? "-1 (disabled)" : t == 0 ? "0 (too hot)" : t == 1 ? "1 (too cold)" : std::to_string(t);
}

/// How `now` differs from `old`, for the message: empty when it is the same monitor (or not known to differ).
std::vector<std::string> differences(const Monitor& old, const Monitor& now) {
  std::vector<std::string> out;
  if (now.limit && old.limit && *now.limit != *old.limit)
    out.push_back(fmt::format("limit {:g} → {:g} °C", *old.limit, *now.limit));
  if (old.sensor && now.sensor && *old.sensor != *now.sensor)
    out.push_back(
        fmt::format("sensor {} → {}{}", *old.sensor, *now.sensor, now.sensor_given ? "" : " as T is omitted"));
  if (old.action != now.action)
    out.push_back(fmt::format("action {} → {}{}", action_name(old.action), action_name(now.action),
                              now.action_given ? "" : " as A is omitted"));
  if (old.trigger != now.trigger)
    out.push_back(fmt::format("condition {} → {}{}", trigger_name(old.trigger), trigger_name(now.trigger),
                              now.trigger_given ? "" : " as C is omitted"));
  return out;
}

/// Is node `id` in a file that other rules judge (config-override.g, resurrect.g)?
bool judged_elsewhere(const NodeContext& cx, NodeId id) {
  return heat::judged_elsewhere(cx.machine, cx.graph, id) ||
         file_role(cx.machine.unit(cx.graph.nodes[id].unit).sd_path) == FileRole::Resurrect;
}

/// The last earlier M143 in this segment that set slot `m.slot` of heater `m.heater`, with what it set in `old`;
/// kNoNode when there is none, or when something between may have changed the heater's monitors (an M950,
/// M563, M140 or M141 for it, an M143 from unknown values, one that may not run).
NodeId earlier_m143(const NodeContext& cx, const Monitor& m, int own_sensor, NodeId created, Monitor& old) {
  // Only what ran since the heater was created counts, and of that the last command that set this monitor or may
  // have changed the heater's monitors decides: the walk goes back from here over those codes and stops at it.
  const NodeId from = tools::later_of(cx.segment().begin, created);
  NodeId found = kNoNode;
  tools::each_code_node_backward(cx, from, cx.id, 'M', {950, 563, 140, 141, 143},
                                 [&](NodeId id, const tools::NodeCommand& k) {
                                   if (k.is('M', 950)) {
                                     const auto H = get_int(*k.pf, *k.c, 'H');
                                     return !H.absent() && (!H.known() || H.value == m.heater);  // a new heater
                                   }
                                   if (!k.is('M', 143)) return heat::names_heater(k, m.heater);  // the defaults
                                   const Monitor o = monitor_of(*k.pf, *k.c, own_sensor);
                                   if (o.kind == Monitor::Kind::Report || (o.heater_known && o.heater != m.heater))
                                     return false;
                                   if (o.kind == Monitor::Kind::Unknown || o.slot != m.slot)
                                     return o.kind == Monitor::Kind::Unknown;
                                   if (tools::certain_at_boot(cx.graph, id) && !judged_elsewhere(cx, id)) {
                                     found = id;
                                     old = o;
                                   }
                                   return true;
                                 });
  return found;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 143)) return;
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_1 || s.unknown_baseline || !cx.certain() || heat::judged_elsewhere(cx)) return;
  if (tools::in_tool_macro(cx.graph, cx.id)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const heat::DeviceRef h = heat::heater_named(pf, c);
  if (!h.known || !s.heaters_known) return;
  const auto it = s.heaters.find(h.number);
  if (it == s.heaters.end() || it->second.maybe) return;
  const int own_sensor = it->second.sensor;
  const Monitor m = monitor_of(pf, c, own_sensor);
  if (m.kind != Monitor::Kind::Set) return;
  const Monitor* now = &m;
  Monitor old;
  const NodeId prev = earlier_m143(cx, *now, own_sensor, it->second.created, old);
  if (prev == kNoNode || prev < it->second.created) return;
  std::vector<std::string> diffs = differences(old, *now);
  if (diffs.empty()) return;
  std::string what = diffs[0];
  for (size_t i = 1; i < diffs.size(); ++i) what += "; " + diffs[i];
  const tools::NodeCommand k = tools::command_at(cx.machine, cx.graph, prev);
  out.report(kMeta, cx.at(c.span),
             fmt::format("{} replaces monitor {} of heater {} that {} set ({}): the earlier monitor is gone "
                         "(if both are meant, give each its own slot, P0 to P2)",
                         tools::quote(pf, c), now->slot, h.number, tools::quote(*k.pf, *k.c), what))
      .note(cx.where(prev), fmt::format("monitor {} of heater {} is set here first", now->slot, h.number));
}

}  // namespace

extern const Rule heater_monitor_replaced{.meta = kMeta, .check_node = check, .on = "M143"};

}  // namespace rrflint
