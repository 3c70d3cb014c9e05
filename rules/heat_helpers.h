// Helpers shared by the device order rules (RRF205–RRF211): which heater, fan or probe a command names, the later
// M950/M308 that creates a device, and the nodes run since a creation. What each command means (its default heater,
// which letter names the device) follows docs/firmware-behaviour.md#heaters-and-their-monitors.
#pragma once

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint::heat {

/// A device number a command names: known, absent (the command names none), or unknown (an expression).
struct DeviceRef {
  int number = -1;
  bool known = false;
};

/// The heater that M307/M570 (H required), M301/M143 (no H: heater 1) names.
inline DeviceRef heater_named(const ParsedFile& pf, const Command& c) {
  auto H = get_int(pf, c, 'H');
  if (H.known()) return {static_cast<int>(H.value), H.value >= 0};
  if (H.absent() && (c.number == 301 || c.number == 143)) return {1, true};
  return {};  // unknown, or M307/M570 without H (RRF answers "missing parameter 'H'")
}

/// Does this M563/M140/M141 name heater h in its H list (or may it: an expression)? Those install the defaults.
inline bool names_heater(const tools::NodeCommand& k, int h) {
  if (!k.is('M', 563) && !k.is('M', 140) && !k.is('M', 141)) return false;
  auto H = get_int_list(*k.pf, *k.c, 'H');
  if (!H.known()) return H.unknown();
  return std::find(H.value.begin(), H.value.end(), h) != H.value.end();
}

/// The later M563/M140/M141 in this segment after `from` that names heater h in its H list (names_heater), or may;
/// kNoNode if none. From indexes built once per graph.
inline NodeId later_installing_defaults(const NodeContext& cx, NodeId from, int h) {
  NodeId first = kNoNode;
  for (const int code : {563, 140, 141}) {
    const tools::DeviceIndex& lists =
        cx.graph.derived<tools::DeviceIndex>("heat.h_lists.M" + std::to_string(code), [&] {
          tools::DeviceIndex out;
          tools::each_code_command(cx.machine, cx.graph, 'M', code,
                                   [&](NodeId id, const Node&, const ParsedFile& pf, const Command& c) {
                                     auto H = get_int_list(pf, c, 'H');
                                     if (H.unknown()) out.add(id, false, 0);
                                     if (!H.known()) return;
                                     for (const int64_t v : H.value)
                                       if (out.known.count(v) == 0 || out.known[v].back() != id) out.add(id, true, v);
                                   });
          return out;
        });
    first = std::min(first, lists.first_after(from, cx.segment().end, h));
  }
  return first;
}

/// Is this node judged by other rules? Lines of config-override.g (at the M501 they are RRF401's notes; unloaded,
/// RRF404's). No finding stands in resurrect.g at all (the engine drops them: docs/firmware-behaviour.md#system-files).
inline bool judged_elsewhere(const Machine& m, const Graph& g, NodeId id) {
  return file_role(m.unit(g.nodes[id].unit).sd_path) == FileRole::ConfigOverride || tools::inside_m501(g, id);
}
inline bool judged_elsewhere(const NodeContext& cx) { return judged_elsewhere(cx.machine, cx.graph, cx.id); }

/// The M950 commands of the graph that create a device of one kind (`letter`, with C) by its number, and those
/// whose number is an expression. Built once per kind (Graph::derived) for later_creation.
inline const tools::DeviceIndex& creations(const NodeContext& cx, char letter) {
  return tools::device_index(cx.machine, cx.graph, std::string("heat.m950.") + letter, 'M', 950,
                             [&](const ParsedFile& pf, const Command& c) -> std::optional<DeviceRef> {
                               auto v = get_int(pf, c, letter);
                               if (v.unknown()) return DeviceRef{};
                               if (v.known() && pf.find(c, 'C')) return DeviceRef{static_cast<int>(v.value), true};
                               return std::nullopt;
                             });
}

/// The later `M950 <letter>n C…` in this segment that creates device n; kNoNode if none. `unknown` is set when the
/// first M950 on the way that may create it creates a device of that kind from an expression (it may be n).
inline NodeId later_creation(const NodeContext& cx, char letter, int n, bool& unknown) {
  return creations(cx, letter).first_later(cx, n, &unknown);
}

/// The commands of code M`number` by the heater they name (heater_named; M307/M570 without H and H{…} apart, as
/// unknown); built once per graph.
inline const tools::DeviceIndex& naming_heater(const NodeContext& cx, int number) {
  return tools::device_index(cx.machine, cx.graph, "heat.named.M" + std::to_string(number), 'M', number,
                             [](const ParsedFile& pf, const Command& c) { return std::optional(heater_named(pf, c)); });
}

using tools::runs_again;

/// The node ranges [begin, end) that ran after node `from` and before this one: in this segment, or, for a macro
/// run after boot, from `from` to the end of its segment (the boot) and then this segment up to here.
inline std::vector<std::pair<NodeId, NodeId>> since(const NodeContext& cx, NodeId from) {
  const Segment& here = cx.segment();
  if (from >= here.begin) return {{from + 1, cx.id}};
  std::vector<std::pair<NodeId, NodeId>> out;
  for (const Segment& sg : cx.graph.segments)
    if (from >= sg.begin && from < sg.end) out.emplace_back(from + 1, sg.end);
  out.emplace_back(here.begin, cx.id);
  return out;
}

/// The M308 commands that create sensors, by sensor number, and those whose sensor number is an expression: as
/// graph nodes in node order, and whether any command on the card (in or out of the graph). Built once per graph
/// (Graph::derived): a card of thousands of heaters asked every M308 for each M950.
struct M308Index {
  tools::DeviceIndex creating;     // S n with a Y type; S {expr}
  std::set<int64_t> card_creates;  // on the card, in any file
  bool card_unknown = false;
};
inline const M308Index& m308_index(const Machine& m, const Graph& g) {
  return g.derived<M308Index>("heat.m308_index", [&] {
    M308Index out;
    for (uint32_t i = 0; i < m.unit_count(); ++i) {
      const ParsedFile& pf = m.unit(i).parsed;
      for (const uint32_t j : pf.with_code('M', 308)) {
        const Command c = pf.commands[j];
        auto S = get_int(pf, c, 'S');
        if (S.unknown()) out.card_unknown = true;
        else if (S.known() && pf.find(c, 'Y')) out.card_creates.insert(S.value);
      }
    }
    tools::each_code_command(m, g, 'M', 308, [&](NodeId id, const Node&, const ParsedFile& pf, const Command& c) {
      auto S = get_int(pf, c, 'S');
      if (S.unknown() || (S.known() && pf.find(c, 'Y'))) out.creating.add(id, S.known(), S.known() ? S.value : 0);
    });
    return out;
  });
}

/// The later `M308 S<n> Y…` in this segment that creates sensor n; kNoNode if none. `unknown` as for
/// later_creation: the first such M308 has an expression for its sensor number (it may be n).
inline NodeId later_sensor(const NodeContext& cx, int n, bool& unknown) {
  return m308_index(cx.machine, cx.graph).creating.first_later(cx, n, &unknown);
}

/// Does any M308 on the card create sensor n? A macro run after boot may create it. An M308 whose sensor number is
/// an expression counts too (it may be n).
inline bool any_m308_creates(const Machine& m, const Graph& g, int n) {
  const M308Index& index = m308_index(m, g);
  return index.card_creates.count(n) || index.card_unknown;
}

}  // namespace rrflint::heat
