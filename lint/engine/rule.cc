#include "lint/engine/rule.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>
#include <vector>

#include "lint/base/strings.h"

namespace rrflint {

RuleSet::RuleSet(std::vector<const Rule*> rules) : rules_(std::move(rules)) {
  std::sort(rules_.begin(), rules_.end(), [](const Rule* a, const Rule* b) { return a->meta.code < b->meta.code; });
}

const Rule* RuleSet::find(std::string_view key) const {
  // A code or a name, in any case (`G10-Missing-Z` finds g10-missing-z).
  for (const Rule* r : rules_)
    if (iequals(r->meta.code, key) || iequals(r->meta.name, key)) return r;
  return nullptr;
}

namespace {

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

const Rule* RuleSet::near_miss(std::string_view written) const {
  const std::string w = to_lower(written);
  if (w.size() >= 4 && w.starts_with("rrf") && std::isdigit(static_cast<unsigned char>(w[3]))) return nullptr;
  // A name farther than this is no near miss. Names whose lengths differ by more cannot be within it, and are not
  // compared: a long word (a 50,000-byte "rule name") then costs nothing instead of its length times every name's.
  const size_t limit = std::max<size_t>(2, w.size() / 4);
  const Rule* best = nullptr;
  size_t best_d = SIZE_MAX;
  for (const Rule* r : rules_) {
    const std::string_view name = r->meta.name;  // lower case (the registry test holds every name to it)
    if ((name.size() > w.size() ? name.size() - w.size() : w.size() - name.size()) > limit) continue;
    const size_t d = edit_distance(w, name);
    if (d < best_d) {
      best_d = d;
      best = r;
    }
  }
  return best_d <= limit ? best : nullptr;
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
  return Report(&out_.push_back(std::move(d)));
}

Location NodeContext::where(NodeId other) const {
  const Node& n = graph.nodes[other];
  const FileUnit& u = machine.unit(n.unit);
  if (n.kind == NodeKind::Command) return Location{u.source->id(), u.parsed.commands[n.index].span};
  if (n.call_site != kNoNode) return where(n.call_site);
  return Location{u.source->id(), Span{0, 0}};
}

Location EndContext::where(NodeId other) const {
  NodeContext nc{machine, graph, target, options, end_of_boot, other, Runs::Yes, graph.nodes[other]};
  return nc.where(other);
}

const Segment& NodeContext::segment() const {
  for (const Segment& s : graph.segments)
    if (id >= s.begin && id < s.end) return s;
  return graph.segments.front();
}

bool parse_triggers(std::string_view on, Triggers& out, std::string* bad) {
  out = Triggers{};
  while (!on.empty()) {
    const size_t b = on.find_first_not_of(' ');
    if (b == std::string_view::npos) break;
    on.remove_prefix(b);
    const std::string_view tok = on.substr(0, on.find(' '));
    on.remove_prefix(tok.size());
    if (tok == "T") {
      out.any_t = true;
      continue;
    }
    int n = 0;
    bool ok = tok.size() >= 2 && tok.size() <= 5 && (tok[0] == 'G' || tok[0] == 'M');
    for (size_t i = 1; ok && i < tok.size(); ++i) {
      ok = tok[i] >= '0' && tok[i] <= '9';
      n = n * 10 + (tok[i] - '0');
    }
    if (!ok) {
      if (bad) *bad = std::string(tok);
      return false;
    }
    out.codes.emplace_back(tok[0], n);
  }
  return true;
}

G10Form NodeContext::g10_form() const {
  if (!g10_form_) g10_form_ = rrflint::g10_form(parsed(), command(), &state, state.firmware);
  return *g10_form_;
}

bool NodeContext::in_boot() const { return !graph.segments.empty() && segment().boot; }

}  // namespace rrflint
