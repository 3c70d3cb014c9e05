// A document at a cursor position, and the model at that point of the boot (model_at.h).
#include "cli/server/model_at.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "lint/engine/rule.h"

namespace rrflint::server {
namespace {

// Does the array at `path` inside `caps` hold "markdown"?
bool has_markdown(const json& caps, std::initializer_list<const char*> path) {
  const json* j = &caps;
  for (const char* key : path) {
    if (!j->is_object()) return false;
    auto it = j->find(key);
    if (it == j->end()) return false;
    j = &*it;
  }
  return j->is_array() && std::find(j->begin(), j->end(), json("markdown")) != j->end();
}

const Segment* segment_of(const Graph& g, NodeId id) {
  for (const Segment& s : g.segments)
    if (id >= s.begin && id < s.end) return &s;
  return nullptr;
}

// RRF's indent of a line's leading blanks: a blank counts 1, a tab advances to the next multiple of 4.
uint32_t indent_of(std::string_view line) {
  uint32_t n = 0;
  for (char c : line) {
    if (c == ' ') ++n;
    else if (c == '\t') n = (n / 4 + 1) * 4;
    else break;
  }
  return n;
}

// A file as the answers name it: its SD path without the leading '/' ("sys/config.g"), else as displayed.
std::string_view file_label(const SourceFile& f) {
  std::string_view p = f.sd_path();
  return p.empty() ? std::string_view(f.display_path()) : p.substr(p.starts_with('/'));
}

using Names = std::map<std::string, std::string>;  // name -> where it is declared

// The `global` declarations of a file on its logical lines [0, before).
void add_globals(const SourceFile& f, const ParsedFile& pf, uint32_t before, Names& out) {
  const LineTable& lines = pf.lines;
  before = std::min<uint32_t>(before, static_cast<uint32_t>(lines.size()));
  for (uint32_t i = 0; i < before; ++i) {
    if (lines.kind(i) != LineKind::Meta) continue;
    const Line l = lines[i];
    if (l.meta == MetaKind::Global && !l.meta_name.empty())
      out.try_emplace(std::string(pf.text(l.meta_name)),
                      fmt::format("{}:{}", file_label(f), f.line_of(l.span.begin) + 1));
  }
}

std::vector<DocAt::Name> listed(const Names& names) {
  std::vector<DocAt::Name> out;
  for (const auto& [name, at] : names) out.push_back({name, at});
  return out;
}

}  // namespace

ClientCaps ClientCaps::of(const json& c) {
  ClientCaps out;
  out.hover_markdown = has_markdown(c, {"textDocument", "hover", "contentFormat"});
  out.completion_markdown = has_markdown(c, {"textDocument", "completion", "completionItem", "documentationFormat"});
  out.signature_markdown =
      has_markdown(c, {"textDocument", "signatureHelp", "signatureInformation", "documentationFormat"});
  return out;
}

Workspace::View Workspace::view(const std::string& uri) const {
  View v;
  auto d = docs_.find(uri);
  if (d == docs_.end()) return v;
  v.text = &d->second.text;
  v.sd_path = d->second.sd_path;
  auto m = machines_.find(d->second.machine);
  if (m != machines_.end() && m->second.last) {
    v.snap = m->second.last.get();
    v.docs_base = m->second.docs_base;
  }
  return v;
}

std::unique_ptr<DocAt> DocAt::make(const Workspace& ws, const std::string& uri, Position pos) {
  std::unique_ptr<DocAt> d(new DocAt());
  d->view_ = ws.view(uri);
  if (!d->view_.text) return nullptr;
  const std::string& text = *d->view_.text;
  if (const Snapshot* s = d->view_.snap; s && s->result.machine) {
    const Machine& m = *s->result.machine;
    for (uint32_t i = 0; i < m.unit_count() && !d->unit_; ++i) {
      const FileUnit& u = m.unit(i);
      const bool same = d->view_.sd_path.empty() ? i == 0 : to_lower(u.sd_path) == to_lower(d->view_.sd_path);
      if (same && u.source->text() == text) d->unit_ = &u;
    }
  }
  if (d->unit_) {
    d->file_ = d->unit_->source;
    d->parsed_ = &d->unit_->parsed;
  } else {
    d->own_sm_ = std::make_unique<SourceManager>();
    d->file_ = &d->own_sm_->add(uri, d->view_.sd_path, TextBuffer(text));
    d->own_parse_ = parse(*d->file_);
    d->parsed_ = &*d->own_parse_;
  }
  // The file's line index finds the line (offset_of would scan every line before it).
  const SourceFile& f = *d->file_;
  if (pos.line >= f.line_count()) d->offset_ = f.size();
  else {
    const Span ls = f.line_span(pos.line);
    d->offset_ = ls.begin + static_cast<uint32_t>(offset_of(f.slice(ls), Position{0, pos.character}));
  }
  const LineTable& lines = d->parsed_->lines;
  uint32_t lo = 0, hi = static_cast<uint32_t>(lines.size());  // the last line that starts at or before the cursor
  while (hi - lo > 1) {
    const uint32_t mid = lo + (hi - lo) / 2;
    (lines.span(mid).begin <= d->offset_ ? lo : hi) = mid;
  }
  d->line_ = lo;
  if (d->unit_) d->locate();
  return d;
}

std::string_view DocAt::before_cursor() const {
  if (parsed_->lines.size() == 0) return {};
  const uint32_t b = parsed_->lines.span(line_).begin;
  return file_->text().substr(b, offset_ > b ? offset_ - b : 0);
}

std::optional<uint32_t> DocAt::command() const {
  if (parsed_->lines.size() == 0) return std::nullopt;
  const Line l = parsed_->lines[line_];
  for (uint32_t i = l.first_command; i < l.first_command + l.command_count; ++i) {
    const Span s = parsed_->commands[i].span;
    if (s.begin <= offset_ && offset_ <= s.end) return i;
  }
  return std::nullopt;
}

bool DocAt::in_comment() const {
  if (parsed_->lines.size() == 0) return false;
  const Line l = parsed_->lines[line_];
  return !l.comment.empty() && offset_ > l.comment.begin;
}

// The point: the first command of the file's first run that ends at or after the cursor, else the run's Leave.
void DocAt::locate() {
  const CommandTable& cmds = parsed_->commands;
  uint32_t lo = 0, hi = static_cast<uint32_t>(cmds.size());
  while (lo < hi) {
    const uint32_t mid = lo + (hi - lo) / 2;
    if (cmds[mid].span.end < offset_) lo = mid + 1;
    else hi = mid;
  }
  const uint32_t first = lo;
  const Graph& g = view_.snap->result.graph;
  NodeId enter = kNoNode;
  for (NodeId id = 0; id < g.nodes.size();) {
    const NodeTable::Stretch st = g.nodes.stretch(id);
    if (st.node.kind == NodeKind::Enter && st.node.unit == unit_->index) {
      if (enter == kNoNode) enter = id;
      ++runs_;
    }
    id = st.end;
  }
  if (enter == kNoNode) return;
  const Segment* seg = segment_of(g, enter);
  point_ = g.nodes.find_if(enter + 1, seg ? seg->end : enter + 1, [&](NodeId, const Node& n) {
    return n.enter == enter && ((n.kind == NodeKind::Command && n.index >= first) || n.kind == NodeKind::Leave);
  });
}

// The forward pass of lint/engine/linter.cc without the rules, from the start of the point's segment to the point.
void DocAt::replay() const {
  replayed_ = true;
  const MachineResult& r = view_.snap->result;
  const Graph& g = r.graph;
  const Segment* seg = segment_of(g, point_);
  if (!seg) return;
  ModelBuilder mb(*r.machine, g, r.target.version, r.target.board);
  MachineState s = seg->boot ? mb.initial_state() : r.end_of_boot;
  if (!seg->boot && !r.has_boot) s.unknown_baseline = true;
  for (NodeId id = seg->begin; id < point_;) {
    const NodeTable::Stretch st = g.nodes.stretch(id);
    const NodeId end = std::min(st.end, point_);
    if (st.node.kind != NodeKind::Command) {
      mb.decide(s, id, st.node);
      mb.step(s, id, st.node);
      id = end;
      continue;
    }
    mb.decide_commands(s, id, end, st.node);
    const CommandTable& commands = r.machine->unit(st.node.unit).parsed.commands;
    for (Node node = st.node; id < end; ++id) {
      node.index = st.node.index + (id - st.begin);
      if (ModelBuilder::changes_state(commands.code(node.index))) mb.step(s, id, node);
    }
  }
  mb.decide(s, point_);
  point_runs_ = mb.runs(point_);
  state_ = std::move(s);
}

const MachineState* DocAt::state() const {
  if (!unit_ || point_ == kNoNode) return nullptr;
  if (!replayed_) replay();
  return state_ ? &*state_ : nullptr;
}

Runs DocAt::point_runs() const {
  state();
  return point_runs_;
}

std::string DocAt::where(NodeId id, bool markdown) const {
  if (id == kNoNode) return "default";
  const MachineResult& r = view_.snap->result;
  const Location at = EndContext{*r.machine, r.graph, r.target, LintOptions{}, r.end_of_boot}.where(id);
  const FileUnit* u = unit_of(*view_.snap, at.file);
  if (!u) return "?";
  const uint32_t line = u->source->line_of(at.span.begin) + 1;
  const std::string text = fmt::format("{}:{}", file_label(*u->source), line);
  if (!markdown) return text;
  if (auto abs = view_.snap->disk.disk_path(u->sd_path))
    return fmt::format("[{}]({}#L{})", text, uri_of_path(*abs), line);
  return fmt::format("`{}`", text);
}

// Globals: every file run that finished before the point declared all of its globals; the runs still going there
// (the point's file and its callers) those on the lines before the cursor or the call. An entry starts after the
// boot, which declared the globals of every file it ran.
std::vector<DocAt::Name> DocAt::globals() const {
  Names out;
  if (!unit_ || point_ == kNoNode) {
    add_globals(*file_, *parsed_, line_, out);
    return listed(out);
  }
  const MachineResult& r = view_.snap->result;
  const Graph& g = r.graph;
  const Segment* seg = segment_of(g, point_);
  std::map<NodeId, uint32_t> open;  // Enter node of a run still going -> the line it is at
  NodeId child = kNoNode;
  for (NodeId e = g.nodes[point_].enter; e != kNoNode; e = g.nodes[e].enter) {
    uint32_t line = line_;
    if (child != kNoNode) {
      const Node site = g.nodes[g.nodes[child].call_site];
      line = site.kind == NodeKind::Command ? r.machine->unit(site.unit).parsed.commands[site.index].line : 0;
    }
    open[e] = line;
    child = e;
    if (g.nodes[e].call_site == kNoNode) break;
  }
  std::set<uint32_t> whole;
  auto runs_in = [&](NodeId begin, NodeId end) {
    for (NodeId id = begin; id < end;) {
      const NodeTable::Stretch st = g.nodes.stretch(id);
      if (st.node.kind == NodeKind::Enter && !open.count(id)) whole.insert(st.node.unit);
      id = st.end;
    }
  };
  if (seg && !seg->boot)
    for (const Segment& b : g.segments)
      if (b.boot) runs_in(b.begin, b.end);
  if (seg) runs_in(seg->begin, point_);
  for (uint32_t u : whole) add_globals(*r.machine->unit(u).source, r.machine->unit(u).parsed, UINT32_MAX, out);
  for (const auto& [e, line] : open) {
    const FileUnit& u = r.machine->unit(g.nodes[e].unit);
    add_globals(*u.source, u.parsed, line, out);
  }
  return listed(out);
}

// Vars: those of the file on the lines before the cursor whose block is still open there (RRF ends a var's scope
// with its block: a line indented less than the declaration).
std::vector<DocAt::Name> DocAt::vars() const {
  Names out;
  const LineTable& lines = parsed_->lines;
  if (lines.size() == 0) return {};
  uint32_t indent = indent_of(file_->text().substr(lines.span(line_).begin));
  for (uint32_t i = line_; i-- > 0;) {
    const LineKind k = lines.kind(i);
    if (k == LineKind::Blank || k == LineKind::Comment) continue;
    const Line l = lines[i];
    if (l.meta == MetaKind::Var && !l.meta_name.empty() && l.indent <= indent)
      out.try_emplace(std::string(parsed_->text(l.meta_name)),
                      fmt::format("line {}", file_->line_of(l.span.begin) + 1));
    indent = std::min(indent, l.indent);
  }
  return listed(out);
}

}  // namespace rrflint::server
