// RRF503 macro-nesting-too-deep: macro calls nest deeper than the firmware allows.
#include <fmt/format.h>

#include "rules/macro_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF503",
    .name = "macro-nesting-too-deep",
    .severity = Severity::Error,
    .summary = "Macro calls nest deeper than the target firmware's limit.",
    .docs = R"md(
## What it does
Counts the nesting of files the boot sequence (and each macro) runs, config.g itself being level 1, and reports the
call that goes past the target's `MaxStackDepth`: 10 from RRF 3.4, 7 for 3.01–3.3, 5 before.

## Firmware versions
A **hazard** whose depth limit depends on the version (5, 7 from 3.01, 10 from 3.4). It is judged at the target
only.

## Why is this bad?
RRF answers `Push(): stack overflow on Trigger` and aborts the whole stack of running files: the rest of config.g does
not run.

## Example
```gcode
; rrflint-options: --firmware 3.0
M98 P"a.g"      ; config.g is level 1, a.g level 2 …
; file: sys/a.g
M98 P"b.g"
; file: sys/b.g
M98 P"c.g"
; file: sys/c.g
M98 P"d.g"
; file: sys/d.g
M98 P"e.g"      ; level 6: past the limit of 5 of RRF 3.0
; file: sys/e.g
M564 H0
```

## Use instead
Flatten the macro chain: call the leaf macros from one level.

## References
- rrflint: [M98 and macros](../firmware-behaviour.md#m98-and-macros), [Errors and aborts](../firmware-behaviour.md#errors-and-aborts)
- Duet3D G-code dictionary: [M98: call macro/subprogram](https://docs.duet3d.com/User_manual/Reference/Gcodes#m98-call-macrosubprogram)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`Push()`: stack overflow), [Configuration.h](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Config/Configuration.h) (`MaxStackDepth` and its history)
)md",
};

void check(const EndContext& cx, Sink& out) {
  std::set<std::string> called;
  bool called_known = false;
  for (const GraphEvent& e : cx.graph.events) {
    if (e.kind != GraphEvent::Kind::TooDeep) continue;
    // One finding per chain: a chain that starts at a macro some other file calls is the tail of a longer one.
    if (!called_known) called = called_files(cx), called_known = true;
    const FileUnit& root = chain_root(cx, e);
    if (called.count(to_lower(root.sd_path))) continue;
    Report r =
        out.report(kMeta, event_path_loc(cx, e),
                   fmt::format("calling '{}' here nests macros {} deep, past RRF {}'s limit of {}: 'Push(): stack "
                               "overflow' aborts every running file",
                               e.path, cx.graph.nodes[e.node].depth + 1, cx.target.version.str(), e.limit));
    const std::vector<NodeId> chain = call_chain(cx.graph, e.node);
    if (!chain.empty())
      r.note(cx.where(chain.back()), fmt::format("the chain of calls starts here, in {}", root.sd_path));
  }
}

}  // namespace

extern const Rule macro_nesting_too_deep{.meta = kMeta, .check_end = check};

}  // namespace rrflint
