// RRF121 replaced-command: a command the target firmware answers with an error that names its replacement (M305 and
// the RRF 2 endstop and probe types on RRF 3, M667 from 3.5), so the line sets nothing up.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "lint/syntax/values.h"
#include "rules/append_fix.h"
#include "rules/tool_helpers.h"
#include "rules/version_gate.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF121",
    .name = "replaced-command",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary = "A command the target firmware rejects with an error naming its replacement, so it sets nothing up.",
    .docs = R"md(
## What it does
Reports the commands that RepRapFirmware still recognises only to reject them, with an error that names what
replaced them:

| command | rejected from | RRF answers | use instead |
|---|---|---|---|
| `M305` (thermistor and sensor settings) | 3.0 | `M305 has been replaced by M308 and M950` | `M308 S<n> P"<pin>" Y"thermistor" T… B…` for the sensor, `M950 H<n> C"<pin>" T<n>` for the heater |
| `M574 … S0` (active-low endstop switch) | 3.0 | `endstop type 0 is no longer supported. Use type 1 and invert the input pin instead.` | `M574 X1 S1 P"!xstop"`, or `S2` for the Z probe |
| `M558 P4`, `P6`, `P7` (an endstop input as the Z probe) | 3.0 | `Invalid Z probe type 4` | `M558 P5 C"<pin>"` (or `P8`, unfiltered) |
| `M667 S<n>` (CoreXY and CoreXZ) | 3.5 | `M667 is no longer supported - use M669 instead` | `M669 K1` (CoreXY), `M669 K2` (CoreXZ), `M669 K0` (Cartesian) |

`unknown-command` (RRF101) stays silent about these codes: the firmware does know them.

## Firmware versions
A **hazard** of the versions in the table. On a target before RRF 3 nothing is reported: a config written for
RRF 2 uses RRF 2's commands, and moving it to RRF 3 is a rewrite (Duet3D's migration guide), not a fix line by
line. `M667` on a target from 3.0 to 3.4 is reported as `info`, with a note, when the files do not rule out 3.5 or
later (a header comment is older than the firmware more often than not); see [Firmware
target](../firmware-behaviour.md#firmware-target).

## Why is this bad?
The command fails, RRF reports the error at boot, and the rest of config.g runs without what it was meant to set
up: a heater without its sensor settings (it faults, or reads the wrong temperature), an axis without its
endstop, no Z probe, or a CoreXY machine that moves as a Cartesian one (each motor drives one axis: the first move
goes diagonally).

## Example
```gcode
; rrflint-options: --firmware 3.5
M584 X0 Y1 Z2
M667 S1
M574 X1 S0
```

## Use instead
```gcode
; rrflint-options: --firmware 3.5
M584 X0 Y1 Z2
M669 K1
M574 X1 S1 P"!xstop"
```

## Fix safety
`M667 S0`, `S1` or `S2` alone on its line is replaced by `M669 K0`, `K1` or `K2`, the kinematics it selected up to
RRF 3.4. The fix is unsafe: on a target that rejects M667 it changes how the machine moves (as intended, but check
the first moves), and on an older firmware that the files do not rule out it does the same as the M667. The other
commands have no fix: the pin of a sensor, an endstop or a probe is not in the old command.

## References
- rrflint: [Command words](../firmware-behaviour.md#command-words)
- Duet3D: [Migrating from RRF 2 to RRF 3](https://docs.duet3d.com/User_manual/RepRapFirmware/Migration_RRF2_to_RRF3), [M669](https://docs.duet3d.com/User_manual/Reference/Gcodes#m669-set-kinematics-type-and-kinematics-parameters), [M574](https://docs.duet3d.com/User_manual/Reference/Gcodes#m574-set-endstop-configuration), [M558](https://docs.duet3d.com/User_manual/Reference/Gcodes#m558-set-z-probe-type)
- RepRapFirmware: [3.0 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.0/src/GCodes/GCodes2.cpp) (case 305), [3.0 EndstopsManager.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.0/src/Endstops/EndstopsManager.cpp) (`HandleM574()`, `HandleM558()`), [3.5.0 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.0/src/GCodes/GCodes2.cpp) (case 667), [3.4.6 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.4.6/src/GCodes/GCodes2.cpp) (case 667: S0 Cartesian, S1 CoreXY, S2 CoreXZ)
)md",
};

// M667 S<n> alone, n a literal 0-2: the M669 K<n> that does what it did up to 3.4.
std::optional<Fix> m667_fix(const FileContext& cx, const Command& c) {
  const ParsedFile& pf = cx.parsed();
  if (!tools::parses_whole(pf, c)) return std::nullopt;
  size_t n = 0;
  for (const Param& p : pf.params(c)) {
    (void)p;
    ++n;
  }
  const auto S = get_int(pf, c, 'S');
  if (n != 1 || !S.known() || S.value < 0 || S.value > 2) return std::nullopt;
  const std::string m669 = fmt::format("M669 K{}", S.value);
  return Fix::unsafe(fmt::format("replace with '{}'", m669), Edit::replace(cx.at(c.span), m669));
}

// The RRF 3 group: from 3.0, at the target only (see the docs).
void check_rrf3(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string on = "RRF " + cx.target.version.str();
  for (const uint32_t ci : pf.with_code('M', 305)) {
    const Command& c = pf.commands[ci];
    if (!c.is('M', 305)) continue;
    out.report(kMeta, cx.at(c.span),
               fmt::format("{} is RRF 2's sensor setting: {} answers 'M305 has been replaced by M308 and M950' and "
                           "sets nothing; define the sensor with 'M308 S<n> P\"<pin>\" Y\"thermistor\" T… B…' and the "
                           "heater with 'M950 H<n> C\"<pin>\" T<n>'",
                           tools::quote(pf, c), on));
  }
  // M<code> whose `letter` is a literal value that `rejected` picks, reported at that parameter.
  auto each = [&](int code, char letter, auto rejected, auto message) {
    for (const uint32_t ci : pf.with_code('M', code)) {
      const Command& c = pf.commands[ci];
      const auto v = get_int(pf, c, letter);
      if (c.is('M', code) && v.known() && rejected(v.value))
        out.report(kMeta, cx.at(v.param->span), message(tools::quote(pf, c), v.value));
    }
  };
  each(
      574, 'S', [](int64_t s) { return s == 0; },
      [&](const std::string& q, int64_t) {
        return fmt::format(
            "{} asks for endstop type 0, RRF 2's active-low switch: {} answers 'endstop type 0 is no longer "
            "supported. Use type 1 and invert the input pin instead.' and sets up no endstop on this line; "
            "write S1 and the pin with '!' (P\"!xstop\"), or S2 to home with the Z probe",
            q, on);
      });
  each(
      558, 'P', [](int64_t p) { return p == 4 || p == 6 || p == 7; },
      [&](const std::string& q, int64_t p) {
        return fmt::format(
            "{} asks for Z probe type {}, an endstop input as the probe in RRF 2: {} answers 'Invalid Z "
            "probe type {}' and creates no probe; a switch probe is type P5 (or P8) with its pin in C\"…\"",
            q, p, on, p);
      });
}

void check(const FileContext& cx, Sink& out) {
  // A config for RRF 2 speaks RRF 2's dialect: nothing here applies until it is rewritten for RRF 3.
  if (cx.target.version < kRrf3_0) return;
  check_rrf3(cx, out);
  constexpr auto from_3_5 = [](Version v) { return v >= kRrf3_5; };
  const std::optional<gate::Gate> g = gate::hazard(cx.target, from_3_5, kMeta.severity);
  if (!g) return;
  constexpr std::string_view kVersions = "3.5 and later";
  const ParsedFile& pf = cx.parsed();
  for (const uint32_t ci : pf.with_code('M', 667)) {
    const Command& c = pf.commands[ci];
    if (!c.is('M', 667)) continue;
    Report r = out.report(kMeta, g->severity, cx.at(c.span),
                          fmt::format("{} selects the kinematics the old way: {} {} 'M667 is no longer supported - "
                                      "use M669 instead', and the machine keeps the kinematics it had (Cartesian, "
                                      "unless an M669 set others); write 'M669 K1' for CoreXY, 'M669 K2' for CoreXZ",
                                      tools::quote(pf, c), gate::on(*g, cx.target, kVersions),
                                      g->at == HazardAt::Target ? "answers" : "answer"));
    gate::explain(r, *g, cx.target, cx.at(c.span), kVersions);
    if (auto f = m667_fix(cx, c)) r.fix(std::move(*f));
  }
}

}  // namespace

extern const Rule replaced_command{.meta = kMeta, .check_file = check};

}  // namespace rrflint
