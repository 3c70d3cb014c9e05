// RRF207 sensor-before-creation: M950 creates a heater whose sensor (T) no M308 has created yet.
#include <fmt/format.h>

#include "lint/base/strings.h"
#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF207",
    .name = "sensor-before-creation",
    .severity = Severity::Warning,
    .summary = "M950 H<n> … T<s> creates a heater before the M308 S<s> that creates its sensor.",
    .docs = R"md(
## What it does
On RRF 3 targets, reports `M950 H<n> C"…" T<s>` where sensor s does not exist yet: the `M308 S<s> Y"…"` that
creates it comes later in the boot sequence, or nowhere on the card. A note points at the later `M308`.

It stays silent where sensors may exist that the model cannot see (an `M308 S{…}`, a macro whose path is an
expression, a lone macro), when the sensor is created inside an `if` branch, for `M950 H<n> C"nil"` (which only
deletes the heater), inside config-override.g and resurrect.g, and when no boot-time `M308` creates the sensor but
a macro on the card does (it may run before the heater is used).

Thermostatic fans are not reported: `M106 P<f> H<s>` before `M308 S<s>` is accepted without a word, the fan looks
its sensors up by number whenever it updates, and a sensor that does not exist yet only runs the fan at full
speed until it does.

## Why is this bad?
RRF creates the heater all the same, with a warning: `Sensor number s has not been defined`. The heater keeps
the number and looks the sensor up whenever it reads its temperature, so once the later `M308` has run the heater
works: the cost is a warning at every boot that hides real ones, and a config that breaks as soon as the `M308`
is moved or deleted. When no `M308` creates the sensor at all, the heater can never read a temperature: it
faults (failed to read sensor) as soon as it is switched on.

## Example
```gcode
M950 H1 C"out1" T1
M308 S1 P"temp1" Y"thermistor" T100000 B4138
```

## Use instead
```gcode
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
```

## Fix safety
There is no fix: moving the `M308` up may move it past commands it depends on.

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors)
- Duet3D G-code dictionary: [M950](https://docs.duet3d.com/User_manual/Reference/Gcodes#m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin), [M308](https://docs.duet3d.com/User_manual/Reference/Gcodes#m308-set-or-report-sensor-parameters)
- RepRapFirmware 3.5: [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/Heat.cpp) (`ConfigureHeater()`, `GetSensorTemperature()`), [LocalHeater.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/LocalHeater.cpp) (`ConfigurePortAndSensor()`, `Spin()`), [LocalFan.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Fans/LocalFan.cpp) (`Check()`)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 950)) return;
  const Command& c = cx.command();
  const ParsedFile& pf = cx.parsed();
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || !s.sensors_known || s.unknown_baseline || heat::judged_elsewhere(cx)) return;
  auto H = get_int(pf, c, 'H');
  auto C = get_string(pf, c, 'C');
  auto T = get_int(pf, c, 'T');
  if (!H.known() || H.value < 0 || !C.present() || !T.known() || T.value < 0) return;
  if (C.known() && to_lower(C.value) == "nil") return;  // deletes the heater; T is not read
  const int sn = static_cast<int>(T.value);
  if (s.sensors.count(sn)) return;
  bool unknown = false;
  // The walk to the end of the boot is needed only when some M308 on the card creates sensor sn, or may: a
  // card-wide look at the M308 lists first keeps a file of many heaters linear.
  const bool may = heat::any_m308_creates(cx.machine, cx.graph, sn);
  const NodeId create = cx.in_boot() && may ? heat::later_sensor(cx, sn, unknown) : kNoNode;
  if (unknown || (create == kNoNode && may && heat::any_m308_creates(cx.machine, cx.graph, sn))) return;
  const std::string what =
      create == kNoNode
          ? fmt::format(
                "no 'M308 S{}' creates it anywhere, so the heater can never read a temperature and faults "
                "as soon as it is switched on",
                sn)
          : fmt::format(
                "'M308 S{}' creates it only later; the heater works once that has run, but every boot "
                "shows the warning",
                sn);
  Report rep = out.report(kMeta, cx.at(c.span),
                          fmt::format("{} gives heater {} sensor {}, which does not exist yet: RRF answers 'Sensor "
                                      "number {} has not been defined'; {}",
                                      tools::quote(pf, c), H.value, sn, sn, what));
  if (create != kNoNode) rep.note(cx.where(create), fmt::format("sensor {} is created here", sn));
}

}  // namespace

extern const Rule sensor_before_creation{.meta = kMeta, .check_node = check, .on = "M950"};

}  // namespace rrflint
