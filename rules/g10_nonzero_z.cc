// RRF305 g10-nonzero-z: tools on one carriage that end the boot sequence with different Z offsets.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "lint/engine/linter.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF305",
    .name = "g10-nonzero-z",
    .severity = Severity::Warning,
    .summary = "Two or more tools on one carriage end up with different Z offsets.",
    .docs = R"md(
## What it does
Looks at the tools as they stand at the end of the boot sequence and reports tools that share one carriage but
have **different** Z offsets. The finding sits at the G10 that gave one tool its Z offset, with notes at the
other tools' G10s (or M563s, for a Z that was never set).

Tools "share a carriage" when they have the same X, Y and Z maps and the machine shows no sign of being a tool
changer. Not counted:
- spindle and laser tools: tools with `R`, tools with no `D`, and any tool on a machine in CNC or laser mode
  (`M453`/`M452`), where Z offsets are tool lengths;
- tools that share their whole heater set: virtual tools on one nozzle (mixing, MMU/ERCF filament slots)
  cannot collide with each other;
- tools whose Z offset is unknown (expression, inside an `if`) or that were created inside an `if`.

Equal offsets cause no collision, and a single tool never fires.

Tool-changer evidence turns the rule off for the machine:
- a tool-change macro (`tfree*.g`, `tpre*.g`, `tpost*.g`) that moves an axis (`G0`–`G3` with an axis letter,
  `G28`, `G30`, `G38.n`, `G53`), calls a macro (`M98`, e.g. a coupler macro) or drives a servo or output
  (`M280`, `M42`). Macros holding only temperature waits or fan commands do not count: the Duet config tool
  writes those for every tool;
- an M563 with a `Z` map (3.5 and later);
- the option `--tool-changer` (`machine.tool-changer = true` in the config file).

When the rule fires, a note says that none of this evidence was found.

## Why is this bad?
A tool offset in Z moves the bed (or the head) so that the active nozzle prints at the right height. On a
carriage with two nozzles, the Z offsets can only differ if one nozzle hangs lower than the other, and then
the lower nozzle drags through the print while the upper one prints. Usually the different Z values are left
over from a tool changer config, or typed for the wrong tool.

## Example
```gcode
M584 X0 Y1 Z2 E3:4
M563 P0 D0 H1
M563 P1 D1 H2
G10 P0 X0 Y0 Z0
G10 P1 X18 Y0 Z-0.6
```

## Use instead
Level the nozzles mechanically and give both tools the same Z offset:
```gcode
G10 P0 X0 Y0 Z0
G10 P1 X18 Y0 Z0
```
On a real tool changer, declare it with `--tool-changer` (or `machine.tool-changer = true`).

## References
- rrflint: [Tool offsets and axis mapping](../firmware-behaviour.md#tool-offsets-and-axis-mapping), [T tool selection](../firmware-behaviour.md#t-tool-selection)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset) ("you want explicitly to set Z0.0")
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`ToolOffsetTransform()`)
)md",
};

/// Does this tool-change macro show tool-changer work (moves, macro calls, servos)?
bool changes_tools(const ParsedFile& pf, const MachineState& s) {
  for (const Command& c : pf.commands) {
    if (c.letter == 'G') {
      if (c.number == 28 || c.number == 30 || c.number == 38 || c.number == 53) return true;
      if (c.number >= 0 && c.number <= 3)
        for (const Param& p : pf.params(c))
          if (tools::is_axis_letter(p.letter, s)) return true;
    } else if (c.letter == 'M' && (c.number == 98 || c.number == 280 || c.number == 42)) {
      return true;
    }
  }
  return false;
}

bool tool_changer_evidence(const EndContext& cx) {
  const MachineState& s = cx.end_of_boot;
  if (cx.options.tool_changer) return true;
  for (const auto& [n, t] : s.tools)
    if (t.zmap.origin != kNoNode) return true;
  for (uint32_t i = 0; i < cx.machine.unit_count(); ++i) {
    const FileUnit& u = cx.machine.unit(i);
    if (is_tool_change_role(file_role(u.sd_path)) && changes_tools(u.parsed, s)) return true;
  }
  return false;
}

std::string format_z(double z) { return fmt::format("{:g}", z); }

/// Of the tools of one carriage, those whose Z differs from that of a tool with another heater set: a tool with
/// heater set h is one when the lowest or the highest Z among the tools of the other sets is 1e-9 or more away from
/// its own. From the extremes of each set, not from every pair of tools (quadratic on a config of thousands of tools
/// with the same heaters).
std::vector<const Tool*> involved_tools(const std::vector<const Tool*>& tools, int z) {
  auto zof = [z](const Tool* t) { return t->offsets[static_cast<size_t>(z)].value; };
  std::map<std::vector<int64_t>, std::pair<double, double>> extremes;  // sorted heater set -> lowest, highest Z
  std::vector<const std::vector<int64_t>*> set_of;                     // each tool's heater set
  for (const Tool* t : tools) {
    std::vector<int64_t> h = t->heaters;
    std::sort(h.begin(), h.end());
    auto [it, fresh] = extremes.try_emplace(std::move(h), zof(t), zof(t));
    it->second = {std::min(it->second.first, zof(t)), std::max(it->second.second, zof(t))};
    set_of.push_back(&it->first);
  }
  // The lowest and highest Z of all the sets, with the set that holds each, and the lowest and highest of the
  // other sets: what "the other sets" have, for a tool of that set and for any other.
  const std::vector<int64_t>*low_set = nullptr, *high_set = nullptr;
  double low = 0, high = 0;
  double low2 = std::numeric_limits<double>::infinity(), high2 = -std::numeric_limits<double>::infinity();
  for (const auto& [h, e] : extremes) {
    if (!low_set) {
      low = e.first, high = e.second;
      low_set = high_set = &h;
      continue;
    }
    if (e.first < low) low2 = low, low = e.first, low_set = &h;
    else low2 = std::min(low2, e.first);
    if (e.second > high) high2 = high, high = e.second, high_set = &h;
    else high2 = std::max(high2, e.second);
  }
  std::vector<const Tool*> involved;
  const bool finite = std::all_of(tools.begin(), tools.end(), [&](const Tool* t) { return std::isfinite(zof(t)); });
  for (size_t i = 0; i < tools.size() && extremes.size() >= 2; ++i) {
    const Tool* a = tools[i];
    if (finite) {
      const double lo = set_of[i] == low_set ? low2 : low, hi = set_of[i] == high_set ? high2 : high;
      if (hi - zof(a) >= 1e-9 || zof(a) - lo >= 1e-9) involved.push_back(a);
      continue;
    }
    // An infinite Z (`Z1e999`): every pair, as the extremes cannot say what |a - b| makes of it.
    for (size_t j = 0; j < tools.size(); ++j)
      if (set_of[j] != set_of[i] && !(std::abs(zof(a) - zof(tools[j])) < 1e-9)) {
        involved.push_back(a);
        break;
      }
  }
  return involved;
}

void check(const EndContext& cx, Sink& out) {
  const MachineState& s = cx.end_of_boot;
  if (!s.tools_known || s.unknown_baseline || s.mode != MachineMode::FFF || s.tools.size() < 2) return;
  const int z = s.axis_index('Z');
  if (z < 0 || z >= kMaxAxisSlots) return;

  // Tools that count, grouped by their axis maps (one group = one carriage).
  using Key = std::tuple<uint32_t, uint32_t, uint32_t>;
  std::map<Key, std::vector<const Tool*>> groups;
  for (const auto& [n, t] : s.tools) {
    if (t.maybe || t.spindle || !t.has_d || !t.drives_known || t.drives.empty() || !t.heaters_known) continue;
    if (!t.xmap.known || !t.ymap.known || !t.zmap.known) continue;
    if (!t.offsets[static_cast<size_t>(z)].known) continue;
    groups[Key{t.xmap.bits, t.ymap.bits, t.zmap.bits}].push_back(&t);
  }
  bool checked_evidence = false;
  for (auto& [key, tools] : groups) {
    if (tools.size() < 2) continue;
    const std::vector<const Tool*> involved = involved_tools(tools, z);
    if (involved.size() < 2) continue;
    if (!checked_evidence) {
      if (tool_changer_evidence(cx)) return;
      checked_evidence = true;
    }
    // The finding sits at the Z of the first tool with a non-zero offset that a command set.
    const Tool* primary = nullptr;
    for (const Tool* t : involved)
      if (t->offsets[static_cast<size_t>(z)].value != 0 && t->offsets[static_cast<size_t>(z)].origin != kNoNode) {
        primary = t;
        break;
      }
    if (!primary) continue;
    std::string numbers, values;
    for (size_t i = 0; i < involved.size(); ++i) {
      const char* sep = i == 0 ? "" : (i + 1 == involved.size() ? " and " : ", ");
      numbers += sep + std::to_string(involved[i]->number);
      values += (i == 0 ? "" : ", ") + format_z(involved[i]->offsets[static_cast<size_t>(z)].value);
    }
    const Fact& pz = primary->offsets[static_cast<size_t>(z)];
    Report r = out.report(kMeta, cx.where(pz.origin),
                          fmt::format("tools {} share one carriage but end up with different Z offsets ({}): the "
                                      "lower nozzle can hit the print while the other one prints",
                                      numbers, values));
    for (const Tool* t : involved) {
      if (t == primary) continue;
      const Fact& f = t->offsets[static_cast<size_t>(z)];
      if (f.origin != kNoNode)
        r.note(cx.where(f.origin), fmt::format("tool {} gets Z offset {} here", t->number, format_z(f.value)));
      else if (t->created != kNoNode)
        r.note(cx.where(t->created), fmt::format("tool {} is created here and keeps Z offset 0", t->number));
    }
    r.note(cx.where(primary->created),
           fmt::format("tool {} is defined here with the same axis maps as the others, and there is no tool-changer "
                       "evidence: no tool-change macro moves an axis or calls a macro, no M563 maps Z, and "
                       "--tool-changer is not set",
                       primary->number));
  }
}

}  // namespace

extern const Rule g10_nonzero_z{.meta = kMeta, .check_end = check};

}  // namespace rrflint
