// RRF329 m568-legacy-mix-meaning: `M568 P<n> S1`, the old "mixing on", now sets 1 °C.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF329",
    .name = "m568-legacy-mix-meaning",
    .severity = Severity::Warning,
    .tag = RuleTag::Deprecated,
    .summary = "M568 P<n> S1 meant \"mixing on\" in RRF 1.x; from RRF 3.3 it sets an active temperature of 1 °C.",
    .docs = R"md(
## What it does
Reports `M568 … S1` with no `R`, `A` or `F`, on targets RRF 3.3 and later. That is the RRF 1.x form "turn
mixing on for tool n", still found in configs carried over from old machines. `S0` ("mixing off") is not
reported: an active temperature of 0 °C is harmless.

## Firmware versions
A **hazard** of RRF 3.3 and later, where `S1` is a temperature. It is judged at the target only.

## Why is this bad?
RRF 1.x used `M568 P<n> S1` to enable mixing. From 1.21 the command did nothing, and from RRF 3.3 `M568` sets
tool settings: `S1` now sets tool n's active temperature to 1 °C. It does not enable mixing (mixing follows the
`M567` ratios alone), and the hot end will be "at temperature" at 1 °C. Remove the line.

## Example
```gcode
M584 X0 Y1 Z2 E3:4
M563 P2 D0:1 H1
M567 P2 E0.5:0.5
M568 P2 S1
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3:4
M563 P2 D0:1 H1
M567 P2 E0.5:0.5
```

## References
- rrflint: [M568 tool settings](../firmware-behaviour.md#m568-tool-settings)
- Duet3D G-code dictionary: [M568: set tool settings](https://docs.duet3d.com/User_manual/Reference/Gcodes#m568-set-tool-settings), [M568: turn off/on tool mix ratios (deprecated)](https://docs.duet3d.com/User_manual/Reference/Gcodes#m568-turn-offon-tool-mix-ratios-deprecated)
- RepRapFirmware: [2.05.1 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/2.05.1/src/GCodes/GCodes2.cpp) (case 568, the old mixing switch)
)md",
};

void check(const FileContext& cx, Sink& out) {
  if (cx.target.version < kRrf3_3) return;
  const ParsedFile& pf = cx.parsed();
  for (const uint32_t ci : pf.with_code('M', 568)) {
    const Command& c = pf.commands[ci];
    if (!c.is('M', 568) || pf.find(c, 'R') || pf.find(c, 'A') || pf.find(c, 'F')) continue;
    auto S = get_float_list(pf, c, 'S');
    if (!S.known() || S.value.size() != 1 || S.value[0] != 1) continue;
    auto P = get_int(pf, c, 'P');
    const std::string tool = P.known() ? fmt::format("tool {}", P.value) : "the tool";
    out.report(kMeta, cx.at(c.span),
               fmt::format("{} is the RRF 1.x 'mixing on' form, but from RRF 3.3 M568 sets {}'s active temperature "
                           "to 1 °C; mixing follows the M567 ratios without it, so remove the line",
                           tools::quote(pf, c), tool));
  }
}

}  // namespace

extern const Rule m568_legacy_mix_meaning{.meta = kMeta, .check_file = check};

}  // namespace rrflint
