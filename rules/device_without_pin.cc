// RRF215 device-without-pin: an M950 H or F for a heater or fan that does not exist yet, with no C pin to create it.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF215",
    .name = "device-without-pin",
    .severity = Severity::Error,
    .tag = RuleTag::Unnecessary,
    .summary = "M950 H or F without a C pin for a heater or fan that does not exist yet: RRF creates nothing.",
    .docs = R"md(
## What it does
On RRF 3 targets, reports `M950 H<n>` or `M950 F<n>` without a `C` pin where heater or fan n does not exist yet
on this boot path: no earlier `M950 … C…` created it. Without `C`, M950 only changes or reports an existing
device (`M950 F1 Q250` sets the PWM frequency of fan 1), so it creates nothing. A note points at a later `M950`
that does create the device, if there is one.

It stays silent when the device exists, or may exist: an earlier `M950` for it inside an `if` branch, an
`M950 H{…}`/`F{…}` or a macro whose path is an expression on the way; on an unknown number (`H{…}`); when `C`
is given in any form (`C{…}` included); on RRF 2 targets, which have no M950; in a macro linted on its own,
and in config-override.g.

`M950 J` (GPIO input), `P` (GPIO output) and `S` (servo) without `C` are not reported: RRF then reports the
port's pin (none) and answers without an error.

## Why is this bad?
RRF 3 has no default heaters or fans: only `M950 … C"pin"` creates one. Without `C`, RRF looks the device up,
finds nothing and answers `Heater n does not exist` (or `Can't change sensor number of existing heater` when
the line has a `T`), or `Fan n not found` (`Fan n does not exist` before 3.5.0-rc.4). At boot that is one error line
among many, and the machine is left with no such heater or fan: every later `M307`, `M143`, `M301` or `M570`
for the heater (`Heater n not found`), and every `M106 P` for the fan, fails as well.

## Example
```gcode
; rrflint-options: --firmware 3.5
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 T1
M950 F1 Q250
```

## Use instead
```gcode
; rrflint-options: --firmware 3.5
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M950 F1 C"out8" Q500
M950 F1 Q250
M950 J1
```

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors)
- Duet3D G-code dictionary: [M950](https://docs.duet3d.com/User_manual/Reference/Gcodes#m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin)
- RepRapFirmware 3.5: [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/Heat.cpp) (`ConfigureHeater()`), [FansManager.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Fans/FansManager.cpp) (`ConfigureFanPort()`), [Platform.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Platform/Platform.cpp) (`ConfigurePort()`), [GpInPort.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GPIO/GpInPort.cpp) and [GpOutPort.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GPIO/GpOutPort.cpp) (`Configure()`: no error without `C`)
)md",
};

/// ConfigureFanPort() says "Fan n not found" from 3.5.0-rc.4, "Fan n does not exist" before.
constexpr Version kFanNotFound = Version::rc(3, 5, 0, 4);

/// RRF's answer to an M950 without C for a device that does not exist.
std::string answer(const NodeContext& cx, char letter, int n) {
  if (letter == 'F')
    return fmt::format("Fan {} {}", n, cx.state.firmware >= kFanNotFound ? "not found" : "does not exist");
  if (cx.parsed().find(cx.command(), 'T')) return "Can't change sensor number of existing heater";
  return fmt::format("Heater {} does not exist", n);
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 950)) return;
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || s.unknown_baseline || heat::judged_elsewhere(cx)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  if (pf.find(c, 'C')) return;
  const char letter = m950_device(pf, c, s.firmware, s.board);
  if (letter != 'H' && letter != 'F') return;
  const auto v = get_int(pf, c, letter);
  if (!v.known() || v.value < 0) return;
  const int n = static_cast<int>(v.value);
  const bool heater = letter == 'H';
  if (heater ? (!s.heaters_known || s.heaters.count(n)) : (!s.fans_known || s.fans.count(n))) return;
  bool unknown = false;
  NodeId create = cx.in_boot() ? heat::later_creation(cx, letter, n, unknown) : kNoNode;
  if (unknown) create = kNoNode;  // an M950 from an expression on the way: it may create n, or not
  const std::string what = fmt::format("{} {}", heater ? "heater" : "fan", n);
  const std::string then =
      create != kNoNode || unknown
          ? fmt::format("this line's settings are lost{}",
                        create != kNoNode ? fmt::format(" (the 'M950 {}{} C…' below creates it later)", letter, n) : "")
          : fmt::format("there is no {}, so every later {} fails too", what,
                        heater ? fmt::format("M307, M143, M301 or M570 with 'H{}'", n) : fmt::format("'M106 P{}'", n));
  Report rep =
      out.report(kMeta, cx.at(c.span),
                 fmt::format("{} has no 'C' pin, so it can only change an existing {}, and {} does not exist "
                             "yet: RRF answers '{}', and {}",
                             tools::quote(pf, c), heater ? "heater" : "fan", what, answer(cx, letter, n), then));
  if (create != kNoNode) rep.note(cx.where(create), fmt::format("{} is created here", what));
}

}  // namespace

extern const Rule device_without_pin{.meta = kMeta, .check_node = check, .on = "M950"};

}  // namespace rrflint
