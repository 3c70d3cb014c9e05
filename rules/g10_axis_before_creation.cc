// RRF302 g10-axis-before-creation: a tool offset on an axis that does not exist yet, or is hidden.
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF302",
    .name = "g10-axis-before-creation",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary = "A tool-offset G10 sets an axis that M584 has not created yet, or that `M584 P` hides.",
    .docs = R"md(
## What it does
Reports a tool-form G10 (`G10 P<n> …`) with an offset for an axis letter (`U`, `V`, `W`, `A`, `B`, `C`, `D`,
`'a`…) that is not a visible axis at that point: the M584 that creates it comes later (a note points at it),
or `M584 P` hides it. One finding per line, naming every such letter.

It stays silent when the axes are not known (an M584 with expressions or inside an `if`), for a G10 inside an
`if`/`while`, and for a letter whose M584 could not create it (too many axes for the board: that M584 is the
mistake). A G10 in a macro that runs after boot is judged by the end-of-boot state, but stays silent when any
M584 on the card names the letter or sets `P`: a macro may create or show the axis at run time.

## Why is this bad?
G10 only looks at the letters of *visible* axes (GCodes.cpp `SetOrReportOffsets()` loops over
`numVisibleAxes`). Any other letter is ignored without a message, so the offset is never set. Commands such as
M92 or M906 accept hidden axes; G10 does not.

## Example
```gcode
M563 P1 D1 H2 X3
G10 P1 U-0.4 Y0.2 Z0
M584 X0 Y1 Z2 U3 E4:5
```

## Use instead
```gcode
M584 X0 Y1 Z2 U3 E4:5
M563 P1 D1 H2 X3
G10 P1 U-0.4 Y0.2 Z0
```

## Fix safety
When the M584 that creates every missing axis comes later in the same file, and no other G10 or M563 for the
same tool lies in between, the fix moves the G10 line to just after that M584. It is unsafe: the offset then
takes effect.

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms), [Axes and M584](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset) (order dependency)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`SetOrReportOffsets()` looks at visible axes only)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('G', 10) || !cx.certain()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (!s.axes_known || s.unknown_baseline) return;
  if (cx.g10_form() != G10Form::Tool) return;

  std::string letters;
  std::optional<Param> first;
  std::vector<std::pair<char, NodeId>> created;  // letter, the later M584 that creates it
  std::vector<char> hidden;
  for (const Param& p : pf.params(c)) {
    const char L = p.letter;
    if (!tools::is_axis_letter(L, s) || tools::axis_visible(s, L) || s.failed_axes.count(L)) continue;
    if (!cx.in_boot() && tools::any_m584_names(cx.machine, L)) continue;  // a macro may create or show it
    if (letters.find(tools::axis_name(L)) != std::string::npos) continue;
    if (!first) first = p;
    if (!letters.empty()) letters += ", ";
    letters += tools::axis_name(L);
    if (s.axis_index(L) >= 0) hidden.push_back(L);
    else created.emplace_back(L, tools::later_m584_for(cx, L));
  }
  if (!first) return;

  const bool several = letters.find(',') != std::string::npos;
  std::string why;
  if (hidden.empty()) why = several ? "axes that do not exist yet" : "an axis that does not exist yet";
  else if (created.empty()) why = several ? "axes hidden by 'M584 P'" : "an axis hidden by 'M584 P'";
  else why = "axes that are hidden or do not exist yet";
  Report r = out.report(kMeta, cx.at(first->span),
                        fmt::format("{} sets an offset on {} ({}): G10 looks only at visible axes, so the value "
                                    "is silently ignored",
                                    tools::quote(pf, c), letters, why));
  for (char L : hidden)
    if (s.visible_set != kNoNode)
      r.note(cx.where(s.visible_set), fmt::format("axis {} is hidden here", tools::axis_name(L)));
  NodeId last = kNoNode;
  bool all_later = !created.empty() && hidden.empty();
  for (auto [L, at] : created) {
    if (at == kNoNode) {
      all_later = false;
      continue;
    }
    r.note(cx.where(at), fmt::format("axis {} is created here", tools::axis_name(L)));
    if (last == kNoNode || at > last) last = at;
  }
  if (!all_later || last == kNoNode) return;
  const ToolRef t = addressed_tool(pf, c, s);
  if (!t.known || !t.explicit_p || tools::same_tool_between(cx, last, t.number)) return;
  if (auto fix = tools::move_line_after(cx, last, "move the line after the 'M584' that creates the axis"))
    r.fix(std::move(*fix));
}

}  // namespace

extern const Rule g10_axis_before_creation{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
