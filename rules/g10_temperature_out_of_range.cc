// RRF313 g10-temperature-out-of-range: a tool temperature at or above its heater's over-temperature limit.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF313",
    .name = "g10-temperature-out-of-range",
    .severity = Severity::Error,
    .summary = "A G10/M568 temperature at or above the heater's over-temperature limit.",
    .docs = R"md(
## What it does
Compares the standby (`R`) and active (`S`) temperatures of a tool-form `G10`, or an `M568` (RRF 3.3+), with
the over-temperature limit the machine model has for each of the tool's heaters: the highest `M143` monitor,
or the default 285 °C tool (125 °C bed) monitor that `M563` (`M140`) installs on a heater that exists at that
point. A single value applies to every heater of the tool; a colon list gives one value per heater.

It stays silent for a heater with no monitor (created after its `M563`, for example): such a heater's limit is
2000 °C, so RRF accepts any value. Values of −273 or lower switch the heater off and are fine, and unknown
values (expressions, `param.*`) are never reported.

## Why is this bad?
RRF checks each temperature against the heater's highest monitor limit and throws `Requested temperature out of
range` when the value is at or above it (`>=`). The temperature is not set, and the rest of the command is
abandoned.

## Example
```gcode
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M563 P0 D0 H1
M568 P0 R150 S290
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M143 H1 S300
M563 P0 D0 H1
M568 P0 R150 S290
```

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors), [G10 forms](../firmware-behaviour.md#g10-forms)
- Duet3D G-code dictionary: [M143: maximum heater temperature](https://docs.duet3d.com/User_manual/Reference/Gcodes#m143-maximum-heater-temperature), [G10: tool temperature setting](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-tool-temperature-setting)
- RepRapFirmware 3.5.3: [Tool.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Tools/Tool.cpp) (`SetToolHeaterActiveOrStandbyTemperature()`), [Heater.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Heating/Heater.cpp) (`GetHighestTemperatureLimit()`, `SetAsToolHeater()`)
)md",
};

struct Violation {
  char letter;
  double value;
  int heater;
  const Heater* h;
};

std::optional<Violation> first_violation(const ParsedFile& pf, const Command& c, const MachineState& s, const Tool& t) {
  // RRF sets R (standby) first, then S (active); the first value out of range throws.
  for (char L : {'R', 'S'}) {
    auto v = get_float_list(pf, c, L);
    if (!v.known() || v.value.empty()) continue;
    for (size_t i = 0; i < t.heaters.size(); ++i) {
      const int h = static_cast<int>(t.heaters[i]);
      const double value = v.value.size() == 1 ? v.value[0] : (i < v.value.size() ? v.value[i] : -1000);
      if (value <= -273) continue;  // off
      auto it = s.heaters.find(h);
      if (h < 0 || it == s.heaters.end() || it->second.maybe || !it->second.monitor_installed) continue;
      if (it->second.limit >= 2000) continue;  // no limit, or one we cannot know
      if (value >= it->second.limit) return Violation{L, value, h, &it->second};
    }
  }
  return std::nullopt;
}

void check(const NodeContext& cx, Sink& out) {
  const Tool* t = tools::temperature_tool(cx);
  if (!t) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  const int n = t->number;
  if (!t || !s.heaters_known) return;
  auto v = first_violation(pf, c, s, *t);
  if (!v) return;
  Report r =
      out.report(kMeta, cx.at(c.span),
                 fmt::format("{} sets tool {}'s {} temperature to {}, at or above heater {}'s limit of {}: RRF answers "
                             "'Requested temperature out of range' and does not set it",
                             tools::quote(pf, c), n, v->letter == 'S' ? "active" : "standby", tools::degrees(v->value),
                             v->heater, tools::degrees(v->h->limit)));
  if (v->h->monitor_origin != kNoNode) {
    const Node& origin = cx.graph.nodes[v->h->monitor_origin];
    const std::optional<Command> oc = origin.kind == NodeKind::Command
                                          ? std::optional(cx.machine.unit(origin.unit).parsed.commands[origin.index])
                                          : std::nullopt;
    const bool user = oc && oc->is('M', 143);
    r.note(cx.where(v->h->monitor_origin),
           user ? fmt::format("'M143' sets heater {}'s over-temperature limit here", v->heater)
                : fmt::format("heater {} gets the default {} over-temperature monitor here", v->heater,
                              tools::degrees(v->h->limit)));
  }
}

}  // namespace

extern const Rule g10_temperature_out_of_range{.meta = kMeta, .check_node = check, .on = "G10 M568"};

}  // namespace rrflint
