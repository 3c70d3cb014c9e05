// RRF308 g10-workplace-out-of-range: G10 L2/L20 with a coordinate system outside 1–9, or an L RRF rejects.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF308",
    .name = "g10-workplace-out-of-range",
    .severity = Severity::Error,
    .summary = "G10 L2/L20 names a workplace outside 1–9, or G10 has an L other than 1, 2 or 20.",
    .docs = R"md(
## What it does
Checks the `L` and `P` parameters of `G10`:
- `L` must be 1 (tool offsets), 2 (set a workplace origin) or 20 (set it from the current position);
- with `L2`/`L20`, `P` names the coordinate system: 1–9 (G54 = 1 … G59.3 = 9). From RRF 3.4 `P0` (or no `P`)
  means the current system; before 3.4 `P0` is rejected.

## Firmware versions
A **hazard** whose limit depends on the version (RRF 3.4 and later reject P above the workplace count). It is
judged at the target only.

## Why is this bad?
Any other `L` gives `Bad or missing parameter`. From RRF 3.4 a `P` of 10 or more gives `parameter 'P' too
high`; RRF 3.3 and older answer `Bad or missing parameter` for `P0` or `P10`. Either way nothing is set: the
workplace origin the file means to define stays where it was.

## Example
```gcode
G10 L2 P10 X100 Y50
G10 L3 P1 X0
```

## Use instead
```gcode
G10 L2 P9 X100 Y50    ; G59.3
G10 L2 P1 X0          ; G54
```

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset)
- RepRapFirmware 3.5.3: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (case 10), [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes3.cpp) (`GetSetWorkplaceCoordinates()`)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const Version fw = cx.target.version;
  const bool limited = fw >= kRrf3_4;  // TryGetLimitedUIValue('P', …, 10)
  for (const uint32_t ci : pf.with_code('G', 10)) {
    const Command& c = pf.commands[ci];
    if (!c.is('G', 10)) continue;
    const G10Form form = g10_form(pf, c, nullptr, fw);
    if (form != G10Form::BadL && form != G10Form::Workplace) continue;
    auto L = get_int(pf, c, 'L');
    if (form == G10Form::BadL) {
      out.report(kMeta, cx.at(L.param->span),
                 fmt::format("{} uses 'L{}': G10 knows only L1 (tool offsets), L2 and L20 (workplace origins), so RRF "
                             "{} and sets nothing",
                             tools::quote(pf, c), L.value,
                             L.value < 0 ? "rejects the negative value" : "answers 'Bad or missing parameter'"));
      continue;
    }
    auto P = get_int(pf, c, 'P');
    if (!P.known()) continue;
    const bool bad = P.value < 0 || P.value > 9 || (!limited && P.value == 0);
    if (!bad) continue;
    const std::string reply = limited && P.value < 0   ? "rejects the negative value"
                              : limited && P.value > 9 ? "answers 'parameter 'P' too high'"
                                                       : "answers 'Bad or missing parameter'";
    out.report(
        kMeta, cx.at(P.param->span),
        fmt::format("{} names workplace {}, but RRF {} has coordinate systems 1–9 (G54 … G59.3){}: it {} and "
                    "sets nothing",
                    tools::quote(pf, c), P.value, fw.str(), limited ? " and P0 for the current one" : "", reply));
  }
}

}  // namespace

extern const Rule g10_workplace_out_of_range{.meta = kMeta, .check_file = check};

}  // namespace rrflint
