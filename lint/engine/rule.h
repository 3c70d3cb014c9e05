// The rule interface. A rule is metadata, Markdown docs and up to three pure check functions:
//   check_file  per parsed file (lexical rules);
//   check_node  per graph node, called with the machine state *before* the node runs;
//   check_end   once per machine, with the graph and the end-of-boot state.
// Rules report through a Sink and keep no state of their own between calls.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lint/base/diagnostic.h"
#include "lint/boot/commands.h"
#include "lint/boot/graph.h"
#include "lint/boot/infer.h"
#include "lint/boot/model.h"
#include "lint/card/card.h"

namespace rrflint {

enum class FixAvailability : uint8_t { None, Sometimes, Always };

/// How an editor may show the rule's findings (the LSP DiagnosticTag): Unnecessary (faded) for a command, or part
/// of one, that RRF ignores or that has no effect; Deprecated (struck through) for a form RRF has deprecated.
enum class RuleTag : uint8_t { None, Unnecessary, Deprecated };
/// "none", "unnecessary", "deprecated".
constexpr std::string_view tag_name(RuleTag t) {
  return t == RuleTag::Unnecessary ? "unnecessary" : t == RuleTag::Deprecated ? "deprecated" : "none";
}

struct RuleMeta {
  std::string_view code;  // "RRF301"
  std::string_view name;  // "g10-tool-before-definition"
  Severity severity = Severity::Warning;
  bool default_enabled = true;
  FixAvailability fix = FixAvailability::None;
  RuleTag tag = RuleTag::None;
  std::string_view summary;  // one sentence, also the first line of the docs
  std::string_view docs;  // Markdown: What it does / Why is this bad? / Example / Use instead / Fix safety / References
};

struct LintOptions;
class Sink;

/// What a per-file rule sees.
struct FileContext {
  const Machine& machine;
  const FileUnit& unit;
  const Target& target;
  const LintOptions& options;
  const ParsedFile& parsed() const { return unit.parsed; }
  const SourceFile& source() const { return *unit.source; }
  Location at(Span s) const { return Location{unit.source->id(), s}; }
};

/// What a per-node rule sees: the node, the state before it runs, and the whole graph for look-ahead.
struct NodeContext {
  const Machine& machine;
  const Graph& graph;
  const Target& target;
  const LintOptions& options;
  const MachineState& state;  // before this node runs
  NodeId id;
  Runs runs;  // Yes, or Maybe (conditional: the node's effects are then unknown); rules never see Runs::No
  Node self;  // graph.nodes[id], decoded once

  /// Does the node certainly run (not inside an if/while, here or in a caller)?
  bool certain() const { return runs == Runs::Yes; }
  const Node& node() const { return self; }
  const FileUnit& unit() const { return machine.unit(self.unit); }
  const ParsedFile& parsed() const { return unit().parsed; }
  /// Valid for NodeKind::Command only.
  Command command() const { return parsed().commands[self.index]; }
  bool is_command() const { return self.kind == NodeKind::Command; }
  bool is(char letter, int number) const {
    return is_command() && parsed().commands.code(self.index).is(letter, number);
  }
  ParamRef param(char letter) const { return parsed().find(command(), letter); }
  Location at(Span s) const { return Location{unit().source->id(), s}; }
  /// Location of any node's command (for notes: "tool 1 is created here").
  Location where(NodeId other) const;
  /// Is this node in the boot sequence (config.g and what it runs), rather than a standalone entry?
  bool in_boot() const;
  /// The segment holding this node.
  const Segment& segment() const;
  /// This node's G10 form (g10_form with the state before the node), decoded once for all the node rules that
  /// ask: a G10 wakes about ten of them, and each decoding looks up several letters.
  G10Form g10_form() const;

  // The cache behind g10_form(): a NodeContext is made per node and the state does not change while its rules run.
  mutable std::optional<G10Form> g10_form_;
};

/// What an end-of-machine rule sees.
struct EndContext {
  const Machine& machine;
  const Graph& graph;
  const Target& target;
  const LintOptions& options;
  const MachineState& end_of_boot;
  Location where(NodeId id) const;
};

/// Builder returned by Sink::report to add notes and a fix.
class Report {
 public:
  explicit Report(Diagnostic* d) : d_(d) {}
  Report& note(Location loc, std::string message);
  Report& fix(Fix f);
  Diagnostic& diagnostic() { return *d_; }

 private:
  Diagnostic* d_;
};

/// The findings a sink collects, in the order reported, in blocks of 64: a pointer to one stays valid while more
/// are added (Report keeps one), and a block is full before the next is taken. (A std::deque holds two findings
/// per 512-byte block; on a config with 100,000 findings that took 50 MB, twice what the findings need.)
class DiagnosticList {
 public:
  Diagnostic& push_back(Diagnostic&& d) {
    if (size_ % kBlock == 0) blocks_.push_back(std::make_unique<Block>());
    Diagnostic& slot = (*blocks_.back())[size_ % kBlock];
    slot = std::move(d);
    ++size_;
    return slot;
  }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  Diagnostic& operator[](size_t i) { return (*blocks_[i / kBlock])[i % kBlock]; }
  void clear() {
    blocks_.clear();
    size_ = 0;
  }
  /// Hands every finding to `take` in order, freeing each block once it is taken; the list is empty after.
  template <class F>
  void drain(F&& take) {
    for (size_t i = 0; i < size_; ++i) {
      take(std::move((*blocks_[i / kBlock])[i % kBlock]));
      if (i % kBlock == kBlock - 1 || i + 1 == size_) blocks_[i / kBlock].reset();
    }
    clear();
  }

 private:
  static constexpr size_t kBlock = 64;
  using Block = std::array<Diagnostic, kBlock>;
  std::vector<std::unique_ptr<Block>> blocks_;
  size_t size_ = 0;
};

class Sink {
 public:
  /// Reports a finding of `meta` at `loc`. The severity is the rule's (possibly overridden) severity.
  Report report(const RuleMeta& meta, Location loc, std::string message);
  /// Same, with an explicit severity (rules with two levels, e.g. warning/info).
  Report report(const RuleMeta& meta, Severity sev, Location loc, std::string message);
  DiagnosticList& diagnostics() { return out_; }

 private:
  DiagnosticList out_;
};

struct Rule {
  RuleMeta meta;
  void (*check_file)(const FileContext&, Sink&) = nullptr;
  void (*check_node)(const NodeContext&, Sink&) = nullptr;
  void (*check_end)(const EndContext&, Sink&) = nullptr;
  /// check_file reads more than its own file (FileContext::machine: the other files, Machine::has_file,
  /// uses_code …). A large machine runs the other file rules while the graph is built and may still load files;
  /// these run once it is built. (tests/fixtures_test.cc checks that a file rule naming the machine sets it.)
  bool whole_card = false;
  /// The commands check_node is called for, blank-separated: codes such as "G10 M563" (any fraction: "M569"
  /// takes M569.1 too) and "T" for every T command. The linter calls check_node for those nodes only, so the
  /// list must name every command the check can report on (the fixture runner checks it against a run that
  /// calls every rule on every node).
  std::string_view on;
  /// The rule reads the file's bytes, not the lines the firmware makes of them: its findings stand where the
  /// firmware reads a file as one line (a CR-only file, RRF107), which drops every other finding past line 1.
  bool raw_bytes = false;
};

/// A rule's `on` list, parsed. False (with the bad token in `bad`) on a malformed list.
struct Triggers {
  std::vector<std::pair<char, int>> codes;  // ('G', 10), ('M', 563)
  bool any_t = false;
};
bool parse_triggers(std::string_view on, Triggers& out, std::string* bad = nullptr);

/// The rules of a run, sorted by code. The engine knows no rule of its own accord: whoever runs it (the CLI,
/// the tests, the fuzz targets, the benchmarks) passes the set, usually rules/registry.h's builtin_rules().
class RuleSet {
 public:
  explicit RuleSet(std::vector<const Rule*> rules);
  const std::vector<const Rule*>& all() const { return rules_; }
  /// By code ("RRF301") or name ("g10-tool-before-definition"), case-insensitive; nullptr if unknown.
  const Rule* find(std::string_view code_or_name) const;
  /// The rule whose name is nearest to a misspelt one ("g10-mising-z" → g10-missing-z), nullptr when none is near
  /// (a code like "RRF999" has none: codes one digit apart are unrelated rules).
  const Rule* near_miss(std::string_view written) const;

 private:
  std::vector<const Rule*> rules_;
};

}  // namespace rrflint
