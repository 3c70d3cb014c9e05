// RRF206 heater-monitor-skipped: a tool or bed names a heater before M950 creates it, so the heater never gets
// its default over-temperature monitor.
#include <fmt/format.h>

#include <optional>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF206",
    .name = "heater-monitor-skipped",
    .severity = Severity::Warning,
    .summary =
        "A tool or bed names a heater before M950 creates it, so the heater gets no default over-temperature monitor.",
    .docs = R"md(
## What it does
On targets from RRF 3.2, reports `M563 … H<n>`, `M140 H<n>` or `M141 H<n>` naming heater n before the `M950 H<n>`
that creates it later in the boot sequence. It stays silent when, after that `M950`, the heater gets a user
over-temperature monitor (`M143 H<n> S…`) or is named again by `M563`/`M140`/`M141`, which installs the defaults.
RRF 2 configs have default heaters and are not checked.

## Why is this bad?
RRF installs the default over-temperature monitor (285 °C for a tool heater, 125 °C for a bed or chamber) and the
default heater model only when `M563`/`M140`/`M141` names a heater that **already exists**. A heater created later
has no monitor at all: its temperature limit is 2000 °C, nothing trips on a runaway, and without an `M307` it stays
disabled (`Heater n not switched on due to bad model`). RRF says nothing at boot.

## Example
```gcode
M563 P0 D0 H1
M308 S1 P"temp1" Y"thermistor"
M950 H1 C"out1" T1
```

## Use instead
```gcode
M308 S1 P"temp1" Y"thermistor"
M950 H1 C"out1" T1
M563 P0 D0 H1
```

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors), [M563 tools](../firmware-behaviour.md#m563-tools)
- Duet3D G-code dictionary: [M950: create heater, fan, …](https://docs.duet3d.com/User_manual/Reference/Gcodes#m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin), [M143: maximum heater temperature](https://docs.duet3d.com/User_manual/Reference/Gcodes#m143-maximum-heater-temperature), [M140](https://docs.duet3d.com/User_manual/Reference/Gcodes#m140-set-bed-temperature-fast-or-configure-bed-heater)
- RepRapFirmware 3.5.3: [Tool.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Tools/Tool.cpp) (`Tool::Create()`), [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Heating/Heat.cpp) (`SetAsToolHeater()`), [Heater.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Heating/Heater.cpp) (`SetAsToolHeater()`, `SetAsBedOrChamberHeater()`, `GetHighestTemperatureLimit()`)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command() || !cx.in_boot()) return;
  const Command& c = cx.command();
  if (c.letter != 'M' || c.fraction >= 0 || (c.number != 563 && c.number != 140 && c.number != 141)) return;
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_2 || !s.heaters_known || s.unknown_baseline) return;
  auto H = get_int_list(cx.parsed(), c, 'H');
  if (!H.known()) return;
  const Segment& seg = cx.segment();
  for (int64_t hv : H.value) {
    const int h = static_cast<int>(hv);
    if (h < 0 || s.heaters.count(h)) continue;
    // The later M950 that creates the heater.
    bool unknown = false;
    const NodeId create = heat::later_creation(cx, 'H', h, unknown);
    if (unknown) return;
    if (create == kNoNode) continue;
    // Closed when, after the M950, an M143 with S sets a monitor of the heater or an M563/M140/M141 names it again.
    const tools::DeviceIndex& monitors =
        tools::device_index(cx.machine, cx.graph, "heater_monitor_skipped.m143_s", 'M', 143,
                            [](const ParsedFile& pf, const Command& kc) -> std::optional<heat::DeviceRef> {
                              if (!pf.find(kc, 'S')) return std::nullopt;
                              auto v = get_int(pf, kc, 'H');
                              if (v.unknown()) return heat::DeviceRef{};
                              return heat::DeviceRef{v.known() ? static_cast<int>(v.value) : 1, true};
                            });
    const bool closed = monitors.first_after(create, seg.end, h) != kNoNode ||
                        heat::later_installing_defaults(cx, create, h) != kNoNode;
    const bool model =
        tools::first_after(tools::ids_of(heat::naming_heater(cx, 307).known, int64_t{h}), create, seg.end) != kNoNode;
    if (closed) continue;
    const bool bed = c.number != 563;
    out.report(kMeta, cx.at(c.span),
               fmt::format("'{}' names heater {} before 'M950 H{}' creates it: the heater gets no default {} °C "
                           "over-temperature monitor (its limit is 2000 °C){}",
                           cx.parsed().text(c.word), h, h, bed ? 125 : 285,
                           model ? "" : ", and with no M307 after its M950 it stays disabled"))
        .note(cx.where(create), fmt::format("heater {} is created here", h));
  }
}

}  // namespace

extern const Rule heater_monitor_skipped{.meta = kMeta, .check_node = check, .on = "M563 M140 M141"};

}  // namespace rrflint
