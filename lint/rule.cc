#include "rule.h"

#include <algorithm>

namespace rrflint {

#define RULE(ident) extern const Rule ident;
#include "../rules/rules.def"
#undef RULE

const std::vector<const Rule*>& all_rules() {
  static const std::vector<const Rule*> rules = [] {
    std::vector<const Rule*> v = {
#define RULE(ident) &ident,
#include "../rules/rules.def"
#undef RULE
    };
    std::sort(v.begin(), v.end(), [](const Rule* a, const Rule* b) { return a->meta.code < b->meta.code; });
    return v;
  }();
  return rules;
}

const Rule* find_rule(std::string_view key) {
  std::string k = to_lower(key);
  for (const Rule* r : all_rules())
    if (to_lower(r->meta.code) == k || r->meta.name == k) return r;
  return nullptr;
}

Report& Report::note(Location loc, std::string message) {
  d_->notes.push_back(Note{loc, std::move(message)});
  return *this;
}

Report& Report::fix(Fix f) {
  d_->fix = std::move(f);
  return *this;
}

Report Sink::report(const RuleMeta& meta, Location loc, std::string message) {
  return report(meta, meta.severity, loc, std::move(message));
}

Report Sink::report(const RuleMeta& meta, Severity sev, Location loc, std::string message) {
  Diagnostic d;
  d.code = meta.code;
  d.name = meta.name;
  d.severity = sev;
  d.loc = loc;
  d.message = std::move(message);
  out_.push_back(std::move(d));
  return Report(&out_.back());
}

Location NodeContext::where(NodeId other) const {
  const Node& n = graph.nodes[other];
  const FileUnit& u = machine.unit(n.unit);
  if (n.kind == NodeKind::Command) return Location{u.source->id(), u.parsed.commands[n.index].span};
  if (n.call_site != kNoNode) return where(n.call_site);
  return Location{u.source->id(), Span{0, 0}};
}

Location EndContext::where(NodeId other) const {
  NodeContext nc{machine, graph, target, options, end_of_boot, other, 2};
  return nc.where(other);
}

const Segment& NodeContext::segment() const {
  for (const Segment& s : graph.segments)
    if (id >= s.begin && id < s.end) return s;
  return graph.segments.front();
}

bool NodeContext::in_boot() const { return !graph.segments.empty() && segment().boot; }

}  // namespace rrflint
