// RRF321 tool-map-before-axis: an M563 X/Y/Z map names an axis index that does not exist (yet) or is hidden.
#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF321",
    .name = "tool-map-before-axis",
    .severity = Severity::Warning,
    .summary = "An M563 X/Y/Z map names an axis index that does not exist (yet) or is hidden by M584 P.",
    .docs = R"md(
## What it does
Checks every index in the `X`, `Y` and (RRF 3.5+) `Z` maps of `M563` against the axes that exist and are
visible at that point. Indices count axes in creation order: X = 0, Y = 1, Z = 2, then the axes `M584` created.
When the index is the driver number of an existing axis, the message says so: `M584 … U5` makes driver 5 the
U motor, but U's axis index is 3.

It stays silent when the axes are not known for certain (an `M584` with expressions or inside a conditional
block) and for maps given as expressions.

## Why is this bad?
RRF ANDs each map with the visible axes and silently drops the rest. A map that loses all its bits leaves the
tool with no axis for that letter: `M563 P1 … X3` before U exists means tool 1's X moves go nowhere, with no
message.

## Example
```gcode
M584 X0 Y1 Z2 E4:5
M563 P1 D1 X3
M584 U3
```

## Use instead
```gcode
M584 X0 Y1 Z2 U3 E4:5
M563 P1 D1 X3
```

## References
- rrflint: [M563 tools](../firmware-behaviour.md#m563-tools)
- Duet3D G-code dictionary: [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`ManageTool()`: maps cut to the visible axes)
)md",
};

/// The axis whose local driver number is `d`, other than axis `not_index`, or -1.
int axis_with_driver(const MachineState& s, int64_t d, int not_index) {
  for (size_t a = 0; a < s.axes.size(); ++a) {
    if (static_cast<int>(a) == not_index) continue;
    for (const DriverId& id : s.axes[a].drivers)
      if (id.board == 0 && id.driver == d) return static_cast<int>(a);
  }
  return -1;
}

std::string tool_name(int n) { return n >= 0 ? fmt::format("tool {}", n) : "the tool"; }

std::string existing_axes(const MachineState& s, int count) {
  std::string out;
  for (int i = 0; i < count && i < static_cast<int>(s.axes.size()); ++i)
    out += (out.empty() ? "" : ", ") + tools::axis_name(s, i);
  return out;
}

void check_map(const NodeContext& cx, const M563Map& m, int tool, Sink& out) {
  const MachineState& s = cx.state;
  const ParsedFile& pf = cx.parsed();
  for (int64_t i : m.indices) {
    if (i < s.visible_axes) continue;
    const int idx = static_cast<int>(i);
    const bool hidden = idx < static_cast<int>(s.axes.size());
    const std::string effect =
        m.bits == 0 ? fmt::format("{}'s {} moves go nowhere", tool_name(tool), m.letter)
                    : fmt::format("{}'s {} moves drive only {}", tool_name(tool), m.letter, s.axis_letters(m.bits));
    std::string msg;
    if (hidden) {
      msg = fmt::format(
          "{} maps {} to axis index {} ({}), which 'M584 P{}' hides: tool maps keep only visible axes, "
          "so RRF silently drops it and {}",
          tools::quote(pf, cx.command()), m.letter, idx, tools::axis_name(s, idx), s.visible_axes, effect);
    } else {
      msg = fmt::format(
          "{} maps {} to axis index {}, but only {} axes exist at this point ({}): RRF silently drops "
          "the index and {}",
          tools::quote(pf, cx.command()), m.letter, idx, s.axes.size(),
          existing_axes(s, static_cast<int>(s.axes.size())), effect);
    }
    const int by_driver = axis_with_driver(s, i, idx);
    const bool mixup = by_driver >= 3 && by_driver < s.visible_axes;
    if (mixup)
      msg += fmt::format("; {} is the driver number of axis {}, whose axis index is {} (write '{}{}')", idx,
                         tools::axis_name(s, by_driver), by_driver, m.letter, by_driver);
    Report r = out.report(kMeta, cx.at(m.param->span), std::move(msg));
    if (hidden && s.visible_set != kNoNode) r.note(cx.where(s.visible_set), "the visible axes are set here");
    if (!hidden) {
      // Look ahead for the M584 that creates enough axes: the first later M584 (not in an if/while) by which the
      // axes named so far outnumber idx. Each new letter counts at its first such M584 (from the index of M584s by
      // letter), so it is the need-th of those.
      std::string letters;
      for (const Axis& a : s.axes) letters += a.letter;
      const tools::CodeIndex& m584s = tools::m584_by_letter(cx.machine, cx.graph);
      NodeId later = kNoNode;
      const ptrdiff_t need = static_cast<ptrdiff_t>(idx) + 1 - static_cast<ptrdiff_t>(letters.size());
      if (need <= 0) {
        later = tools::first_later(cx, m584s.certain);
      } else {
        std::vector<NodeId> firsts;
        for (char L : allowed_axis_letters()) {
          if (letters.find(L) != std::string::npos) continue;
          auto it = m584s.certain_by_letter.find(L);
          if (it == m584s.certain_by_letter.end()) continue;
          if (const NodeId at = tools::first_later(cx, it->second); at != kNoNode) firsts.push_back(at);
        }
        if (firsts.size() >= static_cast<size_t>(need)) {
          std::nth_element(firsts.begin(), firsts.begin() + (need - 1), firsts.end());
          later = firsts[static_cast<size_t>(need - 1)];
        }
      }
      if (later != kNoNode) r.note(cx.where(later), fmt::format("axis index {} is created later, here", idx));
    }
    if (mixup)
      r.note(cx.where(s.axes[static_cast<size_t>(by_driver)].drivers_set),
             fmt::format("driver {} is assigned to axis {} here", idx, tools::axis_name(s, by_driver)));
  }
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 563) || !cx.certain()) return;
  const MachineState& s = cx.state;
  if (!tools::axes_certain(s)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  auto P = get_int(pf, c, 'P');
  const int tool = P.known() ? static_cast<int>(P.value) : -1;
  for (char L : {'X', 'Y', 'Z'}) {
    if (L == 'Z' && !has_z_map(s.firmware)) continue;
    const M563Map m = m563_map(pf, c, s, L);
    if (!m.given || !m.known) continue;
    check_map(cx, m, tool, out);
  }
}

}  // namespace

extern const Rule tool_map_before_axis{.meta = kMeta, .check_node = check, .on = "M563"};

}  // namespace rrflint
