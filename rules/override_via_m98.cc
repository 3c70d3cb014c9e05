// RRF403 override-via-m98: `M98 P"config-override.g"` loads the saved settings without M501's flag.
#include <fmt/format.h>

#include <string>

#include "lint/boot/commands.h"
#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF403",
    .name = "override-via-m98",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary =
        "M98 P\"config-override.g\" instead of M501: the loaded values are not marked as saved, and M502 "
        "loads them too.",
    .docs = R"md(
## What it does
Reports an `M98` whose `P` names /sys/config-override.g (`"config-override.g"`, `"0:/sys/config-override.g"`,
`"/sys/CONFIG-OVERRIDE.g"`: a bare name is looked for in /sys, and the name is compared without case), in any file
of the card but config-override.g itself. An `M98` inside an `if` is reported too: the choice between M98 and
M501 is the same whichever branch runs. It stays silent for a path from an expression (`P{…}`) and for a file of
that name in another folder (`"/macros/config-override.g"`).

## Why is this bad?
Both commands run the file, and both answer `Macro file config-override.g not found` when it is missing; but only
M501 runs it as RRF's saved-settings file (`runningM501`):
- values loaded by M501 are marked as saved: tool offsets (`G10 P…`), axis limits (`M208`) and probe values
  (`G31`). Loaded by M98 they are not, so the next `M500` (without `P10`/`P31`) leaves them out of the file it
  writes, and they are lost at the following boot;
- `M500` warns `No M501 command was executed in config.g`;
- `M502` ("revert to factory settings") re-runs config.g ignoring its M501, but not an M98: the saved values are
  loaded again.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
M98 P"config-override.g"
; file: sys/config-override.g
G10 P0 X22.340 Y41.620 Z-12.240
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
M501
; file: sys/config-override.g
G10 P0 X22.340 Y41.620 Z-12.240
```

## Fix safety
The fix replaces the command with `M501`. It is unsafe: that changes what M500 and M502 do afterwards (the
changes this rule asks for), and M501 inside a macro that config-override.g runs is ignored. It is offered only
when the command has no parameter but `P`.

## References
- rrflint: [Saved settings: M500, M501, M502](../firmware-behaviour.md#saved-settings-m500-m501-m502)
- Duet3D G-code dictionary: [M501](https://docs.duet3d.com/User_manual/Reference/Gcodes#m501-read-stored-parameters), [M500](https://docs.duet3d.com/User_manual/Reference/Gcodes#m500-store-parameters)
- RepRapFirmware 3.5: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes2.cpp) (cases 98, 501), [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes.cpp) (`DoFileMacro()` sets `runningM501` for M501 only; `WriteConfigOverrideFile()`)
)md",
};

/// Does this M98 path name /sys/config-override.g? A bare name is in /sys (M98 looks there first).
bool names_override(std::string path) {
  path = to_lower(path);
  if (path.starts_with("0:")) path.erase(0, 2);
  return path == "config-override.g" || path == "/sys/config-override.g" || path == "sys/config-override.g";
}

/// Has the command a parameter other than P (the fix would drop it)?
bool has_other_params(const ParsedFile& pf, const Command& c) {
  for (const Param& p : pf.params(c))
    if (p.letter != 'P') return true;
  return false;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 98)) return;
  if (file_role(cx.unit().sd_path) == FileRole::ConfigOverride || tools::inside_m501(cx.graph, cx.id)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  auto P = get_string(pf, c, 'P');
  if (!P.known() || !names_override(P.value)) return;
  const std::string boot = cx.in_boot() ? ", M500 warns 'No M501 command was executed in config.g', and M502 loads "
                                          "the saved values again instead of ignoring them"
                                        : "";
  Report r = out.report(kMeta, cx.at(c.span),
                        fmt::format("{} loads config-override.g without M501: the tool offsets, axis limits and "
                                    "probe values it loads are not marked as saved, so the next M500 leaves them "
                                    "out{}; use M501",
                                    tools::quote(pf, c), boot));
  if (!has_other_params(pf, c)) r.fix(Fix::unsafe("replace with 'M501'", Edit::replace(cx.at(c.span), "M501")));
}

}  // namespace

extern const Rule override_via_m98{.meta = kMeta, .check_node = check, .on = "M98"};

}  // namespace rrflint
