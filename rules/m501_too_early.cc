// RRF401 m501-too-early: M501 runs config-override.g before the commands its lines depend on.
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"
#include "rules/override_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF401",
    .name = "m501-too-early",
    .severity = Severity::Warning,
    .summary =
        "M501 runs config-override.g before config.g creates the heaters, tools, axes or probes its lines "
        "name: those lines fail or are ignored.",
    .docs = R"md(
## What it does
Reports an `M501` in the boot sequence when config-override.g, run at that point, names something that config.g
creates only after it. One finding at the M501, with a note at each line of config-override.g that then fails or
is ignored, and a note at each later command that creates what the line needed:
- `M307`, `M301`, `M570`, `M143 H<n>` for a heater whose `M950 H<n>` comes after the M501 (RRF 3);
- `G10 P<n>` (tool offsets) for a tool whose `M563 P<n>` comes after it;
- axis letters in `G10 L2`, `G10 P<n>`, `M208` and `G31` lines for axes that a later `M584` creates;
- `G31 K<n>` when an `M558 K<n>` that creates the probe comes after it (a new probe starts from its defaults).

It stays silent when the card has no config-override.g, on unknown values (`{…}`) in either command, when the
later creation is inside an `if` or a loop (it may not run), for an M501 in an `if`, in a tool-change macro, and
for a line whose heater, tool or axis nothing creates (a file saved by an older config). The file loaded with
`M98` instead is [override-via-m98](override-via-m98.md)'s finding. The override's own lines
are judged only here: heater-before-creation (RRF205), g10-tool-before-definition (RRF301) and
axis-before-creation (RRF201) leave them to this rule.

## Why is this bad?
M501 runs config-override.g as a macro, there and then, in the machine state of that moment. The file holds the
values M500 saved after tuning (heater models, probed tool offsets, workplaces, probe offsets). Any of its lines
that names a heater or tool not created yet fails (`Heater 1 not found`, `Invalid tool number`), an axis letter not
created yet is ignored without a message, and a probe created later starts again from its defaults: the machine
boots with untuned values, and the next `M500` writes them back. The documentation says to put M501 at the end of
config.g.

## Example
```gcode
M501
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M563 P0 D0 H1
; file: sys/config-override.g
M307 H1 R2.43 K0.56:0.00 D5.50 E1.35 S1.00 B0 V24.0
G10 P0 X22.340 Y41.620 Z-12.240
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M563 P0 D0 H1
M501
; file: sys/config-override.g
M307 H1 R2.43 K0.56:0.00 D5.50 E1.35 S1.00 B0 V24.0
G10 P0 X22.340 Y41.620 Z-12.240
```

## Fix safety
There is no fix: moving the M501 past the commands after it also makes their values lose to the saved ones, which
is usually what is meant but is the user's choice (see [override-after-m501](override-after-m501.md)).

## References
- rrflint: [Saved settings: M500, M501, M502](../firmware-behaviour.md#saved-settings-m500-m501-m502)
- Duet3D G-code dictionary: [M501](https://docs.duet3d.com/User_manual/Reference/Gcodes#m501-read-stored-parameters) ("Ensure that M501 is at the end of config.g")
- RepRapFirmware 3.5: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes2.cpp) (case 501), [EndstopsManager.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Endstops/EndstopsManager.cpp) (`HandleM558()` creates a new probe when P or C is given)
)md",
};

using override_file::Run;

/// A line of config-override.g that fails or is ignored at the M501, why, and the later command it needed.
struct Lost {
  NodeId line = kNoNode;
  std::string why;
  NodeId creator = kNoNode;
  std::string created;  // "heater 1", "tool 0", "axis U", "probe 0"
};

enum class Match : uint8_t { No, Yes, Unknown };

/// The first command after the run, in the boot segment, with code `letter` `number` that creates what the line
/// needs (pred says Yes); kNoNode when there is none, when it runs only maybe (in an if), or when one on the way may
/// create it (pred says Unknown: an expression).
template <class Pred>
NodeId later(const NodeContext& cx, const Run& run, char letter, int number, Pred pred) {
  Match m = Match::No;
  // Only the commands of that code (the code index): each line of a long config-override.g walked every node after
  // the M501.
  const NodeId id = tools::each_code_node(cx, run.leave + 1, cx.segment().end, letter, number,
                                          [&](NodeId, const tools::NodeCommand& k) {
                                            m = pred(k);
                                            if (m != Match::No && k.node.maybe) m = Match::Unknown;
                                            return m != Match::No;
                                          });
  return m == Match::Yes ? id : kNoNode;
}

/// Does this command's `letter` name device n? Unknown for an expression.
Match names(const tools::NodeCommand& k, char letter, int n, int absent = -1) {
  auto v = get_int(*k.pf, *k.c, letter);
  if (v.unknown()) return Match::Unknown;
  const int64_t got = v.known() ? v.value : absent;
  return v.present() || absent >= 0 ? (got == n ? Match::Yes : Match::No) : Match::No;
}

std::optional<Lost> heater_line(const NodeContext& cx, const Run& run, const tools::NodeCommand& k) {
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || !s.heaters_known) return std::nullopt;
  const heat::DeviceRef h = heat::heater_named(*k.pf, *k.c);
  if (!h.known || s.heaters.count(h.number)) return std::nullopt;
  const NodeId c = later(cx, run, 'M', 950, [&](const tools::NodeCommand& m) {
    const Match r = names(m, 'H', h.number);
    return r == Match::Yes && !m.pf->find(*m.c, 'C') ? Match::No : r;
  });
  if (c == kNoNode) return std::nullopt;
  return Lost{kNoNode,
              fmt::format("fails: heater {} does not exist yet ('Heater {} {}')", h.number, h.number,
                          k.c->number == 143 ? "does not exist" : "not found"),
              c, fmt::format("heater {}", h.number)};
}

std::optional<Lost> tool_line(const NodeContext& cx, const Run& run, const tools::NodeCommand& k) {
  const MachineState& s = cx.state;
  auto P = get_int(*k.pf, *k.c, 'P');
  if (!P.known() || P.value < 0) return std::nullopt;
  const int n = static_cast<int>(P.value);
  if (!s.tool_certainly_absent(n) || s.failed_tools.count(n)) return std::nullopt;
  const NodeId c = later(cx, run, 'M', 563, [&](const tools::NodeCommand& m) {
    return m563_defines(*m.pf, *m.c) ? names(m, 'P', n) : Match::No;
  });
  if (c == kNoNode) return std::nullopt;
  return Lost{kNoNode,
              fmt::format("fails: tool {} is defined only later ('{}'), so its offsets are not set", n,
                          tools::invalid_tool_text(s.firmware, n)),
              c, fmt::format("tool {}", n)};
}

std::optional<Lost> axis_line(const NodeContext& cx, const Run& run, const tools::NodeCommand& k) {
  const MachineState& s = cx.state;
  if (!tools::axes_certain(s)) return std::nullopt;
  std::string letters;
  NodeId first = kNoNode;
  for (const Param& p : k.pf->params(*k.c)) {
    if (!tools::is_axis_letter(p.letter, s) || s.axis_index(p.letter) >= 0) continue;
    if (k.is('G', 31) && p.letter == 'C' && s.firmware < kRrf3_3) continue;  // the temperature coefficient
    if (letters.find(p.letter) != std::string::npos) continue;
    const NodeId c = later(cx, run, 'M', 584, [&](const tools::NodeCommand& m) {
      return m.pf->find(*m.c, p.letter) ? Match::Yes : Match::No;
    });
    if (c == kNoNode) continue;
    if (first == kNoNode) first = c;
    letters += p.letter;
  }
  if (letters.empty()) return std::nullopt;
  const std::string list = override_file::letter_list(letters);
  return Lost{kNoNode,
              letters.size() == 1 ? fmt::format("names {}, which is ignored: axis {} does not exist yet", list, list)
                                  : fmt::format("names {}, which are ignored: those axes do not exist yet", list),
              first, fmt::format("{} {}", letters.size() == 1 ? "axis" : "axes", list)};
}

std::optional<Lost> probe_line(const NodeContext& cx, const Run& run, const tools::NodeCommand& k) {
  auto K = get_int(*k.pf, *k.c, 'K');
  if (K.unknown()) return std::nullopt;
  const int n = K.known() ? static_cast<int>(K.value) : 0;
  const NodeId c = later(cx, run, 'M', 558, [&](const tools::NodeCommand& m) {
    if (!m.pf->find(*m.c, 'P') && !m.pf->find(*m.c, 'C')) return Match::No;  // configures, does not create
    return names(m, 'K', n, 0);
  });
  if (c == kNoNode) return std::nullopt;
  return Lost{kNoNode,
              fmt::format("is lost: the M558 that creates probe {} comes later, and a new probe starts with the "
                          "default trigger height and offsets",
                          n),
              c, fmt::format("probe {}", n)};
}

/// What happens to this line of config-override.g when it runs at the M501; nullopt when it works.
std::optional<Lost> judge(const NodeContext& cx, const Run& run, NodeId id, const tools::NodeCommand& k) {
  std::optional<Lost> l;
  if (k.is('M', 307) || k.is('M', 301) || k.is('M', 570) || k.is('M', 143)) l = heater_line(cx, run, k);
  if (k.is('G', 31)) l = probe_line(cx, run, k);
  if (k.is('G', 31) && !l) l = axis_line(cx, run, k);
  if (k.is('G', 10) || k.is('M', 208)) {
    const G10Form f = k.is('G', 10) ? g10_form(*k.pf, *k.c, &cx.state, cx.state.firmware) : G10Form::Workplace;
    if (is_tool_form(f)) l = tool_line(cx, run, k);
    if (!l && (f == G10Form::Workplace || is_tool_form(f))) l = axis_line(cx, run, k);
  }
  if (l) l->line = id;
  return l;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 501) || !cx.certain() || !cx.in_boot()) return;
  if (cx.state.running_m501 || cx.state.unknown_baseline || tools::in_tool_macro(cx.graph, cx.id)) return;
  const std::optional<Run> run = override_file::run_of(cx.graph, cx.id);
  if (!run) return;
  std::vector<Lost> lost;
  cx.graph.nodes.find_if(run->enter + 1, run->leave, [&](NodeId id, const Node& n) {
    const tools::NodeCommand k = tools::command_at(cx.machine, n);
    if (k && !n.maybe)
      if (auto l = judge(cx, *run, id, k)) lost.push_back(std::move(*l));
    return false;
  });
  if (lost.empty()) return;
  std::vector<std::pair<NodeId, std::string>> creators;
  for (const Lost& l : lost)
    if (std::none_of(creators.begin(), creators.end(), [&](const auto& c) { return c.second == l.created; }))
      creators.emplace_back(l.creator, l.created);
  std::sort(creators.begin(), creators.end());
  std::string what;
  for (size_t i = 0; i < creators.size(); ++i)
    what += (i == 0 ? "" : i + 1 == creators.size() ? " and " : ", ") + creators[i].second;
  Report r =
      out.report(kMeta, cx.at(cx.command().span),
                 fmt::format("M501 runs config-override.g before config.g creates {}: {} ignored; move the M501 to "
                             "the end of config.g",
                             what,
                             lost.size() == 1 ? std::string("one of its lines fails or is")
                                              : fmt::format("{} of its lines fail or are", lost.size())));
  for (const Lost& l : lost) {
    const tools::NodeCommand k = tools::command_at(cx.machine, cx.graph, l.line);
    r.note(cx.where(l.line), fmt::format("{} {}", tools::quote(*k.pf, *k.c), l.why));
  }
  for (const auto& [node, name] : creators) r.note(cx.where(node), fmt::format("{} is created here", name));
}

}  // namespace

extern const Rule m501_too_early{.meta = kMeta, .check_node = check, .on = "M501"};

}  // namespace rrflint
