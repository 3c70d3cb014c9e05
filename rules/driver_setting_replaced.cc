// RRF219 driver-setting-replaced: a second M569 for the same driver sets one of its settings (direction, enable
// polarity, mode, chopper timings) to another value before any move: the first value never takes effect.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF219",
    .name = "driver-setting-replaced",
    .severity = Severity::Warning,
    .summary =
        "A second M569 for the same driver gives one of its settings another value before any move: the "
        "first never takes effect.",
    .docs = R"md(
## What it does
Reports an `M569 P<driver>` that sets a setting of a driver to a different value than an earlier `M569` for the
same driver set it, with no move (`G0`–`G3`, `G28`–`G32`) between the two: the direction `S`, the enable polarity
`R`, the step timings `T`, the mode `D`, the chopper control register `C`, the off time `F`, the blanking time
`B`, the thresholds `V` and `H` and the hysteresis `Y`. A note points at the earlier `M569`, and the message
names the drivers the axes and extruders use that no `M569` configures: a copy-paste slip usually leaves one.
`P1` and `P0.1` are the same driver on the main board.

It stays silent when the two give the same value (`S1` and `S2` are both forwards), when they set different
settings (`M569 P0 S1` then `M569 P0 D3`), on drivers and values it cannot know (`{…}`, a list of drivers),
when either `M569` may not run (inside an `if` or a loop, in a tool-change macro), when an `M569` for an unknown
driver comes between, inside config-override.g, and on a macro linted on its own.

## Why is this bad?
`M569` writes each setting it is given into the driver and keeps the others. Two lines for one driver leave
only the last value of each setting, and nothing tells: the first line has no effect. When the two disagree, one
of them was usually meant for another driver, copied from the line above with its `P` left unchanged: the
direction of that other motor is never set, and it runs the wrong way (user reports: a MULDEX config with
`M569 P1 S0 ; X` followed by `M569 P1 S1 ; Y`, fixed days later).

## Example
```gcode
; rrflint-options: --firmware 3.5
M584 X0 Y1 Z2 E3
M569 P1 S0 ; X
M569 P1 S1 ; Y
```

## Use instead
```gcode
; rrflint-options: --firmware 3.5
M584 X0 Y1 Z2 E3
M569 P0 S0 ; X
M569 P1 S1 ; Y
```

## Fix safety
There is no fix: only the author knows which driver each line was meant for.

## References
- rrflint: [M569 per driver](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M569](https://docs.duet3d.com/User_manual/Reference/Gcodes#m569-set-motor-driver-direction-enable-polarity-mode-and-step-pulse-timing)
- RepRapFirmware 3.5: [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes3.cpp) (`ConfigureDriver()`, `ConfigureLocalDriverBasicParameters()`: each parameter given is written, the others kept)
)md",
};

/// The settings M569 writes (ConfigureLocalDriverBasicParameters), in the order the message lists them.
struct Setting {
  char letter;
  const char* name;
  bool list;  // a colon list (T, Y); else one integer
};
constexpr Setting kSettings[] = {
    {'S', "direction", false},     {'R', "enable polarity", false},       {'T', "step timings", true},
    {'D', "mode", false},          {'C', "chopper control", false},       {'F', "off time", false},
    {'B', "blanking time", false}, {'V', "stealthChop threshold", false}, {'H', "high-speed threshold", false},
    {'Y', "hysteresis", true}};

/// The one driver an M569 configures; nullopt when P is absent, unknown, bad or a list of several.
std::optional<DriverId> driver_of(const ParsedFile& pf, const Command& c) {
  const auto P = get_driver_list(pf, c, 'P');
  if (!P.known() || P.value.size() != 1) return std::nullopt;
  return P.value[0];
}

/// The value a setting is given, as RRF stores it: S as forwards or not, T and Y as lists; nullopt when the
/// parameter is absent or not known.
std::optional<std::vector<double>> value_of(const ParsedFile& pf, const Command& c, const Setting& s) {
  if (s.list) {
    const auto v = get_float_list(pf, c, s.letter);
    return v.known() ? std::optional(v.value) : std::nullopt;
  }
  const auto v = get_int(pf, c, s.letter);
  if (!v.known()) return std::nullopt;
  return std::vector<double>{s.letter == 'S' ? (v.value != 0 ? 1.0 : 0.0) : static_cast<double>(v.value)};
}

std::string shown(const Setting& s, const std::vector<double>& v) {
  if (s.letter == 'S') return v[0] != 0 ? "S1 (forwards)" : "S0 (backwards)";
  std::string out(1, s.letter);
  for (size_t i = 0; i < v.size(); ++i) out += fmt::format("{}{:g}", i ? ":" : "", v[i]);
  return out;
}

/// unconfigured(), worked out for the segment [begin, end).
std::vector<std::string> unconfigured_in(const NodeContext& cx, NodeId begin, NodeId end) {
  std::vector<DriverId> configured;
  bool unknown = false;
  tools::each_code_node(cx, begin, end, 'M', 569, [&](NodeId id, const tools::NodeCommand& k) {
    const auto P = get_driver_list(*k.pf, *k.c, 'P');
    // A list configures its first driver only (RRF220 m569-driver-list).
    if (P.known() && !P.value.empty()) configured.push_back(P.value[0]);
    unknown |= P.unknown() || cx.graph.nodes[id].maybe;
    return unknown;
  });
  constexpr std::string_view kLetters = "XYZUVWABCDE";
  std::vector<std::vector<DriverId>> used(kLetters.size());
  for (size_t i = 0; i < 3; ++i) used[i] = {DriverId{0, static_cast<uint16_t>(i), false}};
  tools::each_code_node(cx, begin, end, 'M', 584, [&](NodeId id, const tools::NodeCommand& k) {
    unknown |= cx.graph.nodes[id].maybe;
    for (size_t i = 0; i < kLetters.size() && !unknown; ++i) {
      const auto L = get_driver_list(*k.pf, *k.c, kLetters[i]);
      if (L.known()) used[i] = L.value;
      unknown |= L.unknown();
    }
    return unknown;
  });
  std::vector<std::string> out;
  if (unknown) return out;
  for (size_t i = 0; i < kLetters.size(); ++i)
    for (size_t n = 0; n < used[i].size(); ++n) {
      const DriverId d = used[i][n];
      if (std::find(configured.begin(), configured.end(), d) != configured.end()) continue;
      out.push_back(
          fmt::format("{} ({})", d.str(), kLetters[i] == 'E' ? fmt::format("E{}", n) : std::string(1, kLetters[i])));
      configured.push_back(d);  // named once
    }
  return out;
}

/// For each M569 of the graph that configures one known driver, the M569 before it that a look back stops at: the
/// last earlier one that names the same driver (alone or in a list) or an unknown one; kNoNode when none. Built once
/// per graph (Graph::derived): a look back from each M569 would cost the square of their number on a config of
/// thousands of drivers.
struct M569Index {
  std::vector<NodeId> ids;   // the M569 nodes with one known driver, in order
  std::vector<NodeId> stop;  // for each: where the look back stops
};

const M569Index& m569_index(const NodeContext& cx) {
  return cx.graph.derived<M569Index>("driver_setting_replaced.m569", [&] {
    M569Index out;
    std::map<std::pair<uint16_t, uint16_t>, NodeId> last;
    NodeId last_unknown = kNoNode;
    auto later = [](NodeId a, NodeId b) { return a == kNoNode ? b : b == kNoNode ? a : std::max(a, b); };
    tools::each_code_node(cx, 0, cx.graph.nodes.size(), 'M', 569, [&](NodeId id, const tools::NodeCommand& k) {
      const auto P = get_driver_list(*k.pf, *k.c, 'P');
      if (P.unknown()) last_unknown = id;
      if (!P.known()) return false;
      if (P.value.size() == 1) {
        const auto it = last.find({P.value[0].board, P.value[0].driver});
        out.ids.push_back(id);
        out.stop.push_back(later(it == last.end() ? kNoNode : it->second, last_unknown));
      }
      for (const DriverId d : P.value) last[{d.board, d.driver}] = id;
      return false;
    });
    return out;
  });
}

/// The drivers that the axes and extruders of a segment's M584s use (X, Y and Z default to 0, 1 and 2) and that
/// no M569 of the segment configures (one with a list configures its first driver only), as "0 (X)"; empty when an
/// M584 or M569 may not run or names an unknown one. Built once per segment.
const std::vector<std::string>& unconfigured(const NodeContext& cx) {
  const NodeId begin = cx.segment().begin, end = cx.segment().end;
  return cx.graph.derived<std::vector<std::string>>(fmt::format("driver_setting_replaced.unconfigured.{}", begin),
                                                    [&] { return unconfigured_in(cx, begin, end); });
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 569)) return;
  const MachineState& s = cx.state;
  if (s.unknown_baseline || !tools::certain_at_boot(cx.graph, cx.id) || heat::judged_elsewhere(cx)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const std::optional<DriverId> driver = driver_of(pf, c);
  if (!driver) return;
  // The last earlier M569 of this segment for this driver; none when one for an unknown driver, for a list of
  // drivers, or one that may not run, comes first.
  const M569Index& index = m569_index(cx);
  const auto it = std::lower_bound(index.ids.begin(), index.ids.end(), cx.id);
  if (it == index.ids.end() || *it != cx.id) return;
  const NodeId prev = index.stop[static_cast<size_t>(it - index.ids.begin())];
  if (prev == kNoNode || prev < cx.segment().begin || !tools::certain_at_boot(cx.graph, prev) ||
      heat::judged_elsewhere(cx.machine, cx.graph, prev))
    return;
  const tools::NodeCommand k = tools::command_at(cx.machine, cx.graph, prev);
  if (driver_of(*k.pf, *k.c) != driver) return;  // a list of drivers, or an unknown one
  // A move between uses the first value.
  for (const int g : {0, 1, 2, 3, 28, 29, 30, 32})
    if (tools::each_code_node(cx, prev + 1, cx.id, 'G', g, [](NodeId, const tools::NodeCommand&) { return true; }) !=
        kNoNode)
      return;
  std::vector<std::string> changes;
  ParamRef at;
  for (const Setting& st : kSettings) {
    const auto now = value_of(pf, c, st), before = value_of(*k.pf, *k.c, st);
    if (!now || !before || *now == *before) continue;
    changes.push_back(fmt::format("{} {} replaces {}", st.name, shown(st, *now), shown(st, *before)));
    if (!at) at = pf.find(c, st.letter);
  }
  if (changes.empty()) return;
  std::string what = changes[0];
  for (size_t i = 1; i < changes.size(); ++i) what += "; " + changes[i];
  const std::vector<std::string>& missing = unconfigured(cx);
  std::string hint;
  if (!missing.empty()) {
    hint = missing[0];
    for (size_t i = 1; i < missing.size() && i < 4; ++i) hint += ", " + missing[i];
    if (missing.size() > 4) hint += ", …";
    hint = fmt::format("; was one of them meant for driver{} {}, which no M569 configures?",
                       missing.size() == 1 ? "" : "s", hint);
  }
  out.report(kMeta, cx.at(at->span),
             fmt::format("{} configures driver {} again before any move: {}; the earlier value{} (from {}) never "
                         "take{} effect{}",
                         tools::quote(pf, c), driver->str(), what, changes.size() == 1 ? "" : "s",
                         tools::quote(*k.pf, *k.c), changes.size() == 1 ? "s" : "", hint))
      .note(cx.where(prev), fmt::format("driver {} is configured here first", driver->str()));
}

}  // namespace

extern const Rule driver_setting_replaced{.meta = kMeta, .check_node = check, .on = "M569"};

}  // namespace rrflint
