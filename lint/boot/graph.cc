#include "lint/boot/graph.h"

#include <map>

#include "lint/boot/commands.h"
#include "lint/boot/const_eval.h"
#include "lint/boot/stretches.h"

#include <algorithm>
#include <mutex>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "lint/syntax/values.h"

namespace rrflint {

std::string_view call_kind_name(CallKind k) {
  switch (k) {
    case CallKind::Boot: return "boot";
    case CallKind::Entry: return "entry";
    case CallKind::M98: return "M98";
    case CallKind::M501: return "M501";
    case CallKind::RunOnce: return "runonce";
    case CallKind::ToolFree: return "tfree";
    case CallKind::ToolPre: return "tpre";
    case CallKind::ToolPost: return "tpost";
  }
  return "?";
}

void NodeTable::grow(size_t n) {
  size_ += n;
  while ((block_runs_.size() << kBlockBits) < size_) block_runs_.push_back(static_cast<uint32_t>(runs_.size() - 1));
}

void NodeTable::push_back(const Node& n) {
  if (n.kind == NodeKind::Command && n.call_site == kNoNode) return push_commands(n, 1);
  runs_.push_back(Run{static_cast<NodeId>(size_), kFull, static_cast<uint32_t>(full_.size())});
  full_.push_back(n);
  grow(1);
}

void NodeTable::push_commands(const Node& n, uint32_t count) {
  if (count == 0) return;
  const Frame f{n.call, n.maybe, n.depth, n.unit, n.enter};
  const auto same = [&](const Frame& g) {
    return g.call == f.call && g.maybe == f.maybe && g.depth == f.depth && g.unit == f.unit && g.enter == f.enter;
  };
  // The same frame as the last run, and the next command of it: the run grows.
  if (!runs_.empty() && runs_.back().frame != kFull && same(frames_[runs_.back().frame]) &&
      runs_.back().index + (size_ - runs_.back().first) == n.index)
    return grow(count);
  if (frames_.empty() || !same(frames_.back())) frames_.push_back(f);
  runs_.push_back(Run{static_cast<NodeId>(size_), static_cast<uint32_t>(frames_.size() - 1), n.index});
  grow(count);
}

class GraphCache {
 public:
  std::mutex mutex;
  std::unordered_map<uint32_t, std::vector<NodeId>> by_code;  // letter << 16 | number; references stay valid
  std::recursive_mutex derived_mutex;
  std::unordered_map<std::string, std::shared_ptr<void>> derived;
};

std::recursive_mutex& Graph::derived_mutex() const { return cache_->derived_mutex; }
std::shared_ptr<void>& Graph::derived_slot(const std::string& key) const { return cache_->derived[key]; }

Graph::Graph() : cache_(std::make_unique<GraphCache>()) {}
Graph::~Graph() = default;
Graph::Graph(Graph&& o) noexcept = default;
Graph& Graph::operator=(Graph&& o) noexcept = default;

const std::vector<NodeId>* Graph::code_nodes(const Machine& m, char letter, int32_t number) const {
  if ((letter != 'G' && letter != 'M') || number < 0 || number >= 1024) return nullptr;
  const uint32_t key = static_cast<uint32_t>(letter) << 16 | static_cast<uint32_t>(number);
  std::lock_guard<std::mutex> lock(cache_->mutex);
  auto [it, fresh] = cache_->by_code.try_emplace(key);
  if (!fresh) return &it->second;
  std::vector<NodeId>& out = it->second;
  nodes.each_command_run([&](NodeId first, uint32_t unit, uint32_t index, uint32_t count) {
    const std::span<const uint32_t> cmds = m.unit(unit).parsed.with_code(letter, number).indices();
    for (auto c = std::lower_bound(cmds.begin(), cmds.end(), index); c != cmds.end() && *c < index + count; ++c)
      out.push_back(first + (*c - index));
  });
  return &out;
}

namespace {

// MaxFilenameLength (Configuration.h): the longest path RRF builds, "0:" and the trailing "/" included.
constexpr size_t kMaxFilenameLength = 120;

class Builder {
 public:
  Builder(Machine& m, const GraphOptions& o) : m_(m), o_(o), sys_dir_(o.sys_dir) {}

  Graph build();

 private:
  NodeId push(Node n) {
    g_.nodes.push_back(n);
    return static_cast<NodeId>(g_.nodes.size() - 1);
  }
  bool full() {
    if (g_.nodes.size() >= o_.max_nodes) g_.truncated = true;
    return g_.truncated;
  }
  // Records an event once per call context: the same kind, calling command and path, at the same depth and
  // certainty, with the same files running (stack_). Every rule's finding about a repeat is the same as about the
  // first. A macro called many times over (20 calls in each of 9 files that call the next) repeated one event
  // millions of times, and the findings made of them were de-duplicated only after they were made: 9 s and 1.6 GB.
  void record(GraphEvent e) {
    const Node n = g_.nodes[e.node];
    std::string key;
    auto put = [&key](uint32_t v) { key.append(reinterpret_cast<const char*>(&v), sizeof v); };
    put(static_cast<uint32_t>(e.kind));
    put(n.unit);
    put(n.index);
    put(n.depth);
    put(n.maybe ? 1 : 0);
    put(static_cast<uint32_t>(stack_.size()));
    for (uint32_t u : stack_) put(u);
    key += e.path;
    if (events_seen_.insert(std::move(key)).second) g_.events.push_back(std::move(e));
  }
  void run_file(const FileUnit& u, CallKind call, NodeId call_site, bool maybe, uint16_t depth, uint32_t tool = 0);
  void call(const std::string& name, CallKind kind, NodeId site, bool maybe, uint16_t depth, bool report_missing,
            uint32_t tool = 0);
  void tool_change(const FileUnit& u, const Command& c, NodeId site, bool maybe, uint16_t depth);
  const FileUnit* tool_macro(std::string_view kind, int tool);
  /// The commands of a file that the graph acts on (T, M98, M501, M505, no fraction), in order; found once a file.
  const std::vector<uint32_t>& acting_commands(const FileUnit& u);

  Machine& m_;
  const GraphOptions& o_;
  Graph g_;
  std::string sys_dir_;
  std::vector<uint32_t> stack_;                  // units currently running (cycle detection)
  std::unordered_set<std::string> events_seen_;  // record()'s keys
  std::set<uint32_t> reached_;                   // units run by the boot sequence
  bool booting_ = false;                         // run_file is running the boot sequence: record the units it reaches
  int current_tool_ = kNoTool;                   // or kUnknownTool
  std::unordered_map<uint64_t, std::optional<std::string>> m98_paths_;  // (unit, command) -> M98 P, if known
  std::unordered_map<uint32_t, std::vector<uint32_t>> acting_;          // unit -> acting_commands
  // Values known at boot: globals set to constants so far on the boot path (a name set in an `if`, or to
  // anything else, is absent: unknown).
  std::map<std::string, ConstValue> globals_;
  struct FileValues;  // the `var`s of one file run, and which assignment lines it has applied
  /// The file's top-level if/elif/else chains (lint/boot/branches.h); found once a file.
  const std::vector<Chain>& chains(const FileUnit& u) {
    auto [it, fresh] = chains_.try_emplace(u.index);
    if (fresh) it->second = top_level_chains(u.parsed);
    return it->second;
  }
  std::unordered_map<uint32_t, std::vector<Chain>> chains_;  // unit -> chains
  /// The file's global/var/set lines, in order; found once a file.
  const std::vector<uint32_t>& assignment_lines(const FileUnit& u);
  std::unordered_map<uint32_t, std::vector<uint32_t>> assignments_;  // unit -> assignment_lines
  void assign_until(const FileUnit& u, FileValues& fv, uint32_t line);
  /// What an expression may read here: directories.system (the M505 folder), the globals, the file's vars.
  ConstEnv env(const FileValues& fv) const;
  std::optional<std::string> evaluated_path(const FileUnit& u, const Command& c, FileValues& fv, uint32_t line);
};

struct Builder::FileValues {
  const std::vector<uint32_t>& lines;  // the file's global/var/set lines, in order
  size_t next = 0;
  std::map<std::string, ConstValue> vars;
};

const std::vector<uint32_t>& Builder::assignment_lines(const FileUnit& u) {
  auto [it, fresh] = assignments_.try_emplace(u.index);
  if (fresh) {
    const LineTable& lines = u.parsed.lines;
    for (uint32_t li = 0; li < lines.size(); ++li)
      if (lines.kind(li) == LineKind::Meta) {
        const MetaKind k = lines[li].meta;
        if (k == MetaKind::Global || k == MetaKind::Var || k == MetaKind::Set) it->second.push_back(li);
      }
  }
  return it->second;
}

ConstEnv Builder::env(const FileValues& fv) const { return ConstEnv{"0:" + sys_dir_ + "/", &globals_, &fv.vars}; }

// Applies the file's assignments on lines before `line`: a constant value is known from there on, anything else
// (or an assignment inside a block) makes the name unknown.
void Builder::assign_until(const FileUnit& u, FileValues& fv, uint32_t line) {
  const ParsedFile& pf = u.parsed;
  for (; fv.next < fv.lines.size() && fv.lines[fv.next] < line; ++fv.next) {
    const Line l = pf.lines[fv.lines[fv.next]];
    std::string_view name = pf.text(l.meta_name);
    std::map<std::string, ConstValue>* scope = &fv.vars;
    if (l.meta == MetaKind::Global || (l.meta == MetaKind::Set && name.starts_with("global."))) scope = &globals_;
    if (l.meta == MetaKind::Set) name.remove_prefix(name.find('.') + 1);  // "global.x" / "var.x": the parser checked
    // An element (`set global.a[1] = …`), a value set in a block, or anything not constant: unknown from here.
    // Between the name and the value, within the line: a line with no name (`var = 12`, a syntax error) has an empty
    // name span at offset 0, and searching from there searched the whole file before it, for each such line.
    const uint32_t after_name = std::max(l.meta_name.end, l.span.begin);
    const bool element = after_name < l.meta_arg.begin &&
                         pf.text(Span{after_name, l.meta_arg.begin}).find('[') != std::string_view::npos;
    const ConstValue v =
        element || l.conditional || l.in_loop ? ConstValue{} : const_eval(pf.text(l.meta_arg), env(fv));
    if (v.known()) (*scope)[std::string(name)] = v;
    else scope->erase(std::string(name));
  }
}

// The path of `M98 P{…}` when its expression is known at boot.
std::optional<std::string> Builder::evaluated_path(const FileUnit& u, const Command& c, FileValues& fv, uint32_t line) {
  const ParsedFile& pf = u.parsed;
  const ParamRef P = pf.find(c, 'P');
  if (!P || P->kind != ValueKind::Expression) return std::nullopt;
  std::string_view e = pf.text(P->value);
  if (e.size() < 2 || e.front() != '{' || e.back() != '}') return std::nullopt;
  assign_until(u, fv, line);
  const ConstValue v = const_eval(e.substr(1, e.size() - 2), env(fv));
  if (v.kind != ConstValue::Kind::String) return std::nullopt;
  return v.str;
}

void Builder::call(const std::string& name, CallKind kind, NodeId site, bool maybe, uint16_t depth, bool report_missing,
                   uint32_t tool) {
  bool outside = false;
  auto path = resolve_sd_path(sys_dir_, name, &outside);
  if (!path) {
    record({outside ? GraphEvent::Kind::OutsideRoot : GraphEvent::Kind::OtherVolume, site, name});
    return;
  }
  const FileUnit* u = m_.load(*path);
  if (!u) {
    bool unreadable = std::any_of(m_.problems().begin(), m_.problems().end(),
                                  [&](const LoadProblem& p) { return to_lower(p.sd_path) == to_lower(*path); });
    if (unreadable) record({GraphEvent::Kind::UnreadableFile, site, *path});
    else if (report_missing) record({GraphEvent::Kind::MissingFile, site, *path});
    return;
  }
  if (std::find(stack_.begin(), stack_.end(), u->index) != stack_.end()) {
    record({GraphEvent::Kind::Cycle, site, *path});
    return;
  }
  const int limit = max_stack_depth(o_.firmware);
  if (depth + 1 > limit || depth + 1 > 64) {
    record({GraphEvent::Kind::TooDeep, site, *path, limit});
    return;
  }
  run_file(*u, kind, site, maybe, static_cast<uint16_t>(depth + 1), tool);
}

const FileUnit* Builder::tool_macro(std::string_view kind, int tool) {
  auto numbered = resolve_sd_path(sys_dir_, std::string(kind) + std::to_string(tool) + ".g");
  if (numbered)
    if (const FileUnit* u = m_.load(*numbered)) return u;
  if (o_.firmware >= kRrf3_5) {  // generic fallbacks from 3.5 (commit 7cea891d)
    auto generic = resolve_sd_path(sys_dir_, std::string(kind) + ".g");
    if (generic) return m_.load(*generic);
  }
  return nullptr;
}

const std::vector<uint32_t>& Builder::acting_commands(const FileUnit& u) {
  auto [it, fresh] = acting_.try_emplace(u.index);
  if (!fresh) return it->second;
  const ParsedFile& pf = u.parsed;
  std::vector<uint32_t>& out = it->second;
  for (const auto& [letter, number] : {std::pair{'T', -1}, {'M', 98}, {'M', 501}, {'M', 505}})
    for (uint32_t i : pf.with_code(letter, number))
      if (pf.commands.code(i).fraction < 0) out.push_back(i);
  // G28, G29 and G32 may run macros too, and act only on what follows them on their line (drops_rest_of_line).
  for (const int number : {28, 29, 32})
    for (uint32_t i : pf.with_code('G', number))
      if (pf.commands.code(i).fraction < 0 && i + 1 < pf.commands.size() &&
          pf.commands.code(i + 1).line == pf.commands.code(i).line)
        out.push_back(i);
  std::sort(out.begin(), out.end());
  return out;
}

void Builder::tool_change(const FileUnit& u, const Command& c, NodeId site, bool maybe, uint16_t depth) {
  const ParsedFile& pf = u.parsed;
  int bits = 7;
  auto p = get_int(pf, c, 'P');
  if (p.known()) bits = static_cast<int>(p.value);
  else if (p.present()) bits = -1;  // unknown
  int target;
  if (c.number_expr) target = kUnknownTool;
  else if (c.number < 0) target = kNoTool;  // T-1: deselect
  else target = c.number;
  if (!c.has_number && !c.number_expr) return;  // a bare `T` only reports; `T R1` and friends: not modelled
  if (target == kUnknownTool || bits < 0) {
    current_tool_ = kUnknownTool;
    push(Node{NodeKind::ToolSelect, CallKind::Boot, true, depth, u.index, kNoToolNumber, g_.nodes[site].enter, site});
    return;
  }
  if (target == current_tool_) return;  // same tool: no macros run
  if ((bits & 1) && current_tool_ >= 0) {
    if (const FileUnit* f = tool_macro("tfree", current_tool_))
      call(f->sd_path, CallKind::ToolFree, site, maybe, depth, false, static_cast<uint32_t>(current_tool_));
  }
  if (target >= 0 && (bits & 2)) {
    if (const FileUnit* f = tool_macro("tpre", target))
      call(f->sd_path, CallKind::ToolPre, site, maybe, depth, false, static_cast<uint32_t>(target));
  }
  push(Node{NodeKind::ToolSelect, CallKind::Boot, maybe, depth, u.index,
            target < 0 ? kNoToolNumber : static_cast<uint32_t>(target), g_.nodes[site].enter, site});
  if (target >= 0 && (bits & 4)) {
    if (const FileUnit* f = tool_macro("tpost", target))
      call(f->sd_path, CallKind::ToolPost, site, maybe, depth, false, static_cast<uint32_t>(target));
  }
  current_tool_ = maybe ? kUnknownTool : target;
}

void Builder::run_file(const FileUnit& u, CallKind call_kind, NodeId call_site, bool maybe, uint16_t depth,
                       uint32_t tool) {
  if (full()) return;
  if (booting_) reached_.insert(u.index);
  const NodeId enter = push(Node{NodeKind::Enter, call_kind, maybe, depth, u.index, tool,
                                 call_site == kNoNode ? kNoNode : g_.nodes[call_site].enter, call_site});
  stack_.push_back(u.index);
  const ParsedFile& pf = u.parsed;
  // The commands between those the graph acts on are pushed a stretch at a time (lint/boot/stretches.h).
  const std::vector<uint32_t>& acts = acting_commands(u);
  FileValues fv{assignment_lines(u)};
  Stretches stretches(pf, chains(u), [&](uint32_t line) {
    assign_until(u, fv, line);
    return const_eval(pf.text(pf.lines[line].meta_arg), env(fv));
  });
  uint32_t ci = 0;                       // the next command to push
  auto push_until = [&](uint32_t end) {  // pushes commands [ci, end); false when the node limit cut them short
    while (ci < end) {
      const Stretches::Stretch st = stretches.next(ci, end);
      if (!st.runs) {
        ci = st.end;
        continue;
      }
      const size_t room = o_.max_nodes - std::min(o_.max_nodes, g_.nodes.size());
      const auto n = static_cast<uint32_t>(std::min<size_t>(st.end - ci, room));
      const bool m = maybe || (st.in_block && !st.certain);
      g_.nodes.push_commands(Node{NodeKind::Command, call_kind, m, depth, u.index, ci, enter, kNoNode}, n);
      ci += n;
      if (ci < st.end) {
        g_.truncated = true;
        return false;
      }
    }
    return true;
  };
  for (const uint32_t a : acts) {
    if (a < ci) continue;  // after a macro call on its line: never runs
    if (!push_until(a) || full()) break;
    const CommandTable::Code code = pf.commands.code(a);
    const Stretches::Stretch st = stretches.next(a, a + 1);
    if (!st.runs) {  // in a branch known not to run
      ci = a + 1;
      continue;
    }
    const bool m = maybe || (pf.lines.in_block(code.line) && !st.certain);
    const NodeId id = push(Node{NodeKind::Command, call_kind, m, depth, u.index, a, enter, kNoNode});
    ++ci;
    if (code.letter == 'T') {
      tool_change(u, pf.commands[a], id, m, depth);
    } else if (code.number == 98) {
      // A macro runs its M98 calls each time it runs (tool macros run for every T): read each path once.
      auto [it, fresh] = m98_paths_.try_emplace(uint64_t{u.index} << 32 | a);
      if (fresh) {
        auto p = get_string(pf, pf.commands[a], 'P');
        if (p.known()) it->second = std::move(p.value);
      }
      if (it->second) {
        call(*it->second, CallKind::M98, id, m, depth, true);
      } else if (auto path = evaluated_path(u, pf.commands[a], fv, code.line)) {
        g_.evaluated_calls.push_back(id);
        call(*path, CallKind::M98, id, m, depth, true);
      }
    } else if (code.number == 501) {
      call("config-override.g", CallKind::M501, id, m, depth, true);
    } else if (code.letter == 'M' && code.number == 505) {
      auto p = get_string(pf, pf.commands[a], 'P');
      if (p.known() && !m) {
        // Platform::SetSysDir keeps the old folder when "0:" + the new one + "/" does not fit MaxFilenameLength (120):
        // a relative M505 repeated in a loop or in concatenated configs cannot grow the path without bound.
        if (auto d = resolve_sd_path(sys_dir_, p.value); d && d->size() + 3 <= kMaxFilenameLength) sys_dir_ = *d;
      }
    }
    if (drops_rest_of_line(pf, pf.commands[a]))
      while (ci < pf.commands.size() && pf.commands.code(ci).line == code.line) ++ci;
  }
  if (!g_.truncated && !full()) push_until(static_cast<uint32_t>(pf.commands.size()));
  assign_until(u, fv, static_cast<uint32_t>(pf.lines.size()));  // the file's globals hold for what runs next
  stack_.pop_back();
  push(Node{NodeKind::Leave, call_kind, maybe, depth, u.index, tool, enter, call_site});
}

Graph Builder::build() {
  // Boot: config.g (fallback config.g.bak), then runonce.g.
  const FileUnit* config = m_.load(o_.sys_dir + "/config.g");
  if (!config) config = m_.load(o_.sys_dir + "/config.g.bak");
  if (config) {
    Segment seg;
    seg.begin = 0;
    seg.unit = config->index;
    seg.boot = true;
    booting_ = true;
    run_file(*config, CallKind::Boot, kNoNode, false, 1);
    if (const FileUnit* ro = m_.load(sys_dir_ + "/runonce.g")) {
      if (std::find(stack_.begin(), stack_.end(), ro->index) == stack_.end())
        run_file(*ro, CallKind::RunOnce, kNoNode, false, 1);
    }
    booting_ = false;
    seg.end = static_cast<NodeId>(g_.nodes.size());
    g_.segments.push_back(seg);
  }
  if (!o_.include_entries) return std::move(g_);
  for (const std::string& path : machine_files(m_.reader(), o_.sys_dir)) {
    if (full()) break;
    const FileUnit* u = m_.load(path);
    if (!u || reached_.count(u->index)) continue;
    const std::string lower = to_lower(u->sd_path);
    if (lower.ends_with("/config.g.bak") || lower.ends_with("/config-override.g")) {
      // config-override.g not loaded by an M501 is still linted, as an entry.
      if (lower.ends_with("/config.g.bak")) continue;
    }
    Segment seg;
    seg.begin = static_cast<NodeId>(g_.nodes.size());
    seg.unit = u->index;
    current_tool_ = kUnknownTool;
    sys_dir_ = o_.sys_dir;
    run_file(*u, CallKind::Entry, kNoNode, false, 1);
    seg.end = static_cast<NodeId>(g_.nodes.size());
    g_.segments.push_back(seg);
  }
  return std::move(g_);
}

bool is_gcode_name(std::string_view path, bool allow_no_extension) {
  size_t slash = path.rfind('/');
  std::string_view base = path.substr(slash == std::string_view::npos ? 0 : slash + 1);
  if (base.empty() || base.front() == '.') return false;
  std::string l = to_lower(base);
  if (l.ends_with(".g")) return true;
  return allow_no_extension && l.find('.') == std::string::npos;
}

}  // namespace

std::vector<std::string> machine_files(FileReader& reader, const std::string& sys_dir) {
  std::vector<std::string> out;
  for (auto& p : reader.list(sys_dir))
    if (is_gcode_name(p, false)) out.push_back(p);
  for (auto& p : reader.list("/macros"))
    if (is_gcode_name(p, true)) out.push_back(p);
  for (auto& p : reader.list("/filaments"))
    if (is_gcode_name(p, false)) out.push_back(p);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Graph build_graph(Machine& machine, const GraphOptions& opts) { return Builder(machine, opts).build(); }

}  // namespace rrflint
