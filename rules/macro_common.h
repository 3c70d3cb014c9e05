// Shared helpers for the RRF5xx macro rules: reading the graph's events.
#pragma once

#include "../lint/rule.h"

namespace rrflint {

/// The command node that caused a graph event, as a Location plus whether it sits in a conditional block.
inline Command event_command(const EndContext& cx, const GraphEvent& e) {
  const Node& n = cx.graph.nodes[e.node];
  return cx.machine.unit(n.unit).parsed.commands[n.index];
}

inline bool event_is_m98(const EndContext& cx, const GraphEvent& e) {
  const Command& c = event_command(cx, e);
  return c.letter == 'M' && c.number == 98 && c.fraction < 0;
}

/// The P parameter's span of the calling command (the path), or the whole command.
inline Location event_path_loc(const EndContext& cx, const GraphEvent& e) {
  const Node& n = cx.graph.nodes[e.node];
  const FileUnit& u = cx.machine.unit(n.unit);
  const Command& c = u.parsed.commands[n.index];
  ParamRef p = u.parsed.find(c, 'P');
  return Location{u.source->id(), p ? p->span : c.span};
}

}  // namespace rrflint
