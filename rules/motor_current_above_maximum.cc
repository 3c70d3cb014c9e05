// RRF221 motor-current-above-maximum: M906 sets a motor current above what the board's own stepper drivers accept;
// RRF lowers it to that maximum without a word.
#include <fmt/format.h>

#include <optional>
#include <string>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF221",
    .name = "motor-current-above-maximum",
    .severity = Severity::Warning,
    .summary = "M906 sets a motor current above the maximum of the board's own drivers: RRF lowers it without a word.",
    .docs = R"md(
## What it does
On a board rrflint knows (`--board`, or named in config.g's header as the configuration tool writes it), reports
an `M906` that gives an axis or extruder more current than the board's own stepper drivers accept, when that axis
or extruder is driven by one of them:

| board | drivers | maximum |
|---|---|---|
| Duet 2 WiFi/Ethernet | TMC2660, drivers 0–4 | 2400 mA before 3.1, 2500 mA from 3.1 |
| Duet 3 Mini 5+ | TMC2209, drivers 0–4 | 2000 mA |
| Duet 2 Maestro | TMC2224, drivers 0–4 | 1600 mA |

It stays silent on drivers of CAN expansion boards and on drivers 5 and up (a DueX, an expansion or breakout board:
rrflint cannot tell which), on the Duet 3 6HC and 6XD (6.3 A; the 6XD drives external drivers), on an unknown
board, on values from expressions and when the axis mapping is not known.

## Why is this bad?
`M906` stores the current as given, and the object model and `M906` without parameters report that value. But the
driver is set with `TmcDriverState::SetCurrent()`, which clamps it to the driver's maximum: `M906 U3000` on a Duet 3
Mini 5+ runs the motor at 2000 mA. A motor that needs the higher current skips steps, and the configuration says
otherwise. Usually the value was copied from a bigger board, or the motor needs an external driver.

## Example
```gcode
; rrflint-options: --firmware 3.5 --board duet3-mini
M584 X0.0 Y0.1 Z0.2 E0.3
M906 X1200 Y1200 Z3000 E800 I30
```

## Use instead
```gcode
; rrflint-options: --firmware 3.5 --board duet3-mini
M584 X0.0 Y0.1 Z0.2 E0.3
M906 X1200 Y1200 Z2000 E800 I30
```

## Fix safety
There is no fix: lowering the value changes nothing on the machine, and only the author knows whether the motor
needs another driver.

## References
- Duet3D G-code dictionary: [M906](https://docs.duet3d.com/User_manual/Reference/Gcodes#m906-set-motor-currents)
- RepRapFirmware 3.5: [TMC22xx.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/StepperDrivers/TMC22xx.cpp) and [TMC2660.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/StepperDrivers/TMC2660.cpp) (`SetCurrent()`, `MaximumMotorCurrent`), [Platform.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Platform/Platform.cpp) (`SetMotorCurrent()`)
)md",
};

struct BoardDrivers {
  const char* board;   // as the message names it
  const char* chip;    // the driver chip
  double max_ma = 0;   // 0: not checked
  uint16_t count = 5;  // drivers 0…count-1 of board 0 are the board's own
};

BoardDrivers own_drivers(Board b, Version fw) {
  switch (b) {
    case Board::Duet2: return {"Duet 2", "TMC2660", fw >= kRrf3_1 ? 2500.0 : 2400.0};
    case Board::Duet3_Mini: return {"Duet 3 Mini 5+", "TMC2209", 2000.0};
    case Board::Maestro: return {"Duet 2 Maestro", "TMC2224", 1600.0};
    default: return {"", "", 0};
  }
}

/// Is one of these drivers one of the board's own?
bool on_board(const std::vector<DriverId>& drivers, const BoardDrivers& b) {
  for (const DriverId d : drivers)
    if (d.board == 0 && d.driver < b.count) return true;
  return false;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 906)) return;
  const MachineState& s = cx.state;
  const BoardDrivers b = own_drivers(s.board, s.firmware);
  if (b.max_ma == 0 || s.unknown_baseline || !s.axes_known) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  std::vector<std::string> over;
  ParamRef at;
  auto judge = [&](const std::string& who, double ma, const std::vector<DriverId>& drivers, ParamRef p) {
    if (ma <= b.max_ma || !on_board(drivers, b)) return;
    over.push_back(fmt::format("{} {:g} mA", who, ma));
    if (!at) at = p;
  };
  for (size_t i = 0; i < s.axes.size(); ++i) {
    const Axis& a = s.axes[i];
    const auto v = get_float_list(pf, c, a.letter);  // RRF reads the first value of a list
    if (v.known() && !v.value.empty() && !a.maybe)
      judge(tools::axis_name(a.letter), v.value[0], a.drivers, pf.find(c, a.letter));
  }
  if (s.extruders_known) {
    const auto E = get_float_list(pf, c, 'E');
    if (E.known())
      for (size_t e = 0; e < E.value.size() && e < s.extruder_drivers.size(); ++e)
        judge(fmt::format("E{}", e), E.value[e], {s.extruder_drivers[e]}, pf.find(c, 'E'));
  }
  if (over.empty()) return;
  std::string what = over[0];
  for (size_t i = 1; i < over.size(); ++i) what += ", " + over[i];
  out.report(kMeta, cx.at(at->span),
             fmt::format("{} sets {}, above the {:g} mA the {}'s own {} drivers accept: RRF runs the motor at "
                         "{:g} mA without a word (and reports the value given)",
                         tools::quote(pf, c), what, b.max_ma, b.board, b.chip, b.max_ma));
}

}  // namespace

extern const Rule motor_current_above_maximum{.meta = kMeta, .check_node = check, .on = "M906"};

}  // namespace rrflint
