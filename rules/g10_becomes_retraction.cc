// RRF303 g10-becomes-retraction: a G10 meant as an offset that RRF runs as firmware retraction.
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF303",
    .name = "g10-becomes-retraction",
    .severity = Severity::Error,
    .summary = "A G10 with no L, P, R or S whose axis letters are not visible axes runs firmware retraction.",
    .docs = R"md(
## What it does
Reports two kinds of G10 that RRF dispatches as firmware retraction although they look like offset commands:
- a G10 with no `L`, `P`, `R` or `S` (nor `F` on 3.3–3.4) whose only axis letters name axes that do not exist
  (yet) or are hidden by `M584 P`, anywhere;
- a bare `G10` in config.g or a file it runs at boot (not in tool-change macros, where a bare G10 is a
  deliberate retraction).

It stays silent when the axes are not known (an M584 with expressions or inside an `if`), for a G10 inside
an `if`/`while`, and in a macro that runs after boot when any M584 on the card names the letter or sets `P`.

## Why is this bad?
Without L, RRF treats G10 as a tool command only if it sees P, R, S or the letter of a *visible* axis
(GCodes2.cpp, case 10). Otherwise it retracts the current tool's filament with the M207 settings, or does
nothing when no tool is selected. The offset is never set, and no message says so.

## Example
```gcode
M584 X0 Y1 Z2 E3
G10 U10          ; meant: offset of the current tool on U
G10              ; meant: "set tool offsets"
```

## Use instead
```gcode
M584 X0 Y1 Z2 U4 E3
G10 P1 U10
```

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset), [G10: retract](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-retract)
- RepRapFirmware 3.5.3: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (`HandleGcode()` case 10); [3.4.6 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.4.6/src/GCodes/GCodes2.cpp) (3.4.x also counts `F`)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('G', 10) || !cx.certain()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (c.param_count == 0) {
    if (!cx.in_boot() || tools::in_tool_macro(cx.graph, cx.id)) return;
    out.report(kMeta, cx.at(c.span),
               "bare 'G10' at boot runs firmware retraction, not a tool-offset command: name the tool and the "
               "axes, e.g. 'G10 P0 X0 Y0 Z0'");
    return;
  }
  if (cx.g10_form() != G10Form::Retraction) return;
  std::string letters;
  std::vector<char> list;
  for (const Param& p : pf.params(c)) {
    if (!tools::is_axis_letter(p.letter, s)) continue;
    if (!letters.empty()) letters += ", ";
    letters += tools::axis_name(p.letter);
    list.push_back(p.letter);
  }
  if (list.empty()) return;
  if (!cx.in_boot())
    for (char L : list)
      if (tools::any_m584_names(cx.machine, L)) return;  // a macro may create or show the axis
  Report r = out.report(
      kMeta, cx.at(c.span),
      fmt::format("{} has no L, P, R or S and {} {} here: RRF runs firmware retraction instead of setting a "
                  "tool offset",
                  tools::quote(pf, c), letters, list.size() > 1 ? "are not visible axes" : "is not a visible axis"));
  for (char L : list) {
    if (s.axis_index(L) >= 0) {
      if (s.visible_set != kNoNode)
        r.note(cx.where(s.visible_set), fmt::format("axis {} is hidden here", tools::axis_name(L)));
    } else if (NodeId at = tools::later_m584_for(cx, L); at != kNoNode) {
      r.note(cx.where(at), fmt::format("axis {} is created here", tools::axis_name(L)));
    }
  }
}

}  // namespace

extern const Rule g10_becomes_retraction{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
