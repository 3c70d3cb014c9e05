// RRF325 tool-used-before-definition: M568/M567/M207 P<n> or T<n> before M563 creates tool n.
#include <fmt/format.h>

#include <unordered_set>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF325",
    .name = "tool-used-before-definition",
    .severity = Severity::Error,
    .summary = "M568/M567/M207 or T names a tool before M563 creates it, or a tool that is never created.",
    .docs = R"md(
## What it does
Reports `M568 P<n>` (RRF 3.3+), `M567 P<n>` and `M207 P<n>` where the machine model says tool n does not
exist: before the `M563 P<n>` that creates it, or for a tool no file creates. These are errors. `T<n>` for such
a tool is a warning. A note points at the later `M563`, if there is one.

In a standalone macro the rule reports only tools that no `M563` on the SD card creates. `T<n>` with n of 50 or
more that no `M563` names is the old idiom for deselecting every tool (like `T-1`) and is not reported, nor is
the firmware-written resurrect.g. It stays silent for
tool numbers given as expressions, inside `if`/`while` blocks, when tools may have been created in ways the
model cannot follow, and for a tool whose `M563` failed (for example `bad drive number`): that mistake is
reported where it happens, once. `G10 P<n>` is `g10-tool-before-definition` (RRF301).

## Why is this bad?
- `M568 P<n>` and (from RRF 3.4) `M567 P<n>` throw `Invalid tool number` (`M568` on 3.3: `Tool settings can only
  be set for existing tools`); `M207 P<n>` answers `Tool n does not exist`. Nothing is set.
- `T<n>` for a tool that does not exist silently selects no tool: later commands that need a current tool fail.

## Example
```gcode
M584 X0 Y1 Z2 E3
M568 P0 R0 S0
M563 P0 D0
T0 P0
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
M568 P0 R0 S0
T0 P0
```

## References
- rrflint: [Other ordering rules](../firmware-behaviour.md#other-ordering-rules), [T tool selection](../firmware-behaviour.md#t-tool-selection)
- Duet3D G-code dictionary: [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool), [T: select tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#t-select-tool)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`GetSpecifiedOrCurrentTool()`), [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (cases 207, 567, 568), [RawMove.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Movement/RawMove.cpp) (`SelectTool()`)
)md",
};

/// Does any file of the machine have an M563 that could create tool n (its P is n, an expression, or absent)? The
/// numbers are gathered once per graph: each finding scanned every M563 of the card.
bool created_anywhere(const NodeContext& cx, int n) {
  struct Created {
    std::unordered_set<int64_t> numbers;
    bool any = false;  // an M563 whose P is not a number: it may create any tool
  };
  const Created& created = cx.graph.derived<Created>("tool_used_before_definition.created", [&] {
    Created out;
    for (uint32_t i = 0; i < cx.machine.unit_count(); ++i) {
      const ParsedFile& pf = cx.machine.unit(i).parsed;
      for (const uint32_t ci : pf.with_code('M', 563)) {
        const Command& c = pf.commands[ci];
        if (!c.is('M', 563)) continue;
        auto P = get_int(pf, c, 'P');
        if (P.known()) out.numbers.insert(P.value);
        else out.any = true;
      }
    }
    return out;
  });
  return created.any || created.numbers.count(n) > 0;
}

std::string consequence(const Command& c, Version fw, int n) {
  if (c.letter == 'T') return "RRF silently selects no tool";
  if (c.is('M', 207)) return fmt::format("RRF answers 'Tool {} does not exist' and sets nothing", n);
  if (c.is('M', 568) && fw < kRrf3_4)
    return "RRF answers 'Tool settings can only be set for existing tools' and sets nothing";
  if (c.is('M', 567) && fw < kRrf3_4) return fmt::format("RRF {} silently ignores it", fw.str());
  return "RRF answers 'Invalid tool number' and sets nothing";
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command() || !cx.certain()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  int n = -1;
  if (c.letter == 'T' && c.fraction < 0) {
    if (c.number_expr || c.number < 0) return;
    n = c.number;
  } else if (c.is('M', 567) || c.is('M', 207) || (c.is('M', 568) && s.firmware >= kRrf3_3)) {
    auto P = get_int(pf, c, 'P');
    if (!P.known() || P.value < 0) return;
    n = static_cast<int>(P.value);
  } else {
    return;
  }
  if (!s.tool_certainly_absent(n) || s.failed_tools.count(n)) return;
  const NodeId later = cx.in_boot() ? tools::later_m563(cx, n) : kNoNode;
  if (!cx.in_boot() && created_anywhere(cx, n)) return;
  // `T99` for a tool that nothing creates, beyond the 0–49 range, is the old way to deselect every tool.
  if (c.letter == 'T' && n >= 50 && later == kNoNode && !created_anywhere(cx, n)) return;
  const std::string when = later != kNoNode ? fmt::format(" before 'M563 P{}' creates it", n)
                           : cx.in_boot()   ? ", which the boot sequence never creates"
                                            : ", which no M563 on the SD card creates";
  const Severity sev = c.letter == 'T' ? Severity::Warning : Severity::Error;
  Report r =
      out.report(kMeta, sev, cx.at(c.span),
                 fmt::format("{} names tool {}{}: {}", tools::quote(pf, c), n, when, consequence(c, s.firmware, n)));
  if (later != kNoNode) r.note(cx.where(later), fmt::format("tool {} is created here", n));
}

}  // namespace

extern const Rule tool_used_before_definition{.meta = kMeta, .check_node = check, .on = "T M207 M567 M568"};

}  // namespace rrflint
