// RRF505 path-outside-root: an M98 path that climbs above the SD card's root.
#include <fmt/format.h>

#include "rules/macro_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF505",
    .name = "path-outside-root",
    .severity = Severity::Warning,
    .summary = "An M98 path climbs above the SD card's root.",
    .docs = R"md(
## What it does
Reports an `M98 P"…"` whose path, resolved against `/sys` (or the `M505` folder), uses `..` to climb above the root of
the SD card. rrflint never reads outside the root it was given.

## Why is this bad?
There is nothing above the root of the card: RRF cannot find the file and carries on without running it.

## Example
```gcode
M98 P"../../macros/park.g"
```

## Use instead
```gcode
M98 P"0:/macros/park.g"
```

## References
- rrflint: [M98 and macros](../firmware-behaviour.md#m98-and-macros)
- Duet3D G-code dictionary: [Filenames and Paths](https://docs.duet3d.com/User_manual/Reference/Gcodes#filenames-and-paths)
- RepRapFirmware 3.5.3: [MassStorage.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Storage/MassStorage.cpp) (`CombineName()`)
)md",
};

void check(const EndContext& cx, Sink& out) {
  for (const GraphEvent& e : cx.graph.events) {
    if (e.kind != GraphEvent::Kind::OutsideRoot || !event_is_m98(cx, e)) continue;
    out.report(kMeta, event_path_loc(cx, e),
               fmt::format("'{}' climbs above the root of the SD card: there is no such file", clip(e.path, 120)));
  }
}

}  // namespace

extern const Rule path_outside_root{.meta = kMeta, .check_end = check};

}  // namespace rrflint
