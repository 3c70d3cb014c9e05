// RRF202 extruder-before-creation: extruder values or extruder numbers before `M584 E…` creates the extruders.
#include <algorithm>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF202",
    .name = "extruder-before-creation",
    .severity = Severity::Error,
    .summary = "An extruder is used before `M584 E…` creates it (RRF 3.3 and later have no default extruder).",
    .docs = R"md(
## What it does
On targets from RRF 3.3, where no extruder exists until `M584 E…` creates it, reports:
- `M563 … D<n>` naming an extruder that does not exist (yet): the tool is not created. Notes point at the later
  `M584 E…` and at later lines that name the tool (`G10`, `M568`, `T`), which then fail or do nothing;
- `E` values in M92, M201, M203, M205, M350, M566, M906, M913 or M917 with more values than there are
  extruders (any value before the first `M584 E…`);
- `D` in M572, M591 and M221 naming an extruder that does not exist.

It stays silent on RRF 2.x–3.2 targets (they have default extruders), for values written as expressions, when
the extruder count is not known (an `M584 E` with expressions or inside an `if`), and for commands inside an
`if`/`while`. A line that runs again after the `M584 E…` (a macro called before and after it) takes effect
then, and is not reported either.

## Firmware versions
A **hazard** of RRF 3.3 and later, which have no default extruder. It is judged at the target only. A config that
uses extruders with no `M584 E` is not taken as evidence of an older version: that is the mistake this rule
reports.

## Why is this bad?
- M563 checks its drives after deleting any old tool with that number: `bad drive number`, and the tool number
  then does not exist at all. Every later G10, M568 or T for it fails or selects nothing.
- An E list longer than the extruder count throws `array too long for parameter 'E'` (3.5.2 and later;
  `array too long, max length = 0` on 3.3–3.5.1). The axis values of the same line are applied, the E values
  are lost.
- `M572 D0` answers `Invalid extruder number '0'`; `M591 D0` and `M221 D0` answer `parameter 'D' too high`.

## Example
```gcode
M584 X0 Y1 Z2
M92 X80 Y80 Z400 E420
M563 P0 D0 H1
M584 E3
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M92 X80 Y80 Z400 E420
M563 P0 D0 H1
```

## References
- rrflint: [Other ordering rules](../firmware-behaviour.md#other-ordering-rules), [M563 tools](../firmware-behaviour.md#m563-tools), [Axes and M584](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M584: set drive mapping](https://docs.duet3d.com/User_manual/Reference/Gcodes#m584-set-drive-mapping), [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool)
- RepRapFirmware 3.5.3: [Tool.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Tools/Tool.cpp) (`Tool::Create()`: `bad drive number`), [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`CheckArrayLength()`), [Move.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Movement/Move.cpp) (`ConfigurePressureAdvance()`), [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (no extruders by default)
)md",
};

std::string extruders_here(int n) {
  if (n == 0) return "no extruder exists yet (RRF 3.3 and later have none until 'M584 E…')";
  return n == 1 ? "only 1 extruder exists here" : fmt::format("only {} extruders exist here", n);
}

NodeId later_m584_e(const NodeContext& cx) { return tools::later_m584_for(cx, 'E'); }

/// Does this very line run again after the M584 that creates the extruders (a macro called before and after it)?
/// Then it takes effect after all.
bool runs_again_later(const NodeContext& cx) {
  const NodeId at = later_m584_e(cx);
  return at != kNoNode && tools::runs_again(cx, at);
}

void note_m584_e(const NodeContext& cx, Report& r) {
  if (NodeId at = later_m584_e(cx); at != kNoNode) r.note(cx.where(at), "the extruders are created here");
}

/// Per tool number, the nodes that select it (T) or name it (G10 in the tool form, M568, M563), in node order; built
/// once per graph and firmware. The notes of a failed M563 used to walk every later node, for each: a config of
/// thousands of tools that all fail was quadratic.
struct ToolUses {
  std::unordered_map<int64_t, std::vector<NodeId>> by_tool;
};
const ToolUses& tool_uses(const NodeContext& cx) {
  const Version fw = cx.state.firmware;
  return cx.graph.derived<ToolUses>("extruder_before_creation.tool_uses." + fw.str(), [&] {
    ToolUses out;
    for (const auto& [letter, number] : {std::pair{'G', 10}, std::pair{'M', 568}, std::pair{'M', 563}})
      tools::each_code_command(cx.machine, cx.graph, letter, number,
                               [&](NodeId id, const Node&, const ParsedFile& pf, const Command& c) {
                                 auto P = get_int(pf, c, 'P');
                                 if (!P.known()) return;
                                 if (c.is('G', 10) && !is_tool_form(g10_form(pf, c, nullptr, fw))) return;
                                 out.by_tool[P.value].push_back(id);
                               });
    cx.graph.nodes.each_whole([&](NodeId id, const Node& n) {
      if (n.kind == NodeKind::ToolSelect && n.index != kNoToolNumber) out.by_tool[n.index].push_back(id);
    });
    for (auto& [tool, ids] : out.by_tool) std::sort(ids.begin(), ids.end());
    return out;
  });
}

/// Notes at later lines that name tool n, up to its next definition: they fail or do nothing.
void note_tool_uses(const NodeContext& cx, Report& r, int n) {
  const std::vector<NodeId>& uses = tools::ids_of(tool_uses(cx).by_tool, int64_t{n});
  int notes = 0;
  for (auto it = std::upper_bound(uses.begin(), uses.end(), cx.id);
       it != uses.end() && *it < cx.segment().end && notes < 8; ++it) {
    const Node& node = cx.graph.nodes[*it];
    if (node.kind == NodeKind::ToolSelect) {
      r.note(cx.where(node.call_site), fmt::format("'T{}' here selects no tool", n));
      ++notes;
      continue;
    }
    const ParsedFile& pf = cx.machine.unit(node.unit).parsed;
    const Command c = pf.commands[node.index];
    if (c.is('M', 563)) {
      if (m563_defines(pf, c)) return;
      continue;
    }
    r.note(cx.where(*it), fmt::format("{} for tool {} here has no effect", c.letter == 'G' ? "G10" : "M568", n));
    ++notes;
  }
}

// The first extruder number at or above `extruders` (one that does not exist), or -1.
int64_t first_beyond(const std::vector<int64_t>& numbers, int extruders) {
  auto it = std::find_if(numbers.begin(), numbers.end(), [&](int64_t d) { return d >= extruders; });
  return it == numbers.end() ? -1 : *it;
}

void check_m563(const NodeContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  auto D = get_int_list(pf, c, 'D');
  if (!D.known() || !pf.find(c, 'P')) return;
  const int64_t bad = first_beyond(D.value, s.extruders);
  if (bad < 0 || runs_again_later(cx)) return;
  auto P = get_int(pf, c, 'P');
  const bool n_known = P.known() && P.value >= 0;
  const int n = n_known ? static_cast<int>(P.value) : -1;
  std::string tool = n_known ? fmt::format("tool {}", n) : std::string("the tool");
  std::string deleted = n_known && s.tool(n) ? fmt::format(", and the existing tool {} is deleted", n) : "";
  Report r = out.report(kMeta, cx.at(D.param->span),
                        fmt::format("{} names extruder {}, but {}: RRF answers 'bad drive number' and {} is not "
                                    "created{}",
                                    tools::quote(pf, c), bad, extruders_here(s.extruders), tool, deleted));
  note_m584_e(cx, r);
  if (n_known) note_tool_uses(cx, r, n);
}

void check_e_values(const NodeContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  ParamRef e = pf.find(c, 'E');
  if (!e || e->kind == ValueKind::None || is_unknown_value(*e)) return;
  if (e->kind != ValueKind::Number && e->kind != ValueKind::List) return;
  const size_t count = list_items(pf, *e).size();
  if (count <= static_cast<size_t>(s.extruders) || runs_again_later(cx)) return;
  const std::string answer = s.firmware >= kRrf3_5_2 ? std::string("array too long for parameter 'E'")
                                                     : fmt::format("array too long, max length = {}", s.extruders);
  std::string what = count == 1 ? "an extruder value" : fmt::format("{} extruder values", count);
  Report r = out.report(kMeta, cx.at(e->span),
                        fmt::format("{} gives {}, but {}: RRF answers '{}' and the E values are lost",
                                    tools::quote(pf, c), what, extruders_here(s.extruders), answer));
  note_m584_e(cx, r);
}

void check_d(const NodeContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (c.number == 572 && !pf.find(c, 'S')) return;  // without S, M572 only reports
  auto D = get_int_list(pf, c, 'D');
  if (!D.known() || D.value.empty()) return;
  if (c.number != 572) D.value.erase(D.value.begin() + 1, D.value.end());  // M591/M221 read one number
  const int64_t bad = first_beyond(D.value, s.extruders);
  if (bad < 0 || runs_again_later(cx)) return;
  const std::string answer =
      c.number == 572 ? fmt::format("Invalid extruder number '{}'", bad) : std::string("parameter 'D' too high");
  Report r = out.report(kMeta, cx.at(D.param->span),
                        fmt::format("{} names extruder {}, but {}: RRF answers '{}'", tools::quote(pf, c), bad,
                                    extruders_here(s.extruders), answer));
  note_m584_e(cx, r);
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command() || !cx.certain()) return;
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_3 || !s.extruders_known || s.unknown_baseline) return;
  const Command& c = cx.command();
  if (c.letter != 'M' || c.fraction >= 0) return;
  switch (c.number) {
    case 563: check_m563(cx, out); break;
    case 92:
    case 201:
    case 203:
    case 205:
    case 350:
    case 566:
    case 906:
    case 913:
    case 917: check_e_values(cx, out); break;
    case 572:
    case 591:
    case 221: check_d(cx, out); break;
    default: break;
  }
}

}  // namespace

extern const Rule extruder_before_creation{
    .meta = kMeta, .check_node = check, .on = "M563 M92 M201 M203 M205 M350 M566 M906 M913 M917 M572 M591 M221"};

}  // namespace rrflint
