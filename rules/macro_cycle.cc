// RRF502 macro-cycle: M98 calls that form a cycle no condition breaks.
#include <fmt/format.h>

#include "rules/macro_common.h"

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
- rrflint: [M98 and macros](../firmware-behaviour.md#m98-and-macros)
- Duet3D G-code dictionary: [M98: call macro/subprogram](https://docs.duet3d.com/User_manual/Reference/Gcodes#m98-call-macrosubprogram)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`Push()`), [Configuration.h](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Config/Configuration.h) (`MaxStackDepth`)
)md",
};

void check(const EndContext& cx, Sink& out) {
  std::set<std::set<std::string>> seen;  // the files of each cycle reported: one finding per cycle
  for (const GraphEvent& e : cx.graph.events) {
    if (e.kind != GraphEvent::Kind::Cycle) continue;
    if (cx.graph.nodes[e.node].maybe) continue;  // a condition may break it
    // The calls that make the cycle: up the chain from this call to the call that started the file called again.
    const std::vector<NodeId> chain = call_chain(cx.graph, e.node);
    const std::string again = to_lower(e.path);
    std::vector<NodeId> calls;
    std::set<std::string> files{again, to_lower(cx.machine.unit(cx.graph.nodes[e.node].unit).sd_path)};
    for (NodeId site : chain) {
      const Node& entered = cx.graph.nodes[site];
      calls.push_back(site);
      files.insert(to_lower(cx.machine.unit(entered.unit).sd_path));
      if (to_lower(cx.machine.unit(entered.unit).sd_path) == again) break;
    }
    if (!seen.insert(files).second) continue;
    Report r = out.report(kMeta, event_path_loc(cx, e),
                          fmt::format("'{}' is already running when this M98 calls it again: the calls repeat until "
                                      "RRF's nesting limit aborts every running file",
                                      e.path));
    for (auto it = calls.rbegin(); it != calls.rend(); ++it)
      r.note(cx.where(*it),
             fmt::format("{} runs the next file of the cycle here", cx.machine.unit(cx.graph.nodes[*it].unit).sd_path));
  }
}

}  // namespace

extern const Rule macro_cycle{.meta = kMeta, .check_end = check};

}  // namespace rrflint
