// RRF326 tool-select-runs-macros-at-boot: `T<n>` at boot runs tool-change macros that move an un-homed
// machine, or switches heaters on.
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/node_index.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF326",
    .name = "tool-select-runs-macros-at-boot",
    .severity = Severity::Warning,
    .summary = "T<n> without P0 at boot runs tool-change macros before anything is homed, or heats the tool.",
    .docs = R"md(
## What it does
Looks at each `T<n>` without `P0` in config.g or a file it runs at boot, on targets RRF 3.1.0 and later, for a
tool that exists at that point:
- **warning** when a tool-change macro that this `T` runs (`tpre<n>.g`, `tpost<n>.g`; the generic `tpre.g` and
  `tpost.g` on 3.5+; `tfree<m>.g` only when another tool was selected before) contains a move (`G0`–`G3`),
  homing (`G28`), probing (`G29`, `G30`, `G32`, `G38.x`, `M585`) or an `M98`, outside an `if` that tests
  `move.axes[…].homed` (or after such an `if` that aborts);
- **info** otherwise, when an active temperature of 40 °C or more was set for the tool before the `T`: selecting
  the tool switches its heaters on.

It is silent when the macros are missing, hold only comments, or hold only waits (`M116`, `M109`) while the
active temperature is below 40 °C, since at boot such a wait returns at once. It is also silent for `T-1`,
`T<n> P0`, re-selecting the current tool, targets before 3.1.0 (where the macros waited for homing) and inside
`if`/`while` blocks.

## Why is this bad?
From RRF 3.1.0 tool-change macros run even when no axis is homed (the documentation says 3.3; the source says
3.1.0). At boot nothing is homed, so a pick-up or park move in tpre/tpost either fails with a homing error or
moves the carriage from an assumed position into the frame. `T<n> P0` selects the tool without running any
macro, which is what the Duet documentation recommends for config.g.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
T0
; file: sys/tpost0.g
G1 Y250 F6000
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
T0 P0
; file: sys/tpost0.g
G1 Y250 F6000
```

## References
- rrflint: [T tool selection](../firmware-behaviour.md#t-tool-selection)
- Duet3D [Tool changing](https://docs.duet3d.com/User_manual/Tuning/Tool_changing#selecting-tool-in-configg), [T: select tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#t-select-tool)
- RepRapFirmware 3.5.3: [GCodes4.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes4.cpp) (tool-change states, run even when not homed), [Tool.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Tools/Tool.cpp) (`HeatersToActiveOrStandby()`), [Heat.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Heating/Heat.cpp) (`TemperatureSoLowDontCare`)
)md",
};

bool is_motion(const Command& c) {
  if (c.letter == 'G')
    return (c.fraction < 0 &&
            (c.number <= 3 || c.number == 28 || c.number == 29 || c.number == 30 || c.number == 32)) ||
           c.number == 38;
  return c.is('M', 585) || c.is('M', 98);
}

bool mentions_homed(std::string_view s) { return to_lower(s).find("homed") != std::string::npos; }

/// Does the condition of this if/elif/else/while line, or of the if chain an else belongs to, test homing?
bool header_tests_homed(const ParsedFile& pf, size_t j) {
  const Line& h = pf.lines[j];
  if (h.meta == MetaKind::If || h.meta == MetaKind::While) return mentions_homed(pf.text(h.meta_arg));
  if (h.meta != MetaKind::Elif && h.meta != MetaKind::Else) return false;
  if (h.meta == MetaKind::Elif && mentions_homed(pf.text(h.meta_arg))) return true;
  for (size_t k = j; k-- > 0;) {  // the earlier branches of the same chain
    const Line& b = pf.lines[k];
    if (b.kind == LineKind::Blank || b.kind == LineKind::Comment || b.indent > h.indent) continue;
    if (b.indent < h.indent || b.kind != LineKind::Meta) break;
    if ((b.meta == MetaKind::If || b.meta == MetaKind::Elif) && mentions_homed(pf.text(b.meta_arg))) return true;
    if (b.meta == MetaKind::If) break;
  }
  return false;
}

/// Is the command inside a block guarded by a homing test, or after an `if` on homing that aborts/returns?
bool guarded(const ParsedFile& pf, const Command& c) {
  const size_t li = c.line;
  uint32_t want = pf.lines[li].indent;
  for (size_t j = li; j-- > 0 && want > 0;) {
    const Line& l = pf.lines[j];
    if (l.kind == LineKind::Blank || l.kind == LineKind::Comment || l.indent >= want) continue;
    if (l.kind == LineKind::Meta && header_tests_homed(pf, j)) return true;
    want = l.indent;
  }
  // `if !move.axes[0].homed` followed by `abort` / `M99` earlier in the file.
  for (size_t j = 0; j < li; ++j) {
    const Line& h = pf.lines[j];
    if (h.kind != LineKind::Meta || h.meta != MetaKind::If || !mentions_homed(pf.text(h.meta_arg))) continue;
    for (size_t k = j + 1; k < li; ++k) {
      const Line& b = pf.lines[k];
      if (b.kind == LineKind::Blank || b.kind == LineKind::Comment) continue;
      if (b.indent <= h.indent) break;
      if (b.meta == MetaKind::Abort) return true;
      for (uint32_t ci = b.first_command; ci < b.first_command + b.command_count; ++ci)
        if (pf.commands[ci].is('M', 99)) return true;
    }
  }
  return false;
}

std::string file_name(std::string_view sd_path) {
  const size_t slash = sd_path.rfind('/');
  return std::string(slash == std::string_view::npos ? sd_path : sd_path.substr(slash + 1));
}

/// The G10s (letter 'G') or M568s (letter 'M') with S, which may set an active temperature, by the tool their P
/// names; built once per graph. Each T used to walk every node before it. A P given by an expression is left out.
const tools::DeviceIndex& temperature_setters(const NodeContext& cx, char letter) {
  struct Named {
    int64_t number;
    bool known;
  };
  return tools::device_index(cx.machine, cx.graph, std::string("tool_select.temperature_setters.") + letter, letter,
                             letter == 'G' ? 10 : 568,
                             [](const ParsedFile& pf, const Command& c) -> std::optional<Named> {
                               auto P = get_int(pf, c, 'P');
                               if (!P.known() || !pf.find(c, 'S')) return std::nullopt;
                               return Named{P.value, true};
                             });
}

/// The last G10/M568 before this node that set an active temperature for tool n.
NodeId temperature_origin(const NodeContext& cx, int n) {
  return tools::later_of(temperature_setters(cx, 'G').last_in(cx.segment().begin, cx.id, n),
                         temperature_setters(cx, 'M').last_in(cx.segment().begin, cx.id, n));
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command() || !cx.certain() || !cx.in_boot()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  if (c.letter != 'T' || c.fraction >= 0 || c.number_expr || c.number < 0) return;
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_1 || s.unknown_baseline) return;
  auto P = get_int(pf, c, 'P');
  if (P.present() && (!P.known() || P.value == 0)) return;
  const int n = c.number;
  const Tool* tool = s.tool(n);
  if (!tool || tool->maybe || !s.current_tool_known || s.current_tool == n) return;

  // The tool-change macros the graph runs for this T, and the first unguarded motion in them.
  const Node& self = cx.node();
  std::vector<NodeId> macros;
  NodeId motion = kNoNode;
  const Segment& seg = cx.segment();
  cx.graph.nodes.find_if(cx.id + 1, seg.end, [&](NodeId j, const Node& nd) {
    if ((nd.kind == NodeKind::Command || nd.kind == NodeKind::Leave) && nd.enter == self.enter) return true;
    if (nd.kind == NodeKind::Enter && nd.call_site == cx.id &&
        (nd.call == CallKind::ToolFree || nd.call == CallKind::ToolPre || nd.call == CallKind::ToolPost))
      macros.push_back(j);
    if (nd.kind != NodeKind::Command || motion != kNoNode || macros.empty() || nd.enter != macros.back()) return false;
    const ParsedFile& mpf = cx.machine.unit(nd.unit).parsed;
    const Command& mc = mpf.commands[nd.index];
    if (is_motion(mc) && !guarded(mpf, mc)) motion = j;
    return false;
  });

  if (motion != kNoNode) {
    const Node& mn = cx.graph.nodes[motion];
    const FileUnit& mu = cx.machine.unit(mn.unit);
    const Command& mc = mu.parsed.commands[mn.index];
    const std::string what = mc.is('M', 98)                       ? "runs a macro"
                             : mc.is('G', 28)                     ? "homes axes"
                             : mc.letter == 'G' && mc.number <= 3 ? "moves the machine"
                                                                  : "probes";
    std::string names;
    for (NodeId m : macros)
      names += (names.empty() ? "" : ", ") + file_name(cx.machine.unit(cx.graph.nodes[m].unit).sd_path);
    out.report(kMeta, cx.at(c.span),
               fmt::format("{} runs {} at boot, before any axis is homed, and {} there {}: RRF 3.1 and later run "
                           "tool-change macros even when nothing is homed; select the tool with 'T{} P0' in config.g",
                           tools::quote(pf, c), names, tools::quote(mu.parsed, mc), what, n))
        .note(cx.where(motion), fmt::format("{} {} here", file_name(mu.sd_path), what));
    return;
  }

  if (!tool->temps_known) return;
  double hot = 0;
  for (double v : tool->active) hot = std::max(hot, v);
  if (hot < 40) return;
  Report r = out.report(kMeta, Severity::Info, cx.at(c.span),
                        fmt::format("{} selects tool {} at boot, which switches its heaters to the {} active "
                                    "temperature set before it: the hot end heats as soon as the machine is powered",
                                    tools::quote(pf, c), n, tools::degrees(hot)));
  if (NodeId o = temperature_origin(cx, n); o != kNoNode)
    r.note(cx.where(o), fmt::format("tool {}'s active temperature is set here", n));
}

}  // namespace

extern const Rule tool_select_runs_macros_at_boot{.meta = kMeta, .check_node = check, .on = "T"};

}  // namespace rrflint
