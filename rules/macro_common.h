// Shared helpers for the RRF5xx macro rules: reading the graph's events.
#pragma once

#include <set>
#include <vector>

#include "lint/engine/rule.h"

namespace rrflint {

/// The command node that caused a graph event, as a Location plus whether it sits in a conditional block.
inline Command event_command(const EndContext& cx, const GraphEvent& e) {
  const Node& n = cx.graph.nodes[e.node];
  return cx.machine.unit(n.unit).parsed.commands[n.index];
}

inline bool event_is_m98(const EndContext& cx, const GraphEvent& e) {
  const Command& c = event_command(cx, e);
  return c.is('M', 98);
}

/// The P parameter's span of the calling command (the path), or the whole command.
inline Location event_path_loc(const EndContext& cx, const GraphEvent& e) {
  const Node& n = cx.graph.nodes[e.node];
  const FileUnit& u = cx.machine.unit(n.unit);
  const Command& c = u.parsed.commands[n.index];
  ParamRef p = u.parsed.find(c, 'P');
  return Location{u.source->id(), p ? p->span : c.span};
}

/// The call chain above a command node, innermost first: the M98/M501/T command nodes that called the file it is in,
/// the file that called that one, and so on up to config.g or the entry.
inline std::vector<NodeId> call_chain(const Graph& g, NodeId node) {
  std::vector<NodeId> out;
  for (NodeId enter = g.nodes[node].enter; enter != kNoNode;) {
    const NodeId site = g.nodes[enter].call_site;
    if (site == kNoNode) break;
    out.push_back(site);
    enter = g.nodes[site].enter;
  }
  return out;
}

/// The files that some other file calls (M98, M501, tool-change macros), including calls the graph did not follow
/// because they closed a cycle or went too deep. A macro chain found from one of them is part of a longer chain
/// that starts further up, and is reported there: one finding per chain, not one per file of it.
inline std::set<std::string> called_files(const EndContext& cx) {
  std::set<std::string> out;
  for (const Node& n : cx.graph.nodes)
    if (n.kind == NodeKind::Enter && n.call_site != kNoNode) out.insert(to_lower(cx.machine.unit(n.unit).sd_path));
  for (const GraphEvent& e : cx.graph.events)
    if (e.kind == GraphEvent::Kind::Cycle || e.kind == GraphEvent::Kind::TooDeep) out.insert(to_lower(e.path));
  return out;
}

/// The file an event's chain starts from: config.g for the boot sequence, else the entry macro.
inline const FileUnit& chain_root(const EndContext& cx, const GraphEvent& e) {
  const std::vector<NodeId> chain = call_chain(cx.graph, e.node);
  const NodeId top = chain.empty() ? e.node : chain.back();
  return cx.machine.unit(cx.graph.nodes[top].unit);
}

}  // namespace rrflint
