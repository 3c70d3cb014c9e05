// The linting pipeline for one machine: load and parse files -> infer the target -> build the graph ->
// one forward pass of the model with the enabled rules -> sorted, de-duplicated diagnostics.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lint/base/diagnostic.h"
#include "lint/boot/graph.h"
#include "lint/boot/infer.h"
#include "lint/boot/model.h"
#include "lint/card/card.h"
#include "lint/engine/rule.h"

namespace rrflint {

struct LintOptions {
  std::optional<Version> firmware;
  std::optional<Board> board;
  std::vector<std::string> select;         // codes or names; "ALL"; empty = the default set
  std::vector<std::string> extend_select;  // added to the selection
  std::vector<std::string> ignore;
  std::map<std::string, Severity> severity;  // per-rule override, by code
  bool tool_changer = false;                 // machine.tool-changer: evidence for RRF305
  bool include_entries = true;               // lint every other macro as its own entry
  std::string sys_dir = "/sys";
  /// Threads one machine may use, and the work worth a thread: a file is parsed in parts of at least
  /// `part_bytes` each, and a machine with twice that much source runs its file rules beside the forward pass.
  /// The findings are the same for any count.
  unsigned threads = 1;
  size_t part_bytes = size_t{2} << 20;
  bool inline_suppressions = true;  // honour `; rrflint: disable=…` comments (--no-inline-suppressions: false)
  /// The graph's node limit (GraphOptions::max_nodes). The front ends take RRFLINT_MAX_NODES from the environment
  /// when it is set, for tests that need to reach the limit quickly.
  size_t max_graph_nodes = 4'000'000;
  /// Per-file ignores (config file): is rule `code` switched off for this file? Null: never.
  std::function<bool(const SourceFile&, std::string_view code)> ignored_in_file;
  /// Tests only: call every check_node rule on every node, ignoring the rules' `on` lists. The fixture runner
  /// lints each case both ways and requires the same findings, which proves the lists complete.
  bool dispatch_every_node = false;
  /// Tests only: parse with every prefilter off (ParseOptions::no_prefilters). The fixture runner lints each case
  /// both ways and requires the same findings, which proves the rules keep the prefilters' contract.
  bool no_prefilters = false;
};

/// Which rules are on, after select/extend/ignore. Unknown names go to `errors`.
std::vector<const Rule*> enabled_rules(const RuleSet& rules, const LintOptions& o,
                                       std::vector<std::string>* errors = nullptr);

struct MachineResult {
  std::unique_ptr<Machine> machine;
  Target target;
  Graph graph;
  MachineState end_of_boot;
  bool has_boot = false;
  std::vector<Diagnostic> diagnostics;  // sorted by file, position, code
};

/// Adds `base` to every FileId in a result (after SourceManager::adopt moved its files).
void shift_file_ids(MachineResult& r, FileId base);

/// Lints the machine that `reader` holds (SD paths: /sys/config.g, /macros/…).
/// `rules` are the rules that exist (usually rules/registry.h's builtin_rules()); `options` choose among them.
MachineResult lint_machine(SourceManager& sources, FileReader& reader, const RuleSet& rules,
                           const LintOptions& options);

/// Applies edits to `text`, skipping any that overlap an earlier one. Returns how many were applied.
size_t apply_edits(std::string& text, std::vector<Edit> edits);

}  // namespace rrflint
