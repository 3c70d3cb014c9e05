// RRF328 m568-before-3.3: M568 used for temperatures on RRF 3.2 or older, where it does nothing.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"
#include "rules/version_gate.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF328",
    .name = "m568-before-3.3",
    .severity = Severity::Warning,
    .tag = RuleTag::Unnecessary,
    .summary = "M568 sets tool temperatures, but the target is RRF 3.2 or older, where M568 does nothing.",
    .docs = R"md(
## What it does
Reports an `M568` that sets temperatures (`R`, `S` other than 0 or 1, or `A`) on a target before RRF 3.3.
`M568 P<n> S0`/`S1` on such a target is the old "mixing off/on" form, which also does nothing but was not meant
to set a temperature; `m568-legacy-mix-meaning` (RRF329) covers it on newer targets.

## Firmware versions
A **hazard** of RRF before 3.3, where M568 does nothing. At such a target it is a warning. When no `--firmware` is
given and the files do not rule out such a version (the target is newer, but nothing in the files needs a version
that new), it is reported as `info` with a note that names the versions and the evidence; see [Firmware
target](../firmware-behaviour.md#firmware-target).

## Why is this bad?
Before RRF 3.3, `M568` was the obsolete "turn tool mixing on/off" command: RRF 1.21 to 3.2 reply `The M568
command is no longer needed` and do nothing. The temperatures are silently lost. `G10 P<n> R… S…` sets them on
those versions; or update the firmware, since the file was probably written for 3.3 or later.

## Example
```gcode
; rrflint-options: --firmware 3.2
M584 X0 Y1 Z2 E3
M563 P0 D0 H1
M568 P0 R150 S210
```

## Use instead
```gcode
; rrflint-options: --firmware 3.2
M584 X0 Y1 Z2 E3
M563 P0 D0 H1
G10 P0 R150 S210
```

## References
- rrflint: [M568 tool settings](../firmware-behaviour.md#m568-tool-settings)
- Duet3D G-code dictionary: [M568: set tool settings](https://docs.duet3d.com/User_manual/Reference/Gcodes#m568-set-tool-settings)
- RepRapFirmware: [3.2.2 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.2.2/src/GCodes/GCodes2.cpp) (case 568: "The M568 command is no longer needed"), [3.3 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.3/src/GCodes/GCodes2.cpp) (case 568 sets temperatures)
)md",
};

/// Does this M568 set temperatures (rather than the legacy mixing flag)?
bool sets_temperatures(const ParsedFile& pf, const Command& c) {
  if (pf.find(c, 'R') || pf.find(c, 'A')) return true;
  auto S = get_float_list(pf, c, 'S');
  if (S.absent()) return false;
  if (!S.known()) return true;
  for (double v : S.value)
    if (v != 0 && v != 1) return true;
  return false;
}

void check(const FileContext& cx, Sink& out) {
  constexpr auto before_3_3 = [](Version v) { return v < kRrf3_3; };
  const std::optional<gate::Gate> g = gate::hazard(cx.target, before_3_3, kMeta.severity);
  if (!g) return;
  constexpr std::string_view kVersions = "3.2 and earlier";
  const ParsedFile& pf = cx.parsed();
  for (const uint32_t ci : pf.with_code('M', 568)) {
    const Command& c = pf.commands[ci];
    if (!c.is('M', 568) || !sets_temperatures(pf, c)) continue;
    Report r = out.report(kMeta, g->severity, cx.at(c.span),
                          fmt::format("{} sets tool heater settings, but before RRF 3.3 M568 does nothing: {} {} "
                                      "'The M568 command is no longer needed'; use 'G10 P<n> R… S…' there",
                                      tools::quote(pf, c), gate::on(*g, cx.target, kVersions),
                                      g->at == HazardAt::Target ? "replies" : "reply"));
    gate::explain(r, *g, cx.target, cx.at(c.span), kVersions);
  }
}

}  // namespace

extern const Rule m568_before_3_3{.meta = kMeta, .check_file = check};

}  // namespace rrflint
