// RRF320 tool-redefined: M563 re-creates a tool that G10/M568/M207/M567 already configured.
#include <fmt/format.h>

#include <algorithm>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF320",
    .name = "tool-redefined",
    .severity = Severity::Warning,
    .summary = "M563 re-creates a tool after G10/M568/M207/M567 configured it, resetting those settings.",
    .docs = R"md(
## What it does
Reports an `M563 P<n>` that defines tool n (it has `S`, `D`, `H`, `X`, `Y`, `Z`, `F` or `R`) while tool n
already exists and carries settings made since its creation: non-zero offsets (`G10`), temperatures above 0
(`G10`/`M568`), firmware retraction (`M207`) or a mix ratio (`M567`). A note points at the command whose
setting is lost.

In a standalone macro only settings made by that same macro count: a macro that re-runs part of config.g (a
tool-set file, expansion-reconnect.g) re-creates the tools on purpose. Settings loaded from config-override.g by
`M501` are left to `override-after-m501` (RRF402), and an `M563`
that RRF rejects before deleting the old tool (overlapping axis maps) is left to `tool-maps-overlap`.

## Why is this bad?
Defining an existing tool first deletes it and then creates a fresh one: offsets 0, temperatures off, default
retraction and mix. RRF says nothing. It often happens when a tool is "amended" further down, for example to
add a name: `M563 P0 S"Hotend" D0 H1` after the offsets were set.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
G10 P0 X10 Y5 Z0
M563 P0 D0 S"Hotend"
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0 S"Hotend"
G10 P0 X10 Y5 Z0
```

## References
- rrflint: [M563 tools](../firmware-behaviour.md#m563-tools)
- Duet3D G-code dictionary: [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`ManageTool()`), [Tool.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Tools/Tool.cpp) (`Tool::DeleteTool()`, `Tool::Create()`)
)md",
};

/// Would RRF reject this M563 before deleting the old tool (overlapping maps, docs/firmware-behaviour.md#m563-tools)?
bool rejected_early(const ParsedFile& pf, const Command& c, const MachineState& s) {
  const auto x = m563_map(pf, c, s, 'X'), y = m563_map(pf, c, s, 'Y');
  const auto z = has_z_map(s.firmware) ? m563_map(pf, c, s, 'Z') : M563Map{'Z', false, true, 0};
  if (!x.known || !y.known || !z.known) return true;  // cannot tell: stay silent
  return (x.bits & y.bits) || (x.bits & z.bits) || (y.bits & z.bits);
}

struct Lost {
  std::string what;
  NodeId where = kNoNode;
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 563) || !cx.certain()) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  auto P = get_int(pf, c, 'P');
  if (!P.known() || !m563_defines(pf, c)) return;
  const int n = static_cast<int>(P.value);
  const Tool* t = s.tool(n);
  if (!t || t->maybe || s.unknown_baseline || rejected_early(pf, c, s)) return;
  auto D = get_int_list(pf, c, 'D');
  auto H = get_int_list(pf, c, 'H');
  if (D.known() && H.known() && D.value == std::vector<int64_t>{-1} && H.value == std::vector<int64_t>{-1} &&
      !pf.find(c, 'R'))
    return;  // `D-1 H-1` deletes the tool on purpose

  std::vector<Lost> lost;
  // In a standalone macro, only settings made by that macro count: a macro that re-runs part of config.g
  // (a tool-set file, expansion-reconnect.g) re-creates the tools on purpose and configures them again.
  const NodeId since = cx.in_boot() ? 0 : cx.segment().begin;
  auto keep = [&](std::string what, NodeId where) {
    if (where == kNoNode || where < since || tools::inside_m501(cx.graph, where)) return;
    lost.push_back(Lost{std::move(what), where});
  };
  for (size_t i = 0; i < s.axes.size() && i < t->offsets.size(); ++i) {
    const Fact& f = t->offsets[i];
    if (f.origin != kNoNode && (!f.known || f.value != 0)) {
      keep("offsets", f.origin);
      break;
    }
  }
  bool hot = !t->temps_known;
  for (double v : t->active) hot = hot || v > 0;
  for (double v : t->standby) hot = hot || v > 0;
  // Retraction and mix ratios are not modelled as values: any M207/M567 for this tool since it was created.
  // The temperatures' note goes to the last G10/M568 that set R or S for it. Only the nodes of those codes are visited
  // (the code index): a walk of every node since the tool's creation cost a config of many tools dearly.
  NodeId temps_at = kNoNode;
  auto visit = [&](NodeId j, const tools::NodeCommand& k) {
    if (k.node.maybe) return false;
    const ParsedFile& opf = *k.pf;
    const Command& oc = *k.c;
    const bool m207 = oc.is('M', 207), temps = oc.is('G', 10) || oc.is('M', 568);
    auto op = get_int(opf, oc, 'P');
    if (temps) {
      if (op.known() && op.value == n && (opf.find(oc, 'R') || opf.find(oc, 'S')))
        temps_at = temps_at == kNoNode ? j : std::max(temps_at, j);  // the last one: G10s and M568s are visited apart
      return false;
    }
    if (op.known() ? op.value != n : !(m207 && op.absent())) return false;
    keep(m207 ? "retraction settings" : "mix ratios", j);
    return false;
  };
  tools::each_code_node(cx, t->created + 1, cx.id, 'G', 10, visit);
  tools::each_code_node(cx, t->created + 1, cx.id, 'M', {207, 567, 568}, visit);
  if (hot) keep("temperatures", temps_at != kNoNode ? temps_at : t->last_configured);
  if (lost.empty()) return;
  std::vector<std::string> names;
  for (const Lost& l : lost)
    if (std::find(names.begin(), names.end(), l.what) == names.end()) names.push_back(l.what);
  std::string what;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) what += i + 1 == names.size() ? " and " : ", ";
    what += names[i];
  }
  Report r = out.report(kMeta, cx.at(c.span),
                        fmt::format("{} re-creates tool {}, which was already configured: RRF deletes the tool and "
                                    "makes a fresh one, so its {} are reset",
                                    tools::quote(pf, c), n, what));
  r.note(cx.where(t->created), fmt::format("tool {} is created here", n));
  // One note per command, naming everything it set.
  std::vector<std::pair<NodeId, std::string>> notes;
  for (const Lost& l : lost) {
    auto it = std::find_if(notes.begin(), notes.end(), [&](const auto& e) { return e.first == l.where; });
    if (it == notes.end()) notes.emplace_back(l.where, l.what);
    else if (it->second.find(l.what) == std::string::npos) it->second += " and " + l.what;
  }
  for (const auto& [where, set] : notes) r.note(cx.where(where), fmt::format("tool {}'s {} are set here", n, set));
}

}  // namespace

extern const Rule tool_redefined{.meta = kMeta, .check_node = check, .on = "M563"};

}  // namespace rrflint
