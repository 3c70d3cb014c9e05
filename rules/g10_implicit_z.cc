// RRF331 g10-implicit-z: a tool-offset G10 that leaves Z out where Z is provably 0 (opt-in).
#include "rules/append_fix.h"
#include "rules/missing_z.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF331",
    .name = "g10-implicit-z",
    .severity = Severity::Info,
    .default_enabled = false,
    .fix = FixAvailability::Sometimes,
    .summary = "A tool-offset G10 leaves Z out; Z is 0 here, but say so explicitly.",
    .docs = R"md(
## What it does
Off by default (select it with `--select g10-implicit-z`). Reports a tool-offset G10 that sets X/Y (or other
axes) but not Z, where the tool's Z offset is provably 0: the places where `g10-missing-z` stays silent
because a fresh tool starts with every offset at 0 (right after its M563, IDEX copy and mirror tools).

It stays silent when a later G10 in the same boot sequence sets the tool's Z before a `T` selects it, for a
G10 inside an `if`/`while`, inside config-override.g, and in macros outside the boot sequence unless the tool
was created in that macro.

## Why is this bad?
It is not wrong today. It follows the Duet docs literally ("you want explicitly to set Z0.0"): a G10 that
names every axis documents the whole offset and keeps its meaning when lines are moved or an earlier G10 with
a Z is added later.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0 H1
G10 P0 X0 Y0
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0 H1
G10 P0 X0 Y0 Z0
```

## Fix safety
The fix appends ` Z0` right after the last parameter, before any comment. Z is 0 at that point, so the line
keeps its meaning: safe. There is no fix where the appended text would not be read as a parameter: after an
unterminated string or `{`, a ';' that cuts an expression open, or a CNC-mode `(` comment that no `)` closes.

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms), [M563 tools](../firmware-behaviour.md#m563-tools)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset)
- RepRapFirmware 3.5.3: [Tool.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Tools/Tool.cpp) (`Tool::Create()` starts every offset at 0), [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`SetOrReportOffsets()`)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  auto m = tools::missing_z(cx);
  if (!m || !m->z.known || m->z.value != 0 || m->probed) return;
  if (!cx.in_boot()) {
    const NodeId begin = cx.segment().begin;
    if (m->t->created == kNoNode || m->t->created < begin) return;
    if (m->z.origin != kNoNode && m->z.origin < begin) return;
  }
  Report r = out.report(kMeta, cx.at(cx.command().span),
                        fmt::format("{} leaves the Z offset of tool {} implicit (it is 0 here): write 'Z0'",
                                    tools::quote(cx.parsed(), cx.command()), m->tool));
  if (tools::appendable_z(cx, "0")) r.fix(tools::append_z(cx, "0"));
}

}  // namespace

extern const Rule g10_implicit_z{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
