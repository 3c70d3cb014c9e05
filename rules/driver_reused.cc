// RRF212 driver-reused: one motor driver assigned to two axes or extruders by M584.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF212",
    .name = "driver-reused",
    .severity = Severity::Warning,
    .summary = "One motor driver is assigned to two axes or extruders.",
    .docs = R"md(
## What it does
Reports a driver that an `M584` assigns to a second axis or extruder while another axis or extruder still
uses it: twice in the same `M584` (`M584 X0 Y1 Z2 U0`), or an axis that an earlier `M584` mapped to the
driver and that this `M584` leaves alone. Driver numbers `0.n` and `n` are the same driver on the main board.
Drivers given by expressions, and `M584` commands inside `if`/`while` blocks, are not checked. When the second
axis is hidden by `M584 P` in the same command (a deliberate hidden axis, e.g. for a tool changer or a
homing trick), the finding is only info.

## Why is this bad?
RRF does not refuse the mapping: `M584` stores the drivers of each axis and extruder without checking that
they are distinct. Both axes then send step pulses to the same motor, and the driver's current, microstepping
and direction end up being whatever the last command for either axis set. Usually the driver number is a typo.

## Example
```gcode
M584 X0 Y1 Z2 U1
```

## Use instead
```gcode
M584 X0 Y1 Z2 U3
```

## References
- rrflint: [Axes and M584](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M584: Set drive mapping](https://docs.duet3d.com/User_manual/Reference/Gcodes#m584-set-drive-mapping)
- RepRapFirmware 3.5: [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes3.cpp) (`DoDriveMapping()`: the drivers are range-checked, not checked for reuse)
)md",
};

struct Use {
  char axis = 0;        // the axis letter, or 0 for an extruder
  size_t extruder = 0;  // the extruder's number
  DriverId driver;
  int axis_index = -1;  // -1 for extruders
  Location where;
  bool same_user(const Use& o) const { return axis == o.axis && (axis != 0 || extruder == o.extruder); }
  // "axis U", "extruder 0": written only for a finding (a config maps many drivers, and few are reused)
  std::string who() const { return axis ? fmt::format("axis {}", axis) : fmt::format("extruder {}", extruder); }
};

/// Axes and extruders this M584 maps, with the axis index each letter gets.
std::vector<Use> uses_here(const NodeContext& cx) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  std::vector<Use> out;
  int next_new = static_cast<int>(cx.state.axes.size());
  for (char L : allowed_axis_letters()) {
    ParamRef p = pf.find(c, L);
    if (!p) continue;
    int idx = cx.state.axis_index(L);
    if (idx < 0) idx = next_new++;
    auto d = get_driver_list(pf, c, L);
    if (!d.known()) continue;  // an expression: its drivers are not checked
    for (DriverId id : d.value) out.push_back({L, 0, id, idx, cx.at(p->span)});
  }
  if (ParamRef p = pf.find(c, 'E')) {
    auto d = get_driver_list(pf, c, 'E');
    if (d.known())
      for (size_t i = 0; i < d.value.size(); ++i) out.push_back({0, i, d.value[i], -1, cx.at(p->span)});
  }
  return out;
}

/// Axes mapped by earlier M584 commands that this one leaves alone.
std::vector<Use> earlier_uses(const NodeContext& cx) {
  std::vector<Use> out;
  if (!cx.state.axes_known || cx.state.unknown_baseline) return out;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  for (size_t i = 0; i < cx.state.axes.size(); ++i) {
    const Axis& a = cx.state.axes[i];
    if (a.maybe || a.drivers_set == kNoNode || pf.find(c, a.letter)) continue;
    for (DriverId id : a.drivers) out.push_back({a.letter, 0, id, static_cast<int>(i), cx.where(a.drivers_set)});
  }
  if (!pf.find(c, 'E') && cx.state.extruders_known && cx.state.extruders_set != kNoNode)
    for (size_t i = 0; i < cx.state.extruder_drivers.size(); ++i)
      out.push_back({0, i, cx.state.extruder_drivers[i], -1, cx.where(cx.state.extruders_set)});
  return out;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 584) || !cx.certain()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  std::vector<Use> here = uses_here(cx);
  std::vector<Use> before = earlier_uses(cx);
  auto P = get_int(pf, c, 'P');
  const int visible = P.known() ? static_cast<int>(P.value) : 1000;
  const bool p_given = static_cast<bool>(pf.find(c, 'P'));
  if (p_given && !P.known()) return;
  for (size_t i = 0; i < here.size(); ++i) {
    const Use& u = here[i];
    const Use* first = nullptr;
    for (size_t j = 0; j < i && !first; ++j)
      if (here[j].driver == u.driver && !here[j].same_user(u)) first = &here[j];
    for (size_t j = 0; j < before.size() && !first; ++j)
      if (before[j].driver == u.driver) first = &before[j];
    if (!first) continue;
    const bool hidden = p_given && ((u.axis_index >= visible) || (first->axis_index >= visible));
    out.report(kMeta, hidden ? Severity::Info : Severity::Warning, u.where,
               fmt::format("driver {} is assigned to {} but {} already uses it{}", u.driver.str(), u.who(),
                           first->who(), hidden ? " (the axis is hidden with 'P', so this may be on purpose)" : ""))
        .note(first->where, fmt::format("{} is mapped to driver {} here", first->who(), u.driver.str()));
  }
}

}  // namespace

extern const Rule driver_reused{.meta = kMeta, .check_node = check, .on = "M584"};

}  // namespace rrflint
