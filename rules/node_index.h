// Indexes of graph nodes that a node rule builds once per graph (Graph::derived) and asks with a binary search,
// instead of walking every later (or earlier) node for each command it checks. A look-ahead that walks the nodes
// is quadratic on a config of thousands of similar lines; see docs/adding-a-rule.md, "Bound what a finding may
// cost".
#pragma once

#include <algorithm>
#include <string>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "lint/engine/rule.h"

namespace rrflint::tools {

/// Calls f(id, node, file, command) for each command node of code `letter` `number` (no fraction), in node order:
/// what an index built once per graph (Graph::derived) walks.
template <class F>
void each_code_command(const Machine& m, const Graph& g, char letter, int number, F f) {
  const std::vector<NodeId>* ids = g.code_nodes(m, letter, number);
  if (!ids) return;
  for (const NodeId id : *ids) {
    const Node n = g.nodes[id];
    const ParsedFile& pf = m.unit(n.unit).parsed;
    if (pf.commands.code(n.index).fraction >= 0) continue;
    f(id, n, pf, pf.commands[n.index]);
  }
}

/// The first of `ids` (sorted) in (from, end); kNoNode if none.
inline NodeId first_after(const std::vector<NodeId>& ids, NodeId from, NodeId end) {
  auto next = std::upper_bound(ids.begin(), ids.end(), from);
  return next != ids.end() && *next < end ? *next : kNoNode;
}

/// The first of `ids` (sorted) in [begin, end); kNoNode if none.
inline NodeId first_in(const std::vector<NodeId>& ids, NodeId begin, NodeId end) {
  auto next = std::lower_bound(ids.begin(), ids.end(), begin);
  return next != ids.end() && *next < end ? *next : kNoNode;
}

/// The last of `ids` (sorted) in [begin, before); kNoNode if none.
inline NodeId last_before(const std::vector<NodeId>& ids, NodeId begin, NodeId before) {
  auto it = std::lower_bound(ids.begin(), ids.end(), before);
  return it != ids.begin() && *std::prev(it) >= begin ? *std::prev(it) : kNoNode;
}

/// The later of two nodes, either of which may be kNoNode (none): kNoNode only when both are.
inline NodeId later_of(NodeId a, NodeId b) {
  if (a == kNoNode) return b;
  return b == kNoNode ? a : std::max(a, b);
}

/// The first of `ids` (sorted) after the node at `cx`, in its segment; kNoNode if none.
inline NodeId first_later(const NodeContext& cx, const std::vector<NodeId>& ids) {
  return first_after(ids, cx.id, cx.segment().end);
}

/// The ids an index keeps under `key`, or an empty list.
template <class Map, class Key>
const std::vector<NodeId>& ids_of(const Map& index, const Key& key) {
  static const std::vector<NodeId> none;
  auto it = index.find(key);
  return it == index.end() ? none : it->second;
}

/// first_later of the nodes an index keeps under `key` (none: kNoNode).
template <class Map, class Key>
NodeId first_later(const NodeContext& cx, const Map& index, const Key& key) {
  return first_later(cx, ids_of(index, key));
}

/// The command nodes of one code (no fraction) in node order: by the parameter letters they carry, and those not
/// inside an if/while.
struct CodeIndex {
  std::unordered_map<char, std::vector<NodeId>> by_letter;
  std::unordered_map<char, std::vector<NodeId>> certain_by_letter;  // those not inside an if/while
  std::vector<NodeId> certain;                                      // every one not inside an if/while
  const std::vector<NodeId>& operator[](char letter) const { return ids_of(by_letter, letter); }
};

/// The CodeIndex of code `letter` `number`, built once per graph.
inline const CodeIndex& code_index(const Machine& m, const Graph& g, char letter, int number) {
  return g.derived<CodeIndex>(fmt::format("tools.code_index.{}{}", letter, number), [&] {
    CodeIndex out;
    each_code_command(m, g, letter, number, [&](NodeId id, const Node& n, const ParsedFile& pf, const Command& c) {
      if (!n.maybe) out.certain.push_back(id);
      std::string seen;
      for (const Param& p : pf.params(c))
        if (p.letter != 0 && seen.find(p.letter) == std::string::npos) {
          seen += p.letter;
          out.by_letter[p.letter].push_back(id);
          if (!n.maybe) out.certain_by_letter[p.letter].push_back(id);
        }
    });
    return out;
  });
}

/// The commands of one kind that name a device (a heater, a probe, a sensor…) by its number, in node order, and
/// those that name it with an expression (they may name any number).
struct DeviceIndex {
  std::unordered_map<int64_t, std::vector<NodeId>> known;
  std::vector<NodeId> unknown;
  void add(NodeId id, bool number_known, int64_t number) {
    if (number_known) known[number].push_back(id);
    else unknown.push_back(id);
  }
  /// The first of them in (from, end) that names device n, or may; `*maybe` says it only may (an expression).
  NodeId first_after(NodeId from, NodeId end, int64_t n, bool* maybe = nullptr) const {
    const NodeId named = tools::first_after(ids_of(known, n), from, end);
    const NodeId unsure = tools::first_after(unknown, from, end);
    if (maybe) *maybe = unsure < named;  // kNoNode is the largest id
    return std::min(named, unsure);
  }
  NodeId first_later(const NodeContext& cx, int64_t n, bool* maybe = nullptr) const {
    return first_after(cx.id, cx.segment().end, n, maybe);
  }
  /// The last of them in [begin, end) that names device n, or may; kNoNode if none.
  NodeId last_in(NodeId begin, NodeId end, int64_t n) const {
    return later_of(last_before(ids_of(known, n), begin, end), last_before(unknown, begin, end));
  }
};

/// A DeviceIndex of the commands of code `letter` `number` (no fraction), built once per graph under `key`:
/// `name(file, command)` gives the device a command names, as a DeviceRef-like {number, known}, or nullopt to
/// leave the command out.
template <class Name>
const DeviceIndex& device_index(const Machine& m, const Graph& g, const std::string& key, char letter, int number,
                                Name name) {
  return g.derived<DeviceIndex>(key, [&] {
    DeviceIndex out;
    each_code_command(m, g, letter, number, [&](NodeId id, const Node&, const ParsedFile& pf, const Command& c) {
      if (const auto r = name(pf, c)) out.add(id, r->known, r->number);
    });
    return out;
  });
}

}  // namespace rrflint::tools
