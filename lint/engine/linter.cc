#include "lint/engine/linter.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <tuple>

#include "lint/base/trace.h"
#include "lint/boot/commands.h"
#include "lint/engine/schedule.h"
#include "lint/engine/suppress.h"

namespace rrflint {

std::vector<const Rule*> enabled_rules(const RuleSet& rule_set, const LintOptions& o,
                                       std::vector<std::string>* errors) {
  const auto& all = rule_set.all();
  std::vector<char> on(all.size(), 0);  // by position in `all`
  const auto set = [&](const Rule* r, bool insert) {
    if (auto it = std::find(all.begin(), all.end(), r); it != all.end())
      on[static_cast<size_t>(it - all.begin())] = insert;
  };
  auto add = [&](const std::vector<std::string>& names, bool insert) {
    for (const std::string& n : names) {
      if (iequals(n, "all")) {
        std::fill(on.begin(), on.end(), insert);
        continue;
      }
      // A code prefix such as "RRF3" selects a whole family.
      bool hit = false;
      if (const Rule* exact = rule_set.find(n)) {
        set(exact, insert);
        hit = true;
      } else if (n.size() >= 4 && istarts_with(n, "rrf")) {
        for (size_t i = 0; i < all.size(); ++i)
          if (istarts_with(all[i]->meta.code, n)) {
            on[i] = insert;
            hit = true;
          }
      }
      if (!hit && errors) errors->push_back(n);
    }
  };
  if (o.select.empty()) {
    for (size_t i = 0; i < all.size(); ++i) on[i] = all[i]->meta.default_enabled;
  } else {
    add(o.select, true);
  }
  add(o.extend_select, true);
  add(o.ignore, false);
  std::vector<const Rule*> out;
  for (size_t i = 0; i < all.size(); ++i)
    if (on[i]) out.push_back(all[i]);
  return out;
}

size_t apply_edits(std::string& text, std::vector<Edit> edits) {
  std::stable_sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) {
    return std::tie(a.loc.span.begin, a.loc.span.end) < std::tie(b.loc.span.begin, b.loc.span.end);
  });
  std::string out;
  out.reserve(text.size() + 64);
  uint32_t pos = 0;  // the end of the last edit applied
  size_t applied = 0;
  for (const Edit& e : edits) {
    if (e.loc.span.end > text.size() || e.loc.span.begin > e.loc.span.end) continue;
    if (e.loc.span.begin < pos) continue;  // overlaps: left for the next round
    out.append(text, pos, e.loc.span.begin - pos);
    out += e.replacement;
    pos = e.loc.span.end;
    ++applied;
  }
  out.append(text, pos, std::string::npos);
  text = std::move(out);
  return applied;
}

namespace {

// Which check_node rules a node wakes: by command letter and number, from the rules' `on` lists.
class NodeDispatch {
 public:
  NodeDispatch(const std::vector<const Rule*>& rules, bool every) {
    for (const Rule* r : rules) {
      if (!r->check_node) continue;
      if (every) {
        every_.push_back(r);
        continue;
      }
      Triggers t;
      parse_triggers(r->on, t);  // a malformed list is a test failure (tests/fixtures_test.cc), not a crash
      if (t.any_t) t_.push_back(r);
      for (auto [letter, n] : t.codes) {
        auto& table = letter == 'G' ? g_ : m_;
        if (n >= static_cast<int>(table.size())) table.resize(static_cast<size_t>(n) + 1);
        if (table[n].empty() || table[n].back() != r) table[n].push_back(r);
      }
    }
  }
  /// The rules for a node that is not a command.
  const std::vector<const Rule*>& rules_for_other() const { return every_; }
  /// The rules for a command node of code `c`.
  const std::vector<const Rule*>& rules_for(const CommandTable::Code& c) const {
    if (!every_.empty()) return every_;
    if (c.letter == 'T') return t_;
    const auto& table = c.letter == 'G' ? g_ : m_;
    if (c.number < 0 || c.number >= static_cast<int>(table.size())) return none_;
    return table[c.number];
  }

 private:
  std::vector<std::vector<const Rule*>> g_, m_;
  std::vector<const Rule*> t_, every_, none_;
};

// The dispatch table for these rules, made once per thread for as long as the rules stay the same: a language
// server or a fuzzer lints small files many times with one rule set, and parsing every rule's `on` list cost 7%
// of such a lint (bench/RESULTS.md). The table depends only on what the key holds (each rule, whether it has a node
// check, its `on` list, compared by content), so a rule set made afresh at the same addresses cannot meet a stale
// table.
const NodeDispatch& dispatch_for(const std::vector<const Rule*>& rules, bool every) {
  struct Key {
    const Rule* rule;
    bool node;
    std::string_view on;
    bool operator==(const Key& o) const { return rule == o.rule && node == o.node && on == o.on; }
  };
  thread_local struct {
    std::vector<Key> key;
    std::string on_text;  // the `on` lists the key's views point into (a rule may not outlive this lint)
    bool every = false;
    std::optional<NodeDispatch> table;
  } last;
  const auto same = [&] {
    if (!last.table || last.every != every || last.key.size() != rules.size()) return false;
    for (size_t i = 0; i < rules.size(); ++i)
      if (!(last.key[i] == Key{rules[i], rules[i]->check_node != nullptr, rules[i]->on})) return false;
    return true;
  };
  if (!same()) {
    last.table.emplace(rules, every);
    last.every = every;
    last.key.clear();
    last.on_text.clear();
    for (const Rule* r : rules) last.on_text.append(r->on);
    size_t at = 0;
    for (const Rule* r : rules) {
      last.key.push_back(Key{r, r->check_node != nullptr, std::string_view(last.on_text).substr(at, r->on.size())});
      at += r->on.size();
    }
  }
  return *last.table;
}

}  // namespace

void shift_file_ids(MachineResult& r, FileId base) {
  auto shift = [base](Location& l) {
    if (l.file != kNoFile) l.file += base;
  };
  for (Diagnostic& d : r.diagnostics) {
    shift(d.loc);
    for (Note& n : d.notes) shift(n.loc);
    if (d.fix)
      for (Edit& e : d.fix->edits) shift(e.loc);
  }
  for (Evidence& e : r.target.evidence) shift(e.loc);
}

namespace {

// 8. A file with CR-only line endings is one line to targets that do not end a line at CR (RRF107): the firmware
// never sees its lines 2…n as lines, so only the rules that read raw bytes (Rule::raw_bytes) report on them.
// Earlier targets keep everything.
void drop_after_first_line_of_cr_files(MachineResult& res, const SourceManager& sources,
                                       const std::vector<const Rule*>& rules) {
  if (!cr_is_not_a_line_end(res.target.version)) return;
  std::vector<uint32_t> first_line_end(sources.size(), UINT32_MAX);  // by file: UINT32_MAX = not such a file
  bool any = false;
  for (FileId f = 0; f < sources.size(); ++f) {
    const SourceFile& src = sources.get(f);
    if (!src.endings().cr_only()) continue;
    first_line_end[f] = src.line_span(0).end;
    any = true;
  }
  if (!any) return;
  std::set<std::string_view> raw;
  for (const Rule* r : rules)
    if (r->raw_bytes) raw.insert(r->meta.code);
  std::erase_if(res.diagnostics, [&](const Diagnostic& d) {
    return !raw.count(d.code) && d.loc.file < first_line_end.size() && d.loc.span.begin >= first_line_end[d.loc.file];
  });
}

// 9. resurrect.g is a snapshot the firmware writes at every pause of an SD print and on power loss, and only M916
// runs it: none of its lines is the user's mistake, so no finding stands in it
// (docs/firmware-behaviour.md#system-files). Findings elsewhere may still point into it with a note.
void drop_findings_in_firmware_written_files(MachineResult& res, const Machine& m) {
  std::set<FileId> written;
  for (uint32_t i = 0; i < m.unit_count(); ++i)
    if (file_role(m.unit(i).sd_path) == FileRole::Resurrect) written.insert(m.unit(i).source->id());
  if (written.empty()) return;
  std::erase_if(res.diagnostics, [&](const Diagnostic& d) { return written.count(d.loc.file) != 0; });
}

// 10. A line with a line number and a checksum (`N10 G10 P0 X1*104`, RRF110) runs only while its checksum
// matches, and an edit inside it breaks the checksum: RRF would then drop the whole line silently. A fix with
// such an edit is withdrawn (the finding stays, and RRF110 reports the checksum). An edit that rewrites the line
// from its start to the end of the checksum (RRF110's own fix, or one that replaces the whole line) writes its own
// text and keeps its fix.
void drop_fixes_on_checksummed_lines(MachineResult& res, const Machine& m) {
  std::map<FileId, std::vector<Span>> summed;  // by file: each checksummed line to the end of its checksum, in order
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const FileUnit& u = m.unit(i);
    if (!u.parsed.prefilters.any_line_number) continue;  // a checksum follows a line number
    const std::string_view t = u.source->text();
    std::vector<Span> spans;
    for (const Line& line : u.parsed.lines) {
      if (line.checksum) spans.push_back(Span{line.span.begin, checksum_span(t, line).end});
    }
    if (!spans.empty()) summed.emplace(u.source->id(), std::move(spans));
  }
  if (summed.empty()) return;
  auto breaks_a_checksum = [&](const Edit& e) {
    auto f = summed.find(e.loc.file);
    if (f == summed.end()) return false;
    const std::vector<Span>& lines = f->second;
    // The first checksummed line that does not end before the edit begins.
    auto it = std::lower_bound(lines.begin(), lines.end(), e.loc.span.begin,
                               [](const Span& l, uint32_t b) { return l.end < b; });
    for (; it != lines.end() && it->begin <= e.loc.span.end; ++it)
      if (!(e.loc.span.begin <= it->begin && e.loc.span.end >= it->end)) return true;
    return false;
  };
  for (Diagnostic& d : res.diagnostics)
    if (d.fix && std::any_of(d.fix->edits.begin(), d.fix->edits.end(), breaks_a_checksum)) d.fix.reset();
}

}  // namespace

namespace {

// 1. Load and parse every file of the machine. Returns config.g (or its backup), null when there is neither.
const FileUnit* load_card(Machine& m, FileReader& reader, const LintOptions& options) {
  const FileUnit* config = m.load(options.sys_dir + "/config.g");
  if (!config) config = m.load(options.sys_dir + "/config.g.bak");
  {
    std::vector<std::string> files = machine_files(reader, options.sys_dir);
    m.set_listing(files);
    if (options.include_entries)
      for (const std::string& p : files) m.load(p);
  }
  return config;
}

// 3. The ordered command graph and 5. the forward pass of the model with the node rules, and what they share:
// the model builder and the state at the end of boot.
class ModelRun {
 public:
  ModelRun(Machine& machine, MachineResult& result, const LintOptions& lint_options, const NodeDispatch& rules)
      : m(machine), res(result), options(lint_options), dispatch(rules) {}

  void build() {
    GraphOptions go;
    go.firmware = res.target.version;
    go.sys_dir = options.sys_dir;
    go.include_entries = options.include_entries;
    go.max_nodes = options.max_graph_nodes;
    res.graph = build_graph(m, go);
    trace::mark("graph");
    mb.emplace(m, res.graph, res.target.version, res.target.board);
    boot_end = mb->initial_state();
  }

  void forward_pass(Sink& node_sink) {
    auto check_node = [&](const MachineState& s, NodeId id, Runs runs, const Node& node,
                          const std::vector<const Rule*>& node_rules) {
      if (runs == Runs::No || node_rules.empty()) return;
      const NodeContext nc{m, res.graph, res.target, options, s, id, runs, node};
      if (trace::enabled()) {  // each node rule's total time, printed at the end of the pass
        for (const Rule* r : node_rules) {
          const double t0 = trace::now_ms();
          r->check_node(nc, node_sink);
          node_rule_ms[r] += trace::now_ms() - t0;
        }
        return;
      }
      for (const Rule* r : node_rules) r->check_node(nc, node_sink);
    };
    for (const Segment& seg : res.graph.segments) {
      MachineState s = seg.boot ? mb->initial_state() : boot_end;
      if (!seg.boot && !have_boot) s.unknown_baseline = true;
      for (NodeId id = seg.begin; id < seg.end;) {
        const NodeTable::Stretch st = res.graph.nodes.stretch(id);
        const NodeId end = std::min(st.end, seg.end);
        if (st.node.kind != NodeKind::Command) {  // Enter, Leave, ToolSelect: a stretch of one
          mb->decide(s, id, st.node);
          check_node(s, id, mb->runs(id), st.node, dispatch.rules_for_other());
          mb->step(s, id, st.node);
          id = end;
          continue;
        }
        // A run of commands of one file run: they all run or not alike. Most wake no rule and change nothing, so
        // each command's code is read from its record and nothing more is done for those.
        mb->decide_commands(s, id, end, st.node);
        const Runs runs = mb->runs(id);
        const CommandTable& commands = m.unit(st.node.unit).parsed.commands;
        Node node = st.node;
        for (; id < end; ++id) {
          node.index = st.node.index + (id - st.begin);
          const CommandTable::Code code = commands.code(node.index);
          check_node(s, id, runs, node, dispatch.rules_for(code));
          if (ModelBuilder::changes_state(code)) mb->step(s, id, node);
        }
      }
      if (seg.boot) {
        boot_end = s;
        have_boot = true;
      }
    }
    for (const auto& [r, ms] : node_rule_ms) trace::report_ms("node rule", r->meta.name, ms);
    trace::mark("forward pass");
  }

  /// The state at the end of boot, and whether there was a boot segment, into the result.
  void finish() {
    res.end_of_boot = boot_end;
    res.has_boot = have_boot;
  }

 private:
  Machine& m;
  MachineResult& res;
  const LintOptions& options;
  const NodeDispatch& dispatch;
  std::optional<ModelBuilder> mb;
  MachineState boot_end;
  bool have_boot = false;
  std::map<const Rule*, double> node_rule_ms;  // with RRFLINT_TRACE only
};

// The rules that look at the whole machine once the forward pass is done.
void run_end_rules(const MachineResult& res, const LintOptions& options, const std::vector<const Rule*>& rules,
                   Sink& sink) {
  EndContext ec{*res.machine, res.graph, res.target, options, res.end_of_boot};
  for (const Rule* r : rules)
    if (r->check_end) {
      const trace::Scope time("end rule", r->meta.name);
      r->check_end(ec, sink);
    }
}

// 6. Severity overrides, de-duplication (a macro run twice reports once), order: the sink's findings, appended to
// `out` (empty here: the result has no findings before this step).
void finish_diagnostics(Sink& sink, const LintOptions& options, std::vector<Diagnostic>& out) {
  // The findings are sorted by index and moved once, in order, into `out`: sorting the findings themselves took a
  // buffer of half of them, and growing `out` while the sink still held them all doubled them (the peak memory of
  // a config.g with 100,000 findings).
  DiagnosticList& in = sink.diagnostics();
  std::vector<uint32_t> order(in.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t i, uint32_t j) {
    const Diagnostic &a = in[i], &b = in[j];
    return std::tie(a.loc.file, a.loc.span.begin, a.code, a.loc.span.end) <
           std::tie(b.loc.file, b.loc.span.begin, b.code, b.loc.span.end);
  });
  const size_t before = out.size();
  out.reserve(before + order.size());
  for (uint32_t i : order) {
    Diagnostic& d = in[i];
    // A finding reported twice (same rule, place and message) is kept once, as std::unique would after the sort.
    if (out.size() > before) {
      const Diagnostic& last = out.back();
      if (last.code == d.code && last.loc.file == d.loc.file && last.loc.span == d.loc.span &&
          last.message == d.message)
        continue;
    }
    if (auto it = options.severity.find(std::string(d.code)); it != options.severity.end()) d.severity = it->second;
    out.push_back(std::move(d));
  }
  in.clear();
}

}  // namespace

MachineResult lint_machine(SourceManager& sources, FileReader& reader, const RuleSet& rule_set,
                           const LintOptions& options) {
  MachineResult res;
  res.machine = std::make_unique<Machine>(sources, reader);
  Machine& m = *res.machine;
  m.set_threads(options.threads, options.part_bytes);
  m.set_no_prefilters(options.no_prefilters);
  const std::vector<const Rule*> rules = enabled_rules(rule_set, options);

  // 1. Load and parse every file of the machine.
  const FileUnit* config = load_card(m, reader, options);

  // 2. The firmware target.
  trace::mark("loaded");
  res.target = infer_target(m, config, options.firmware, options.board);
  trace::mark("target");

  // 3. The ordered command graph, 4. per-file rules on every file loaded (including those the graph reached) and
  // 5. the forward pass of the model with the node rules. A large machine runs the file rules and its suppression
  // comments as tasks on other threads while this one builds the graph and runs the forward pass
  // (lint/engine/schedule.cc).
  Sink sink;
  const NodeDispatch& dispatch = dispatch_for(rules, options.dispatch_every_node);
  ModelRun run(m, res, options, dispatch);
  std::vector<std::vector<Directive>> directives;  // suppression comments, by unit (parallel runs only)
  const bool parallel = file_rules_in_parallel(m, options);
  if (parallel) {
    run_file_rules_parallel(
        m, res.target, options, rule_set, rules, [&] { run.build(); },
        [&](Sink& node_sink) { run.forward_pass(node_sink); }, sink, directives);
  } else {
    run.build();
    for (uint32_t i = 0; i < m.unit_count(); ++i) {
      run_file_rules(m, m.unit(i), res.target, options, rules, sink, false);
      run_file_rules(m, m.unit(i), res.target, options, rules, sink, true);
    }
    run.forward_pass(sink);
  }
  run.finish();
  trace::mark("model finished");
  run_end_rules(res, options, rules, sink);
  trace::mark("end rules");

  // 6. Severity overrides, de-duplication, order.
  finish_diagnostics(sink, options, res.diagnostics);
  // 7. Per-file ignores and suppression comments (lint/engine/suppress.cc), which add RRF900/RRF901.
  trace::mark("sorted");
  apply_suppressions(res, rule_set, rules, options, parallel && options.inline_suppressions ? &directives : nullptr);
  trace::mark("suppressions");
  drop_after_first_line_of_cr_files(res, sources, rules);
  drop_findings_in_firmware_written_files(res, m);
  drop_fixes_on_checksummed_lines(res, m);
  return res;
}

}  // namespace rrflint
