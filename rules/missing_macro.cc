// RRF501 missing-macro: M98 names a file that is not on the SD card.
#include <fmt/format.h>

#include "rules/macro_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF501",
    .name = "missing-macro",
    .severity = Severity::Warning,
    .summary = "M98 names a macro file that does not exist on the SD card.",
    .docs = R"md(
## What it does
Resolves every `M98 P"…"` the way RRF does (relative paths under `/sys` or the `M505` folder, `0:/…` and `/…`
absolute, case-insensitive like the SD card) and reports a file that is not there.

## Why is this bad?
RRF prints the warning `Macro file x.g not found` and carries on: whatever the macro was meant to set up (tools,
offsets, fans) silently does not happen. A common cause is a macro under `/macros` called with a relative path,
which RRF looks for under `/sys`.

A top-level folder (such as `/macros`) of which the linted copy holds no file at all (printer-config repositories often keep only `sys/`) is not
judged: the file may well be on the card.

## Example
```gcode
M98 P"macros/levels.g"   ; looks for /sys/macros/levels.g
```

## Use instead
```gcode
M98 P"0:/macros/levels.g"
```

## References
- rrflint: [M98 and macros](../firmware-behaviour.md#m98-and-macros)
- Duet3D G-code dictionary: [M98: call macro/subprogram](https://docs.duet3d.com/User_manual/Reference/Gcodes#m98-call-macrosubprogram), [Filenames and Paths](https://docs.duet3d.com/User_manual/Reference/Gcodes#filenames-and-paths)
- RepRapFirmware 3.5.3: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (case 98), [MassStorage.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Storage/MassStorage.cpp) (`CombineName()`)
)md",
};

void check(const EndContext& cx, Sink& out) {
  for (const GraphEvent& e : cx.graph.events) {
    if (e.kind != GraphEvent::Kind::MissingFile || !event_is_m98(cx, e)) continue;
    // A folder with no file at all on the card (a repository that keeps only sys/) says nothing about the SD card.
    const size_t second = e.path.find('/', 1);
    const std::string top = second == std::string::npos ? std::string() : e.path.substr(0, second);
    if (!top.empty() && !cx.machine.has_dir(top)) continue;
    std::string hint;
    const std::string lower = to_lower(e.path);
    if (lower.starts_with("/sys/macros/")) hint = fmt::format(": did you mean '0:/macros/{}'?", e.path.substr(12));
    out.report(
        kMeta, event_path_loc(cx, e),
        fmt::format("macro file '{}' does not exist: RRF warns 'Macro file not found' and carries on{}", e.path, hint));
  }
}

}  // namespace

extern const Rule missing_macro{.meta = kMeta, .check_end = check};

}  // namespace rrflint
