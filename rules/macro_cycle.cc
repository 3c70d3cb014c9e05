// RRF502 macro-cycle: M98 calls that form a cycle no condition breaks.
#include <fmt/format.h>

#include "macro_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF502",
    .name = "macro-cycle",
    .severity = Severity::Error,
    .summary = "M98 calls form a cycle that no condition breaks.",
    .docs = R"md(
## What it does
Reports an `M98` that calls a macro already running further up the call chain (a file calling itself, or `a.g`
→ `b.g` → `a.g`), when the call is not inside an `if`/`while` block that could end the recursion. rrflint follows
each call once and never loops.

## Why is this bad?
RRF has no cycle detection: the macros call each other until the nesting limit (`MaxStackDepth`, 10 from 3.4) is hit,
then `Push(): stack overflow` aborts the whole file stack, config.g included.

## Example
```gcode
; sys/config.g
M98 P"tools.g"
; sys/tools.g
M98 P"config.g"
```

## Use instead
Call each macro from one place only, or guard recursive calls with a condition that ends them.

## References
- rrf-semantics §2.9 (GCodes.cpp `Push()`, `MaxStackDepth`); R53
)md",
};

void check(const EndContext& cx, Sink& out) {
  for (const GraphEvent& e : cx.graph.events) {
    if (e.kind != GraphEvent::Kind::Cycle) continue;
    if (cx.graph.nodes[e.node].maybe) continue;  // a condition may break it
    out.report(kMeta, event_path_loc(cx, e),
               fmt::format("'{}' is already running when this M98 calls it again: the calls repeat until RRF's nesting "
                           "limit aborts every running file",
                           e.path));
  }
}

}  // namespace

extern const Rule macro_cycle{.meta = kMeta, .check_end = check};

}  // namespace rrflint
