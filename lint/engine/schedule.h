// The file rules' schedule: which per-file rules run on which file, and, for a large machine, the tasks that run
// them on other threads beside the graph build and the forward pass. The only place that knows tasks and atomics.
#pragma once

#include <functional>
#include <vector>

#include "lint/engine/linter.h"
#include "lint/engine/suppress.h"

namespace rrflint {

/// Runs on `u` every rule of `rules` with a check_file whose whole_card is `whole_card`.
void run_file_rules(const Machine& m, const FileUnit& u, const Target& target, const LintOptions& options,
                    const std::vector<const Rule*>& rules, Sink& out, bool whole_card);

/// Is the machine large enough (and are there threads) to run its file rules as tasks?
bool file_rules_in_parallel(const Machine& m, const LintOptions& options);

/// Runs the file rules of `rules` on every file of `m` (and, with options.inline_suppressions, parses each file's
/// suppression comments into `directives`, by unit) as tasks on up to options.threads threads, while this thread
/// calls `build()` (the graph, which may load more files) and then `forward_pass(node_sink)`. The tasks that read
/// only their own file start at once, those that need every file (Rule::whole_card, and the files the graph
/// loads) once `build()` has returned. Each task reports to its own sink; the sinks are appended to `sink` in a
/// fixed order (the tasks', then the forward pass's), so the findings are the same for any thread count.
void run_file_rules_parallel(const Machine& m, const Target& target, const LintOptions& options,
                             const RuleSet& rule_set, const std::vector<const Rule*>& rules,
                             const std::function<void()>& build, const std::function<void(Sink&)>& forward_pass,
                             Sink& sink, std::vector<std::vector<Directive>>& directives);

}  // namespace rrflint
