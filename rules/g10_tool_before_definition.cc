// RRF301 g10-tool-before-definition: a tool-form G10 for a tool that does not exist (yet).
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF301",
    .name = "g10-tool-before-definition",
    .severity = Severity::Error,
    .fix = FixAvailability::Sometimes,
    .summary = "A tool-form G10 names a tool before M563 creates it, or a tool that is never created.",
    .docs = R"md(
## What it does
Follows the boot sequence (config.g, the macros it runs, config-override.g at the M501) and reports a tool-form
`G10 P<n>` (offsets and/or `R`/`S` temperatures) where tool n does not exist: its `M563 P<n>` comes later, or
never. A note points at the later M563. A G10 in a macro is judged by the machine state at the end of the boot
sequence.

It stays silent when the tool may exist: tools created with an expression for the number (`M563 P{param.T}` in
a macro called as `M98 P"mktool.g" T0`) or inside an `if`, a G10 inside an `if`/`while`, and a G10 in the tool's
own tool-change macros (`tpost<n>.g` only runs for a tool that exists). A line of config-override.g that the
M501 runs before a later M563 creates the tool is a note of [m501-too-early](m501-too-early.md)'s finding instead. In a macro that runs after boot it also
stays silent when any M563 on the card could create the tool, since a macro may do that at run time. When the
tool's M563 itself failed
(`bad drive number`), this rule stays silent and `extruder-before-creation` reports the cause.

## Why is this bad?
RRF looks the tool up first and throws `Invalid tool number` (3.4 and later; `Tool n not found` on 3.3,
`Attempt to set/report offsets and temperatures for non-existent tool: n` before). Nothing of the line is set:
the offsets and temperatures are lost, and an M563 later creates the tool with all offsets at 0.

## Example
```gcode
M584 X0 Y1 Z2 E3
G10 P0 X0 Y0 Z-0.2
M563 P0 D0 H1
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0 H1
G10 P0 X0 Y0 Z-0.2
```

## Fix safety
When the M563 that creates the tool comes later in the same file, the fix moves the G10 line to just after it.
Several such lines for one tool (its G10s and M568s before the M563) move together, in their order, with the first
one's fix; another M563 for the tool between them, or a line that cannot move plainly, leaves them without a fix.
It is unsafe: the values then take effect, which changes what the machine does (that is the intent, but check
them), and anything between the two lines that relied on the tool not existing behaves differently.

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms), [Other ordering rules](../firmware-behaviour.md#other-ordering-rules)
- Duet3D G-code dictionary: [G10: tool temperature setting](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-tool-temperature-setting) (order dependency), [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`GetSpecifiedOrCurrentTool()`, `SetOrReportOffsets()`); older texts in [3.3 GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.3/src/GCodes/GCodes.cpp)
)md",
};

/// Could some M563 anywhere on the card create tool n (a literal P<n>, or an expression)?
bool any_m563_could_create(const Machine& m, int n) {
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const ParsedFile& pf = m.unit(i).parsed;
    for (const uint32_t ci : pf.with_code('M', 563)) {
      const Command& c = pf.commands[ci];
      if (!c.is('M', 563) || !m563_defines(pf, c)) continue;
      auto P = get_int(pf, c, 'P');
      if (!P.known() || P.value == n) return true;
    }
  }
  return false;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('G', 10) || !cx.certain()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (!is_tool_form(cx.g10_form())) return;
  auto P = get_int(pf, c, 'P');
  if (!P.known() || P.value < 0) return;
  const int n = static_cast<int>(P.value);
  if (!s.tool_certainly_absent(n) || s.failed_tools.count(n)) return;
  int macro_tool = -1;  // tool n's own change macros run only for a tool that exists
  if (is_tool_change_role(file_role(cx.unit().sd_path, &macro_tool)) && macro_tool == n) return;
  if (!cx.in_boot() && any_m563_could_create(cx.machine, n)) return;  // a macro may create it at run time

  const NodeId later = tools::later_m563(cx, n);
  // A line of config-override.g run before the M563: a note of m501-too-early's finding at the M501.
  if (later != kNoNode && !cx.graph.nodes[later].maybe && tools::inside_m501(cx.graph, cx.id)) return;
  const std::string what = tools::quote(pf, c);
  const std::string answer = tools::invalid_tool_text(s.firmware, n);
  std::string msg =
      later != kNoNode
          ? fmt::format("{} names tool {}, which does not exist yet: RRF answers '{}' and sets nothing", what, n,
                        answer)
          : fmt::format("{} names tool {}, which is never created: RRF answers '{}' and sets nothing", what, n, answer);
  Report r = out.report(kMeta, cx.at(c.span), std::move(msg));
  if (later == kNoNode) return;
  r.note(cx.where(later), fmt::format("tool {} is created here", n));
  // The later lines for this tool before the M563 (its G10s and M568s) move with this one, in their order: the
  // first line's fix moves them all in one round (the others' fixes overlap it and are left). Another M563 for the
  // tool, or a command whose tool is not known, between: no fix.
  const auto also = tools::tool_lines_between(cx, later, n);
  if (!also) return;
  const std::string title = also->empty() ? fmt::format("move the line after the 'M563 P{}'", n)
                                          : fmt::format("move the {} lines of tool {} from here after the 'M563 P{}'",
                                                        also->size() + 1, n, n);
  if (auto fix = tools::move_lines_after(cx, *also, later, title)) r.fix(std::move(*fix));
}

}  // namespace

extern const Rule g10_tool_before_definition{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
