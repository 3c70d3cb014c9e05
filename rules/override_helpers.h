// Helpers shared by the config-override.g rules (RRF401 m501-too-early, RRF402 override-after-m501): the run of
// config-override.g that an M501 makes in the boot sequence, and comparing what two commands set. What M500 writes
// and what M501 does follow docs/firmware-behaviour.md#saved-settings-m500-m501-m502.
#pragma once

#include <cmath>
#include <optional>
#include <unordered_map>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint::override_file {

/// The nodes of one run of config-override.g made by an M501: the Enter node, its Leave node, and the M501.
struct Run {
  NodeId m501 = kNoNode, enter = kNoNode, leave = kNoNode;
  /// Is node `id` one of the file's own nodes (or of a file it calls)?
  bool holds(NodeId id) const { return id != kNoNode && id > enter && id < leave; }
};

/// The run of config-override.g that the M501 at node `m501` makes; nullopt when it makes none (the file is
/// missing, the M501 is nested or never reached).
inline std::optional<Run> run_of(const Graph& g, NodeId m501) {
  if (m501 == kNoNode || m501 + 1 >= g.nodes.size()) return std::nullopt;
  const Node e = g.nodes[m501 + 1];
  if (e.kind != NodeKind::Enter || e.call != CallKind::M501 || e.call_site != m501) return std::nullopt;
  const NodeId enter = m501 + 1;
  // The Leave node of each Enter, found once per graph: each command after the M501 asked, and walked the run.
  struct Leaves {
    std::unordered_map<NodeId, NodeId> of_enter;
  };
  const Leaves& leaves = g.derived<Leaves>("override_file.leaves", [&] {
    Leaves out;
    g.nodes.each_whole([&](NodeId id, const Node& n) {
      if (n.kind == NodeKind::Leave) out.of_enter.emplace(n.enter, id);
    });
    return out;
  });
  const auto leave = leaves.of_enter.find(enter);
  if (leave == leaves.of_enter.end()) return std::nullopt;
  return Run{m501, enter, leave->second};
}

/// The run of config-override.g loaded before this node, in the boot sequence; nullopt if none.
inline std::optional<Run> loaded_run(const NodeContext& cx) {
  if (!cx.in_boot() || cx.state.running_m501 || cx.state.unknown_baseline) return std::nullopt;
  return run_of(cx.graph, cx.state.m501);
}

/// The last command of the run with code `letter` `number` that certainly runs and for which pred holds.
template <class Pred>
NodeId last_in_run(const NodeContext& cx, const Run& r, char letter, int number, Pred pred) {
  return tools::each_code_node_backward(cx, r.enter + 1, r.leave, letter, {number},
                                        [&](NodeId, const tools::NodeCommand& k) { return !k.node.maybe && pred(k); });
}

/// How two values of one letter compare: both known and equal, both known and different, or not comparable.
enum class Cmp : uint8_t { Same, Differ, Unknown };

inline Cmp compare(const tools::NodeCommand& a, const tools::NodeCommand& b, char letter) {
  auto x = get_float_list(*a.pf, *a.c, letter);
  auto y = get_float_list(*b.pf, *b.c, letter);
  if (!x.known() || !y.known()) return Cmp::Unknown;
  if (x.value.size() != y.value.size()) return Cmp::Differ;
  for (size_t i = 0; i < x.value.size(); ++i)
    if (std::fabs(x.value[i] - y.value[i]) > 1e-9) return Cmp::Differ;
  return Cmp::Same;
}

/// The letters of `letters` that both commands set, where they set different values. `unknown` is set when a
/// value of `later` is an expression (rules then stay silent).
inline std::string differing(const tools::NodeCommand& later, const tools::NodeCommand& loaded,
                             std::string_view letters, bool& unknown) {
  std::string out;
  unknown = false;
  for (const char l : letters) {
    if (!later.pf->find(*later.c, l)) continue;
    if (!loaded.pf->find(*loaded.c, l)) continue;
    const Cmp c = compare(later, loaded, l);
    if (c == Cmp::Unknown) unknown = true;
    if (c == Cmp::Differ) out += l;
  }
  return out;
}

/// "X, Y and Z" from "XYZ".
inline std::string letter_list(std::string_view letters) {
  std::string out;
  for (size_t i = 0; i < letters.size(); ++i) {
    if (i > 0) out += i + 1 == letters.size() ? " and " : ", ";
    out += tools::axis_name(letters[i]);
  }
  return out;
}

/// A number without needless zeros: 22.34, 0, -12.5.
inline std::string number(double v) {
  std::string s = fmt::format("{:.3f}", v);
  while (s.ends_with('0')) s.pop_back();
  if (s.ends_with('.')) s.pop_back();
  return s == "-0" ? "0" : s;
}

}  // namespace rrflint::override_file
