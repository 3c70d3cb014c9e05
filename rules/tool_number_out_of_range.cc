// RRF324 tool-number-out-of-range: M563 with a tool number above 49 (RRF 3.1+).
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF324",
    .name = "tool-number-out-of-range",
    .severity = Severity::Error,
    .summary = "M563 uses a tool number above 49, which RRF 3.1 and later reject.",
    .docs = R"md(
## What it does
Reports an `M563` whose `P` (tool number) is 50 or more, on targets RRF 3.1 and later. RRF 2 accepted any
number up to 65535, so old configs sometimes number tools 100, 200 …

## Firmware versions
A **hazard** of RRF 3.1 and later. It is judged at the target only.

## Why is this bad?
From RRF 3.1 tool numbers are 0–49 (`MaxTools` = 50). A higher number gives `parameter 'P' too high`: the tool
is not created, and every later `G10`, `M568` or `T` for it fails or selects nothing.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P100 D0 S"Hotend"
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0 S"Hotend"
```

## References
- rrflint: [M563 tools](../firmware-behaviour.md#m563-tools)
- Duet3D G-code dictionary: [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`ManageTool()`), [Configuration.h](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Config/Configuration.h) (`MaxTools`)
)md",
};

void check(const FileContext& cx, Sink& out) {
  if (cx.target.version < kRrf3_1) return;
  const ParsedFile& pf = cx.parsed();
  for (const uint32_t ci : pf.with_code('M', 563)) {
    const Command& c = pf.commands[ci];
    if (!c.is('M', 563)) continue;
    auto P = get_int(pf, c, 'P');
    if (!P.known() || P.value < 50) continue;
    out.report(kMeta, cx.at(P.param->span),
               fmt::format("{} uses tool number {}, but RRF {} allows tools 0–49: it answers 'parameter 'P' too "
                           "high' and creates no tool",
                           tools::quote(pf, c), P.value, cx.target.version.str()));
  }
}

}  // namespace

extern const Rule tool_number_out_of_range{.meta = kMeta, .check_file = check};

}  // namespace rrflint
