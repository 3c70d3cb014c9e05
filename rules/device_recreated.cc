// RRF211 device-recreated: M950 re-creates a heater or fan after M307/M301/M143/M570 or M106 configured it, and
// the new device starts from the defaults.
#include <fmt/format.h>
#include <algorithm>
#include <optional>
#include <span>

#include <string>
#include <utility>
#include <vector>

#include "lint/base/strings.h"
#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF211",
    .name = "device-recreated",
    .severity = Severity::Warning,
    .summary = "M950 re-creates a heater or fan after it was configured: the new device starts from the defaults.",
    .docs = R"md(
## What it does
On RRF 3 targets, reports `M950 H<n> C"…"` for a heater that already exists and that `M307`, `M301`, `M143` or
`M570` configured since it was created, and `M950 F<n> C"…"` for a fan that `M106 P<n>` configured. The message
names what is lost, and a note points at each configuring command. A setting that is made again after the
re-creation (the same command code for the same device) does not count.

It stays silent on an `M950` that may not run (inside an `if`), on a device created inside an `if` or from an
expression, on `C"nil"` (which deletes the device on purpose), on `M950` without `C` (which only changes or
reports the existing device), inside config-override.g and resurrect.g, and on a lone macro. In a macro run
after boot it stays silent when the macro configures the device again after the `M950` (a deliberate swap).

## Why is this bad?
`M950` with `C` deletes the device and makes a new one (`Heat::ConfigureHeater()`,
`FansManager::ConfigureFanPort()`), with nothing carried over:
- a heater loses its model (`M307`, and the PID values of `M301`): it is disabled again and refuses to heat
  (`Heater n not switched on due to bad model`); its over-temperature monitors (`M143`), including the default
  monitor an earlier `M563`/`M140` installed, so nothing guards it; and its fault detection (`M570`) goes back
  to the defaults;
- a fan loses its name, thermostatic control (`H`, `T`), minimum and maximum speed, blip time and speed
  (`M106`).

## Example
```gcode
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M307 H1 R2.43 K0.56 D5.5 E1.35 S1.00 B0 V24.0
M950 H1 C"out1" T1
```

## Use instead
```gcode
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M307 H1 R2.43 K0.56 D5.5 E1.35 S1.00 B0 V24.0
M950 H1 Q250         ; no C: changes the PWM frequency of the existing heater
```

## Fix safety
There is no fix: delete the second `M950`, or move the configuring commands after it.

## References
- rrflint: [Heaters and their monitors](../firmware-behaviour.md#heaters-and-their-monitors)
- Duet3D G-code dictionary: [M950](https://docs.duet3d.com/User_manual/Reference/Gcodes#m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin)
- RepRapFirmware 3.5: [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/Heat.cpp) (`ConfigureHeater()`), [Heater.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Heating/Heater.cpp) (the constructor), [FansManager.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Fans/FansManager.cpp) (`ConfigureFanPort()`)
)md",
};

/// The commands of code M`code` that configure a heater (letter 'H') or fan ('F'), by its number, and those that
/// name it with an expression; built once per graph. Each re-creation used to walk every later command of the code.
const tools::DeviceIndex& configuring(const NodeContext& cx, char letter, int code) {
  return tools::device_index(cx.machine, cx.graph, fmt::format("device_recreated.M{}", code), 'M', code,
                             [letter](const ParsedFile& pf, const Command& c) -> std::optional<heat::DeviceRef> {
                               if (letter == 'F') {
                                 auto P = get_int(pf, c, 'P');
                                 if (P.unknown()) return heat::DeviceRef{};
                                 if (P.known()) return heat::DeviceRef{static_cast<int>(P.value), true};
                                 return std::nullopt;
                               }
                               if (pf.params(c).begin() == pf.params(c).end())
                                 return std::nullopt;  // no parameters: reports only
                               const heat::DeviceRef r = heat::heater_named(pf, c);
                               if (r.known) return r;
                               if (get_int(pf, c, 'H').unknown()) return heat::DeviceRef{};
                               return std::nullopt;
                             });
}

/// What a heater or fan loses with the setting this command made.
std::string lost(int code) {
  switch (code) {
    case 307: return "the model (M307: without one it refuses to heat, 'bad model')";
    case 301: return "the PID values (M301)";
    case 143: return "the over-temperature monitor (M143)";
    case 570: return "the fault detection settings (M570)";
    default: return "the M106 settings (name, thermostatic control, speeds, blip time)";
  }
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 950) || !cx.certain()) return;
  const Command& c = cx.command();
  const ParsedFile& pf = cx.parsed();
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || s.unknown_baseline || heat::judged_elsewhere(cx)) return;
  auto C = get_string(pf, c, 'C');
  if (!C.present() || (C.known() && to_lower(C.value) == "nil")) return;
  const char letter = pf.find(c, 'H') ? 'H' : pf.find(c, 'F') ? 'F' : 0;
  if (letter == 0) return;
  auto D = get_int(pf, c, letter);
  if (!D.known()) return;
  const int n = static_cast<int>(D.value);
  NodeId created = kNoNode;
  if (letter == 'H') {
    auto it = s.heaters.find(n);
    if (it == s.heaters.end() || it->second.maybe) return;
    created = it->second.created;
  } else {
    auto it = s.fans.find(n);
    if (it == s.fans.end() || it->second.maybe) return;
    created = it->second.created;
  }
  if (created == kNoNode) return;
  // The first configuring command of each code since the creation, unless one of that code follows this line.
  std::vector<std::pair<NodeId, int>> first;  // node, code: in the order they ran
  bool unknown = false, reconfigured = false;
  static constexpr int kFanCodes[] = {106}, kHeaterCodes[] = {307, 301, 143, 570};
  for (const int code : letter == 'F' ? std::span<const int>(kFanCodes) : std::span<const int>(kHeaterCodes)) {
    const tools::DeviceIndex& index = configuring(cx, letter, code);
    const std::vector<NodeId>& named = tools::ids_of(index.known, int64_t{n});
    NodeId at = kNoNode;
    for (const auto& [b, e] : heat::since(cx, created)) {
      unknown = unknown || tools::first_in(index.unknown, b, e) != kNoNode;
      if (at == kNoNode) at = tools::first_in(named, b, e);
    }
    if (at != kNoNode) first.emplace_back(at, code);
  }
  std::sort(first.begin(), first.end());
  std::vector<std::pair<int, NodeId>> lost_at;  // code, node (kNoNode: set again later)
  for (const auto& [id, code] : first) {
    const tools::DeviceIndex& index = configuring(cx, letter, code);
    const NodeId next = tools::first_later(cx, index.known, int64_t{n});
    const bool again = next != kNoNode;
    unknown = unknown || tools::first_later(cx, index.unknown) < next;  // an expression names a device before it
    lost_at.emplace_back(code, again ? kNoNode : id);
    reconfigured = reconfigured || again;
  }
  // A macro run after boot that sets the device up again after re-creating it does so on purpose (a swap, a whole
  // alternative config): what it leaves out is its choice.
  if (reconfigured && !cx.in_boot()) return;
  if (unknown) return;
  std::string what;
  for (const auto& [code, at] : lost_at)
    if (at != kNoNode) what += (what.empty() ? "" : ", ") + lost(code);
  if (what.empty()) return;
  const std::string device = letter == 'H' ? fmt::format("heater {}", n) : fmt::format("fan {}", n);
  Report rep = out.report(kMeta, cx.at(c.span),
                          fmt::format("{} re-creates {}, which was configured after it was created: RRF deletes it "
                                      "and makes a new one with the defaults, losing {}",
                                      tools::quote(pf, c), device, what));
  rep.note(cx.where(created), fmt::format("{} is first created here", device));
  for (const auto& [code, at] : lost_at)
    if (at != kNoNode) rep.note(cx.where(at), fmt::format("M{} configures it here", code));
}

}  // namespace

extern const Rule device_recreated{.meta = kMeta, .check_node = check, .on = "M950"};

}  // namespace rrflint
