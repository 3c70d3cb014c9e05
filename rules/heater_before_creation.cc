// RRF205 heater-before-creation: M307, M301, M570 or M143 names a heater before M950 creates it, and RRF rejects it.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF205",
    .name = "heater-before-creation",
    .severity = Severity::Error,
    .summary = "M307, M301, M570 or M143 names a heater before M950 creates it: RRF rejects the command.",
    .docs = R"md(
## What it does
On RRF 3 targets, reports `M307 H<n>`, `M301 H<n>`, `M570 H<n>` or `M143 H<n>` (`M301` and `M143` without `H`
mean heater 1) where heater n does not exist yet: the `M950 H<n>` that creates it comes later in the boot
sequence, or nowhere. The message says what the heater is left with, and a note points at the later `M950`.

It stays silent on RRF 2 targets, which have default heaters; where heaters may exist that the model cannot see
(an `M950 H{…}` or a macro whose path is an expression); and inside config-override.g, whose lines that fail at
the `M501` are [m501-too-early](m501-too-early.md)'s notes.

## Why is this bad?
RRF 3 has no default heaters. A heater command that names a heater not yet created fails with `Heater n not
found` (`Heater n does not exist` for M143); at boot that is one line in the console among many, and the setting
is simply not there:
- an `M307` rejected before `M950` leaves the heater with no model: it stays disabled and refuses to heat (`Heater
  n not switched on due to bad model`) unless a later `M307` sets one;
- an `M143` rejected before `M950` leaves no user over-temperature monitor: the heater has only the default
  monitor that a later `M563`/`M140`/`M141` installs, or none at all (its limit is then 2000 °C);
- an `M301` leaves the model's own PID values; an `M570` leaves the default heater fault detection.

## Example
```gcode
M307 H1 R2.43 K0.56 D5.5 E1.35 S1.00 B0 V24.0
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
```

## Use instead
```gcode
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M307 H1 R2.43 K0.56 D5.5 E1.35 S1.00 B0 V24.0
```

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors)
- Duet3D G-code dictionary: [M950](https://docs.duet3d.com/User_manual/Reference/Gcodes#m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin), [M307](https://docs.duet3d.com/User_manual/Reference/Gcodes#m307-set-or-report-heating-process-parameters), [M143](https://docs.duet3d.com/User_manual/Reference/Gcodes#m143-maximum-heater-temperature), [M570](https://docs.duet3d.com/User_manual/Reference/Gcodes#m570-configure-heater-fault-detection)
- RepRapFirmware 3.5: [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/Heat.cpp) (`SetOrReportHeaterModel()`, `SetPidParameters()`, `ConfigureHeaterMonitoring()`, `HandleM143()`)
)md",
};

/// Is heater h named later (after `from`) by a command of this code, which sets again what the rejected one meant to?
bool set_later(const NodeContext& cx, NodeId from, int number, int h) {
  return heat::naming_heater(cx, number).first_after(from, cx.segment().end, h) != kNoNode;
}

/// What the heater is left with once this command is rejected.
std::string consequence(const NodeContext& cx, int code, int h, NodeId create) {
  const NodeId after = create == kNoNode ? cx.id : create;
  switch (code) {
    case 307:
      return set_later(cx, after, 307, h) ? "this model is not used (a later M307 sets one)"
                                          : "the heater has no model, so it stays disabled ('bad model')";
    case 143: {
      if (set_later(cx, after, 143, h)) return "this monitor is not installed (a later M143 sets one)";
      const bool defaults = heat::later_installing_defaults(cx, after, h) != kNoNode;
      return defaults ? "the heater has only the default over-temperature monitor"
                      : "the heater has no over-temperature monitor at all (its limit is 2000 °C)";
    }
    case 301: return "the heater keeps the PID values derived from its model";
    default: return "the heater keeps the default fault detection";
  }
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 307) && !cx.is('M', 301) && !cx.is('M', 570) && !cx.is('M', 143)) return;
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || !s.heaters_known || s.unknown_baseline) return;
  if (heat::judged_elsewhere(cx)) return;
  const heat::DeviceRef r = heat::heater_named(cx.parsed(), c);
  if (!r.known || s.heaters.count(r.number)) return;
  bool unknown = false;
  const NodeId create = cx.in_boot() ? heat::later_creation(cx, 'H', r.number, unknown) : kNoNode;
  if (unknown) return;
  if (create != kNoNode && heat::runs_again(cx, create)) return;  // the same line runs again once the heater exists
  const Val<double> A = c.number == 307 ? get_float(cx.parsed(), c, 'A') : Val<double>{};
  const bool disable = A.known() && A.value < 0;  // `M307 H7 A-1 C-1 D-1`: RRF 2's way to free a heater's pin
  const std::string error = c.number == 143 ? "does not exist" : "not found";
  const std::string where = create == kNoNode ? fmt::format("no 'M950 H{}' creates it anywhere", r.number)
                                              : fmt::format("'M950 H{}' creates it only later", r.number);
  Report rep = out.report(kMeta, cx.at(c.span),
                          fmt::format("{} names heater {}, which does not exist yet ({}): RRF answers 'Heater {} {}', "
                                      "and {}",
                                      tools::quote(cx.parsed(), c), r.number, where, r.number, error,
                                      disable ? "the line does nothing: it is RRF 2's way to disable a default heater, "
                                                "and RRF 3 has none (delete it)"
                                              : consequence(cx, c.number, r.number, create)));
  if (create != kNoNode) rep.note(cx.where(create), fmt::format("heater {} is created here", r.number));
}

}  // namespace

extern const Rule heater_before_creation{.meta = kMeta, .check_node = check, .on = "M307 M301 M570 M143"};

}  // namespace rrflint
