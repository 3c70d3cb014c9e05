// RRF322 tool-map-order: an M563 axis index means another letter than the standard order suggests.
#include <fmt/format.h>

#include <algorithm>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF322",
    .name = "tool-map-order",
    .severity = Severity::Warning,
    .summary =
        "An M563 axis index names a different axis than the standard XYZUVWABCD order, because axes were "
        "created out of order.",
    .docs = R"md(
## What it does
`M563` maps a tool's X, Y and Z to axis *indices*, and an axis gets its index when `M584` creates it. One `M584`
creates its new axes in the order XYZUVWABCD…, whatever order the parameters are written in, but separate
`M584` commands create axes in the order they run. The rule reports an index in an `M563` map that names a
different axis than it would if the existing axes had been created in the standard order, which is what the
documentation ("X = 0, Y = 1, Z = 2, U = 3 …") and most examples assume.

It reports only an index that lands on a rotational axis (A–D by default, or `M584 … R1`) where the standard
order has a linear one: mapping a tool's X, Y or Z to a rotary axis is almost never meant. Between two linear
axes the intent cannot be told (the file's author may count in creation order), and the rule stays silent. It
is also silent when the axes are not known for certain, for maps given as expressions, and for indices that do
not exist (that is `tool-map-before-axis`).

## Why is this bad?
The tool drives a different motor than intended, silently: in the example, `X3` maps the tool's X to C, the
rotary axis, rather than to U.

## Example
```gcode
M584 X0 Y1 Z2 C5
M584 U6 E3:4
M563 P1 D1 X3
```

## Use instead
```gcode
M584 X0 Y1 Z2 U6 C5 E3:4
M563 P1 D1 X3
```

## References
- rrflint: [Axes and M584](../firmware-behaviour.md#axes-and-m584), [M563 tools](../firmware-behaviour.md#m563-tools)
- Duet3D G-code dictionary: [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool), [M584: set drive mapping](https://docs.duet3d.com/User_manual/Reference/Gcodes#m584-set-drive-mapping)
- RepRapFirmware 3.5.3: [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes3.cpp) (`DoDriveMapping()`: a new axis gets the next index)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 563) || !cx.certain()) return;
  const MachineState& s = cx.state;
  if (!tools::axes_certain(s)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  // The axes as they would be numbered had they been created in the standard order.
  const std::string_view order = allowed_axis_letters();
  std::vector<char> standard;
  for (const Axis& a : s.axes) standard.push_back(a.letter);
  std::stable_sort(standard.begin(), standard.end(), [&](char a, char b) { return order.find(a) < order.find(b); });
  for (char L : {'X', 'Y', 'Z'}) {
    if (L == 'Z' && !has_z_map(s.firmware)) continue;
    const M563Map m = m563_map(pf, c, s, L);
    if (!m.given || !m.known) continue;
    for (int64_t i : m.indices) {
      if (i < 0 || i >= s.visible_axes || i >= static_cast<int64_t>(s.axes.size())) continue;
      const Axis& actual = s.axes[static_cast<size_t>(i)];
      const char expected = standard[static_cast<size_t>(i)];
      // Only a map that lands on a rotary axis where the standard order has a linear one is reported: a tool's
      // X/Y/Z on a rotary axis is almost never meant, while between two linear axes the intent is unclear.
      if (actual.letter == expected || !actual.rotational) continue;
      if (const int e = s.axis_index(expected); e < 0 || s.axes[static_cast<size_t>(e)].rotational) continue;
      const int exp_index = s.axis_index(expected);
      const std::string exp_name = tools::axis_name(s, exp_index);
      Report r = out.report(
          kMeta, cx.at(m.param->span),
          fmt::format("{} maps {} to axis index {}, which is {} here, not {}: the axes were created out of the "
                      "standard order, and M563 counts them in creation order ({} is index {})",
                      tools::quote(pf, c), L, i, tools::axis_name(s, static_cast<int>(i)), exp_name, exp_name,
                      exp_index));
      if (actual.created != kNoNode)
        r.note(cx.where(actual.created),
               fmt::format("{} is created here, as axis index {}", tools::axis_name(s, static_cast<int>(i)), i));
      if (exp_index >= 0 && s.axes[static_cast<size_t>(exp_index)].created != kNoNode)
        r.note(cx.where(s.axes[static_cast<size_t>(exp_index)].created),
               fmt::format("{} is created here, as axis index {}", exp_name, exp_index));
    }
  }
}

}  // namespace

extern const Rule tool_map_order{.meta = kMeta, .check_node = check, .on = "M563"};

}  // namespace rrflint
