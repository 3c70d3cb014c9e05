// RRF216 pin-reused: a pin given to a second device while another device holds it ("Pin 'x' is not free").
#include <fmt/format.h>

#include "lint/boot/commands.h"
#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF216",
    .name = "pin-reused",
    .severity = Severity::Error,
    .summary = "A pin is given to a device while another device holds it: RRF refuses it with 'Pin is not free'.",
    .docs = R"md(
## What it does
On RRF 3 targets, follows which device holds which pin through the boot sequence, and reports a command that
gives a pin to a device while another device still holds it: `M950 … C` (heaters, fans, GPIO ports, servos,
spindles, LED strips), `M308 … P` (sensors), `M558 … C` (Z probes), `M574 … P` (switch endstops),
`M591 … C` (filament monitors) and `M452 C` (the laser). A pin named twice in one command
(`C"out1+out1"`) is reported too. A note points at the command that gave the pin to the other device.

A device gives its pins back when it is re-created or deleted (`M950 H1 C"nil"`, `M308 S1 P"nil"`, an `M558`
with `P`, `M591 … P0`, `M574 X0` or an `M574` of another type), and when it is given new pins: re-creating
heater 1 on the pin it had is not reported. Pins are compared as RRF looks them up: without case, `_` and `-`,
without the `!`, `^` and `*` flags, and on their board (`out1` and `0.out1` are one pin, `1.out1` another).

It stays silent when the other device may not hold the pin (its command is inside an `if` or `while`, or an
earlier command was refused), when a pin or a device number is an expression (then on every later command: any
pin may have changed hands), after an `M98` whose path is an expression, in a macro linted on its own, in
config-override.g and on RRF 2 targets, which name pins by number.

Some boards give one pin two names (on a Duet 3 6HC, `out9` is also `laser` and `vfd`): rrflint compares the
names, so a pin taken under two different names is not reported.

## Why is this bad?
RRF 3 gives each pin to one device at a time. The second device's command fails with `Pin 'out1' is not free`
(`IoPort::Allocate()`), one error line in the boot messages, and that device is not set up: the fan, heater or
sensor does not exist, the probe or endstop has no input. Every later command for it fails in turn. Usually the
pin is a copy-paste left-over and another pin was meant.

## Example
```gcode
; rrflint-options: --firmware 3.4
M308 S1 P"e0temp" Y"thermistor" T100000 B4725
M950 H1 C"e0heat" T1
M950 F1 C"e0heat"
```

## Use instead
```gcode
; rrflint-options: --firmware 3.4
M308 S1 P"e0temp" Y"thermistor" T100000 B4725
M950 H1 C"e0heat" T1
M950 F1 C"fan1"
M950 H1 C"nil"       ; heater 1 gives e0heat back
M950 F2 C"e0heat"
```

## References
- rrflint: [Pins](../firmware-behaviour.md#pins)
- Duet3D G-code dictionary: [M950](https://docs.duet3d.com/User_manual/Reference/Gcodes#m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin)
- RepRapFirmware 3.5: [IoPorts.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Hardware/IoPorts.cpp) (`AssignPorts()`, `Allocate()`: "Pin '%s' is not free"), [Pins.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Config/Pins.cpp) (`LookupPinName()`)
)md",
};

/// The pin as RRF names it in its answer: without the flags and the board.
std::string_view bare(const PinName& p) { return std::string_view(p.key).substr(p.key.find('.') + 1); }

void check(const NodeContext& cx, Sink& out) {
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || s.unknown_baseline || !s.pins_known || heat::judged_elsewhere(cx)) return;
  const ParsedFile& pf = cx.parsed();
  const Command c = cx.command();
  for (const PinChange& ch : pin_changes(pf, c, s)) {
    if (!ch.device.known() || !ch.pins_known || !ch.param) continue;
    const auto clash = pin_clash(s, ch);
    if (!clash || (clash->holder && clash->holder->maybe)) continue;
    const PinName& p = ch.pins[clash->index];
    const std::string device = ch.device.name();
    const std::string answer =
        fmt::format("RRF answers \"Pin '{}' is not free\" and does not set up {}", bare(p), device);
    if (!clash->holder) {
      out.report(kMeta, cx.at(ch.param->span),
                 fmt::format("{} names pin \"{}\" twice: {}", tools::quote(pf, c), p.written, answer));
      continue;
    }
    const PinOwner& h = *clash->holder;
    out.report(kMeta, cx.at(ch.param->span),
               fmt::format("{} gives pin \"{}\" to {}, but {} holds it: {}", tools::quote(pf, c), p.written, device,
                           h.device.name(), answer))
        .note(cx.where(h.at), fmt::format("{} takes pin \"{}\" here", h.device.name(), h.written));
  }
}

}  // namespace

extern const Rule pin_reused{.meta = kMeta, .check_node = check, .on = "M950 M308 M558 M574 M591 M452"};

}  // namespace rrflint
