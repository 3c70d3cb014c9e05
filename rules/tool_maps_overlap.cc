// RRF323 tool-maps-overlap: the X, Y and Z maps of one M563 share an axis (defaults included).
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF323",
    .name = "tool-maps-overlap",
    .severity = Severity::Error,
    .summary = "Two of a tool's X, Y and Z maps share an axis.",
    .docs = R"md(
## What it does
Builds the X, Y and Z maps of an `M563` the way RRF does and reports when two of them share an axis. A map
that is not given keeps its default: X → X, Y → Y, Z → Z. So `M563 P1 D1 X1` (X driven by the Y motor) fails
unless the same command also moves Y elsewhere. Indices of axes that do not exist or are hidden are dropped
before the test, as RRF does. `M563` has a Z map from RRF 3.5; before that only X and Y are compared.

## Why is this bad?
RRF rejects the command with `Cannot map two or more of X,Y,Z to the same axis` (`Cannot map both X and Y to the
same axis` before 3.5): the tool is not created, and a tool with that number that existed before stays as it
was. Later commands for the tool then fail or configure the old one.

## Example
```gcode
M584 X0 Y1 Z2 U3 E4:5
M563 P1 D1 X1
M563 P2 D1 X0:3 Y3
```

## Use instead
```gcode
M584 X0 Y1 Z2 U3 E4:5
M563 P1 D1 X3
M563 P2 D1 X0:3
```

## References
- rrflint: [M563 tools](../firmware-behaviour.md#m563-tools)
- Duet3D G-code dictionary: [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`ManageTool()`)
)md",
};

std::string describe(const MachineState& s, const M563Map& m) {
  return fmt::format("{} → {}{}", m.letter, s.axis_letters(m.bits),
                     m.given ? "" : " (its default, since it is not given)");
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 563) || !cx.certain()) return;
  const MachineState& s = cx.state;
  if (!tools::axes_certain(s)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  bool any = false;
  for (char L : {'X', 'Y', 'Z'}) any = any || (pf.find(c, L) && (L != 'Z' || has_z_map(s.firmware)));
  if (!any) return;  // all defaults: they never overlap
  const bool z = has_z_map(s.firmware);
  const M563Map maps[3] = {m563_map(pf, c, s, 'X'), m563_map(pf, c, s, 'Y'), z ? m563_map(pf, c, s, 'Z') : M563Map{}};
  for (const auto& m : maps)
    if (!m.known) return;
  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      if (b == 2 && !z) continue;
      const uint32_t shared = maps[a].bits & maps[b].bits;
      if (!shared) continue;
      const std::string reply =
          z ? "Cannot map two or more of X,Y,Z to the same axis" : "Cannot map both X and Y to the same axis";
      const M563Map& given = maps[a].given ? maps[a] : maps[b];
      out.report(kMeta, cx.at(given.param ? given.param->span : c.span),
                 fmt::format("{} maps both {} and {} to {} ({}; {}): RRF answers '{}' and does not create the tool",
                             tools::quote(pf, c), maps[a].letter, maps[b].letter, s.axis_letters(shared),
                             describe(s, maps[a]), describe(s, maps[b]), reply));
      return;
    }
  }
}

}  // namespace

extern const Rule tool_maps_overlap{.meta = kMeta, .check_node = check, .on = "M563"};

}  // namespace rrflint
