#include "lint/engine/schedule.h"

#include <atomic>
#include <utility>

#include "lint/base/parallel.h"
#include "lint/base/trace.h"

namespace rrflint {

void run_file_rules(const Machine& m, const FileUnit& u, const Target& target, const LintOptions& options,
                    const std::vector<const Rule*>& rules, Sink& out, bool whole_card) {
  const FileContext fc{m, u, target, options};
  for (const Rule* r : rules)
    if (r->check_file && r->whole_card == whole_card) {
      const trace::Scope time("rule", r->meta.name);
      r->check_file(fc, out);
    }
}

bool file_rules_in_parallel(const Machine& m, const LintOptions& options) {
  size_t bytes = 0;
  for (uint32_t i = 0; i < m.unit_count(); ++i) bytes += m.unit(i).source->size();
  return options.threads > 1 && bytes >= 2 * options.part_bytes;
}

void run_file_rules_parallel(const Machine& m, const Target& target, const LintOptions& options,
                             const RuleSet& rule_set, const std::vector<const Rule*>& rules,
                             const std::function<void()>& build, const std::function<void(Sink&)>& forward_pass,
                             Sink& sink, std::vector<std::vector<Directive>>& directives) {
  // The tasks: (file, rule) for the files loaded so far and the rules of one file; the suppression comments of
  // those files; then, once the graph is built, each whole-card rule on every file, and all of the files the
  // graph loaded.
  // The files loaded so far, as pointers: the graph may add files (and move Machine's list) while tasks run.
  std::vector<const FileUnit*> loaded;
  for (uint32_t i = 0; i < m.unit_count(); ++i) loaded.push_back(&m.unit(i));
  std::vector<std::pair<const FileUnit*, const Rule*>> own;
  std::vector<const Rule*> whole;
  for (const Rule* r : rules)
    if (r->check_file && r->whole_card) whole.push_back(r);
  for (const FileUnit* u : loaded)
    for (const Rule* r : rules)
      if (r->check_file && !r->whole_card) own.emplace_back(u, r);
  const size_t n_dirs = options.inline_suppressions ? loaded.size() : 0;
  const size_t n_early = own.size() + n_dirs;
  std::vector<Sink> sinks(n_early + whole.size() + 1);
  directives.resize(n_dirs);
  std::vector<std::vector<Directive>> later_directives;  // of the files the graph loaded
  Sink node_sink;
  std::atomic<bool> built{false};
  run_tasks(
      sinks.size(), options.threads,
      [&] {
        struct Done {  // the waiting tasks go on even if the graph throws (the error is rethrown)
          std::atomic<bool>& b;
          ~Done() {
            b = true;
            b.notify_all();
          }
        };
        {
          Done done{built};
          build();
        }
        forward_pass(node_sink);
      },
      [&](size_t k) {
        if (k < own.size()) {
          const FileContext fc{m, *own[k].first, target, options};
          const trace::Scope time("rule", own[k].second->meta.name);
          return own[k].second->check_file(fc, sinks[k]);
        }
        if (k < n_early) {
          const trace::Scope time("suppression comments");
          directives[k - own.size()] = parse_directives(loaded[k - own.size()]->parsed, rule_set);
          return;
        }
        built.wait(false);
        if (k < n_early + whole.size()) {
          const Rule* r = whole[k - n_early];
          const trace::Scope time("rule", r->meta.name);
          for (uint32_t i = 0; i < m.unit_count(); ++i)
            r->check_file(FileContext{m, m.unit(i), target, options}, sinks[k]);
          return;
        }
        trace::mark("last task started");  // this branch is the last task
        for (auto i = static_cast<uint32_t>(loaded.size()); i < m.unit_count(); ++i) {
          run_file_rules(m, m.unit(i), target, options, rules, sinks[k], false);
          if (options.inline_suppressions) later_directives.push_back(parse_directives(m.unit(i).parsed, rule_set));
        }
      });
  trace::mark("tasks joined");
  for (auto& d : later_directives) directives.push_back(std::move(d));
  auto into_sink = [&](Diagnostic&& d) { sink.diagnostics().push_back(std::move(d)); };
  for (Sink& part : sinks) part.diagnostics().drain(into_sink);
  node_sink.diagnostics().drain(into_sink);
}

}  // namespace rrflint
