// `rrflint check`: plan the jobs, lint each machine with its own settings, apply fixes (--fix, --diff) or add
// suppressions (--add-suppressions), render, and choose the exit code.
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <thread>
#include <unordered_map>

#include "cli/cli.h"
#include "frontend/platform.h"
#include "lint/base/parallel.h"
#include "lint/base/trace.h"
#include "lint/engine/suppress.h"
#include "lint/render/render.h"

namespace rrflint::cli {
namespace {

struct Totals {
  std::vector<Diagnostic> diags;
  size_t linted = 0;       // files linted and reported on (never 0 in a run that passes)
  bool lone_hint = false;  // a lone file or stdin was linted with no card around it (say so once)
  size_t files = 0, fixed = 0, fixed_files = 0, suppressions = 0, suppressed_files = 0;
  size_t left_out = 0;  // files of cards linted whole that exclude or .gitignore left out of the report
  bool failing = false, io_error = false;
  std::string diff;
  std::map<std::string, std::string> diffs;  // each file's part of `diff`, by its real path, to give it once
  std::optional<std::string> stdout_text;    // fixed or annotated stdin
  std::vector<MachineTarget> machines;       // each linted machine's firmware target (json)
  std::vector<std::string> inputs;           // the files on disk this run read: no report may be written over one
  std::vector<fs::path> roots;               // the folders named (PlanStats::roots), for write_atomic
};

// The threads of one run: --jobs, or the default.
unsigned co_threads(const CheckOptions& co) { return co.jobs > 0 ? co.jobs : default_threads(); }

// A machine linted ahead, on a worker thread, with its own SourceManager (run_job adopts its files).
struct Prelinted {
  Effective eff;
  SourceManager sources;
  MachineResult result;
  std::exception_ptr error;
};

// Lints the machines of plain `check` runs on up to `threads` threads. Machines are independent: each has its
// own reader and sources, and the rules keep no state. Settings are resolved first, on this thread.
std::vector<std::unique_ptr<Prelinted>> lint_ahead(const std::vector<Job>& jobs, Settings& settings, unsigned threads) {
  std::vector<std::unique_ptr<Prelinted>> out(jobs.size());
  std::vector<size_t> todo;
  for (size_t i = 0; i < jobs.size(); ++i) {
    if (jobs[i].excluded) continue;
    out[i] = std::make_unique<Prelinted>();
    if (!job_settings(jobs[i], settings, threads, out[i]->eff)) return {};  // run_job reports the error in order
    todo.push_back(i);
  }
  run_tasks(todo.size(), threads, [&](size_t k) {
    Prelinted& p = *out[todo[k]];
    try {
      JobReader reader(jobs[todo[k]]);
      p.result = lint_machine(p.sources, reader, builtin_rules(), p.eff.lint);
    } catch (...) {
      p.error = std::current_exception();  // reported by run_job, in order
    }
  });
  return out;
}

// One job once its settings are known: lint (unless linted ahead), then the requested rewrite, then collect what
// is to be reported.
struct JobRun {
  const Job& job;
  const CheckOptions& co;
  Settings& settings;
  GitIgnore& gitignore;
  SourceManager& sm;
  Totals& t;
  const Effective& eff;
  JobReader reader{job};
  std::unordered_map<FileId, bool> reportable_memo;  // decided once per file: a card's files have many findings each
  MachineResult r;

  bool reportable(const SourceFile& f) {
    if (!job.card) return true;
    auto [it, fresh] = reportable_memo.try_emplace(f.id(), true);
    if (!fresh) return it->second;
    const std::string sd = to_lower(f.sd_path());
    if (!job.report_all) it->second = job.only.count(sd) > 0;
    else if (job.stdin_bytes && sd == to_lower(job.stdin_sd_path)) it->second = true;
    else if (job.named_despite_exclusion) it->second = true;
    else if (auto abs = reader.disk_path(f.sd_path()))
      it->second = !settings.excluded(*abs) && !(co.plan.respect_gitignore && gitignore.ignored(*abs));
    return it->second;
  }

  // Lints the machine, or takes the result linted ahead, and notes what could not be linted.
  void lint(std::unique_ptr<Prelinted> pre) {
    if (pre) {
      if (pre->error) std::rethrow_exception(pre->error);
      r = std::move(pre->result);
      shift_file_ids(r, sm.adopt(pre->sources));
    } else {
      r = lint_machine(sm, reader, builtin_rules(), eff.lint);
    }
    if (job.report_all && co.plan.respect_gitignore && !job.named_despite_exclusion) {
      // One `git check-ignore` for the whole card rather than one per file.
      std::vector<std::string> files;
      for (uint32_t i = 0; i < r.machine->unit_count(); ++i)
        if (auto abs = reader.disk_path(r.machine->unit(i).sd_path)) files.push_back(std::move(*abs));
      gitignore.prefetch(files);
    }
    if (note_unlinted(job, eff, *r.machine, t.lone_hint)) t.io_error = true;
    if (r.graph.truncated) warning(truncated_warning(job.title, eff.lint.max_graph_nodes));
    for (uint32_t i = 0; i < r.machine->unit_count(); ++i)
      if (reportable(*r.machine->unit(i).source)) ++t.linted;
  }

  // --fix / --diff: apply fixes round after round until none applies (at most 10 rounds), relinting after each,
  // undoing a round that makes a syntax error (run_fix_rounds). Both are bugs in a rule's fix, and said so.
  FixRounds fix_rounds() {
    FixOptions fo;
    fo.unsafe = co.unsafe_fixes;
    FixRounds fixed = run_fix_rounds(
        sm, r, fo,
        [&](FileId id) {
          const SourceFile& f = sm.get(id);
          return reportable(f) && (reader.disk_path(f.sd_path()) || job.stdin_bytes);
        },
        [&](const std::string& sd, const std::string& text) { reader.set(sd, text); },
        [&] { return lint_machine(sm, reader, builtin_rules(), eff.lint); });
    t.fixed += fixed.fixed;
    for (const auto& [sd, codes] : fixed.reverted)
      warning(
          fmt::format("{}: the fixes of {} made a syntax error in it, so they were undone and the file was not "
                      "fixed further: this is a bug in rrflint, please report it with the file",
                      fixed.display[sd], fmt::join(codes, ", ")));
    if (!fixed.settled)
      warning(
          fmt::format("fixes still apply after {} rounds of --fix: run it again to apply them, and please report "
                      "this with the files (each fix should settle in a round or two)",
                      fo.max_rounds));
    return fixed;
  }

  // Where a fix may write through a symbolic link: below a folder named on the command line, the job's card or a
  // lone file's folder.
  std::vector<fs::path> write_roots() const {
    std::vector<fs::path> roots = t.roots;
    roots.push_back(job.card ? job.card->root : fs::absolute(job.standalone).parent_path());
    return roots;
  }

  // --diff: a file's part of the diff, as --fix would write it: not for a file --fix would refuse (outside the
  // linted folders), and once per file however many cards reach it (by its real name).
  void diff_part(const std::string& sd, const std::string& before, const std::string& text, const std::string& shown,
                 size_t fixes, const std::vector<fs::path>& roots) {
    const auto disk = reader.disk_path(sd);
    auto uncount = [&] {
      --t.fixed_files;
      t.fixed -= std::min(t.fixed, fixes);
    };
    fs::path real;  // the file itself, when it can be resolved: the key that gives it once
    if (const std::string why = disk ? outside_roots(*disk, roots, &real) : ""; !why.empty()) {
      error(fmt::format("{}: {}: --fix would not write it, so the diff leaves it out", shown, why));
      t.io_error = true;
      return uncount();
    }
    const std::string name = diff_name(disk, shown);
    std::string chunk = unified_diff(before, text, name);
    const auto [it, fresh] = t.diffs.try_emplace(real.empty() ? name : real.string(), chunk);
    if (fresh) {
      t.diff += chunk;
      return;
    }
    uncount();
    if (it->second != chunk)
      warning(
          fmt::format("{}: two cards fix this file differently; the diff holds the first one's (run --diff "
                      "again once it is applied)",
                      name));
  }

  // --fix writes the fixed files (a file that cannot be written keeps its text and its findings), --diff collects
  // the diff.
  void write_fixes(FixRounds& fixed) {
    auto& original = fixed.original;
    auto& current = fixed.current;
    auto& display = fixed.display;
    auto& fixed_in = fixed.fixed_in;
    const std::vector<fs::path> roots = write_roots();
    bool unwritten = false;
    for (const auto& [sd, text] : current) {
      const std::string& before = original[sd];
      if (before == text) continue;
      ++t.fixed_files;
      if (co.diff) {
        diff_part(sd, before, text, display[sd], fixed_in[sd], roots);
        continue;
      }
      auto disk = reader.disk_path(sd);
      if (!disk) {
        t.stdout_text = text;  // stdin: the fixed text goes to stdout
        continue;
      }
      std::string err;
      if (!write_atomic(*disk, before, text, roots, &err)) {
        // The file keeps its text: its fixes are not counted, and its findings are reported as they stand.
        error(fmt::format("{}: {}; its findings are reported as they are", display[sd], err));
        t.io_error = true;
        t.fixed -= std::min(t.fixed, fixed_in[sd]);
        --t.fixed_files;
        reader.set(sd, before);
        unwritten = true;
      }
    }
    if (unwritten) r = lint_machine(sm, reader, builtin_rules(), eff.lint);
    if (job.stdin_bytes && co.fix && !t.stdout_text) t.stdout_text = std::string(std::string_view(*job.stdin_bytes));
  }

  // --add-suppressions: a same-line `; rrflint: disable=…` for every finding still reported.
  void add_suppressions() {
    std::map<FileId, std::map<uint32_t, std::vector<std::string>>> by_file;
    for (const Diagnostic& d : r.diagnostics) {
      if (d.loc.file == kNoFile || is_suppression_finding(d)) continue;
      const SourceFile& f = sm.get(d.loc.file);
      if (!reportable(f)) continue;
      auto& names = by_file[d.loc.file][f.line_of(d.loc.span.begin)];
      if (std::find(names.begin(), names.end(), std::string(d.name)) == names.end()) names.emplace_back(d.name);
    }
    for (uint32_t i = 0; i < r.machine->unit_count(); ++i) {
      const FileUnit& u = r.machine->unit(i);
      auto it = by_file.find(u.source->id());
      if (it == by_file.end()) continue;
      std::vector<Edit> edits = suppression_edits(u.parsed, builtin_rules(), it->second, *co.add_suppressions);
      std::string text(u.source->text());
      const std::string before = text;
      apply_edits(text, edits);
      if (text == before) continue;
      auto disk = reader.disk_path(u.sd_path);
      std::string err;
      if (!disk) {
        t.stdout_text = text;
      } else if (!write_atomic(*disk, before, text, write_roots(), &err)) {
        error(fmt::format("{}: {}", u.source->display_path(), err));
        t.io_error = true;
        continue;  // not counted: nothing was added to this file
      }
      for (const auto& [line, names] : it->second) t.suppressions += names.size();
      ++t.suppressed_files;
    }
    if (job.stdin_bytes && !t.stdout_text) t.stdout_text = std::string(std::string_view(*job.stdin_bytes));
  }

  // The findings to report go to the totals; --verbose prints the target and its evidence.
  void collect() {
    for (uint32_t i = 0; i < r.machine->unit_count(); ++i)
      if (reportable(*r.machine->unit(i).source)) ++t.files;
      else if (job.report_all) ++t.left_out;  // (a card's other files are not reported when one file is named)
    std::erase_if(r.diagnostics,
                  [&](const Diagnostic& d) { return d.loc.file != kNoFile && !reportable(sm.get(d.loc.file)); });
    for (const Diagnostic& d : r.diagnostics) t.failing = t.failing || d.severity >= eff.fail_on;
    // Taken over whole when it is the first machine's (a copy, and a vector grown one finding at a time, were a
    // quarter of the peak memory of a config.g with 100,000 findings).
    if (t.diags.empty()) {
      t.diags = std::move(r.diagnostics);
    } else {
      t.diags.insert(t.diags.end(), std::make_move_iterator(r.diagnostics.begin()),
                     std::make_move_iterator(r.diagnostics.end()));
    }
    r.diagnostics = {};
    t.machines.push_back(MachineTarget{job.title, r.target});
    for (uint32_t i = 0; i < r.machine->unit_count(); ++i)
      if (auto abs = reader.disk_path(r.machine->unit(i).sd_path)) t.inputs.push_back(std::move(*abs));
    if (eff.config)
      for (const fs::path& f : eff.config->files) t.inputs.push_back(f.string());
    if (job.stdin_bytes) t.inputs.push_back(co.plan.stdin_filename);  // the file it stands for (none: "")
    if (co.verbose) {
      const Target& tg = r.target;
      std::cerr << "rrflint: " << job.title << ": " << tg.reason << "; " << tg.board_reason << "\n";
      for (const Evidence& e : tg.evidence)
        std::cerr << fmt::format("rrflint:   evidence: {} ({}:{})\n", e.what, sm.get(e.loc.file).display_path(),
                                 sm.get(e.loc.file).position(e.loc.span.begin).line);
      if (eff.config)
        std::cerr << "rrflint:   config: " << Origin{Origin::Kind::File, eff.config->files.back(), 0}.str() << "\n";
    }
  }
};

// One job: lint (unless linted ahead), then the requested rewrite, then collect what is to be reported.
bool run_job(const Job& job, const CheckOptions& co, Settings& settings, GitIgnore& gitignore, SourceManager& sm,
             Totals& t, std::unique_ptr<Prelinted> pre = nullptr) {
  if (job.excluded) {
    // Excluded stdin: nothing to report, and --fix hands the text back unchanged (an editor must not lose it).
    if ((co.fix || co.add_suppressions) && job.stdin_bytes)
      t.stdout_text = std::string(std::string_view(*job.stdin_bytes));
    return true;
  }
  Effective eff;
  if (pre) eff = std::move(pre->eff);
  else if (!job_settings(job, settings, co_threads(co), eff)) return false;
  JobRun run{job, co, settings, gitignore, sm, t, eff};
  run.lint(std::move(pre));
  if (co.fix || co.diff) {
    FixRounds fixed = run.fix_rounds();
    run.write_fixes(fixed);
  }
  if (co.add_suppressions) {
    run.add_suppressions();
    return true;
  }
  run.collect();
  return true;
}

// Runs every job in order; plain checks lint the machines ahead in parallel, rewriting runs (--fix, --diff,
// --add-suppressions) stay serial. False on a config or option error (reported).
bool run_jobs(const std::vector<Job>& jobs, const CheckOptions& co, Settings& settings, GitIgnore& gitignore,
              SourceManager& sm, Totals& t) {
  std::vector<std::unique_ptr<Prelinted>> ahead;
  const unsigned threads = co_threads(co);
  if (!co.fix && !co.diff && !co.add_suppressions && jobs.size() > 1 && threads > 1)
    ahead = lint_ahead(jobs, settings, threads);
  for (size_t i = 0; i < jobs.size(); ++i) {
    const Job& j = jobs[i];
    if (!run_job(j, co, settings, gitignore, sm, t, i < ahead.size() ? std::move(ahead[i]) : nullptr)) {
      if (settings.config_error()) error(settings.config_error()->str());
      return false;
    }
  }
  return true;
}

// The exit code of a run that linted no file: an error, unless every path was left out on purpose with
// --force-exclude (a pre-commit hook passes every changed file, excluded ones too).
int nothing_linted(const Totals& t, const PlanStats& stats, bool io_error) {
  const bool all_forced = stats.force_excluded > 0 && stats.force_excluded == stats.named;
  if (all_forced && !io_error) {
    if (t.stdout_text) std::cout << *t.stdout_text;
    std::cerr << "rrflint: every path given is excluded (--force-exclude): nothing to lint\n";
    return kExitClean;
  }
  if (t.stdout_text) std::cout << *t.stdout_text;  // --fix on stdin: an editor must get its text back
  for (const std::string& why : stats.empty) error(why);
  if (stats.empty.empty() && t.left_out)
    error("every file of the cards given is left out by `exclude` or .gitignore (name a file to lint it anyway)");
  error("no file was linted");
  return kExitError;
}

// --diff: the diff to `os`, a summary to stderr (with the unsafe fixes it leaves out, as ruff does), the exit code.
int report_diff(std::ostream& os, const Totals& t, const CheckOptions& co, bool io_error) {
  os << t.diff;
  os.flush();
  const size_t hidden = co.unsafe_fixes ? 0 : count(t.diags).unsafe_fixable;
  const std::string more = hidden ? fmt::format(" ({} unsafe fix{} hidden: add --unsafe-fixes to see {})", hidden,
                                                hidden == 1 ? "" : "es", hidden == 1 ? "it" : "them")
                                  : "";
  if (t.fixed_files)
    std::cerr << fmt::format("rrflint: would fix {} finding{} in {} file{}{}\n", t.fixed, t.fixed == 1 ? "" : "s",
                             t.fixed_files, t.fixed_files == 1 ? "" : "s", more);
  else std::cerr << "rrflint: no fixes to apply" << more << "\n";
  if (io_error) return kExitError;
  return t.fixed_files && !co.exit_zero ? kExitFindings : kExitClean;
}

// The report written whole to `os` (stdout, stderr or the -o file)?
bool written(std::ostream& os, const CheckOptions& co) {
  return flushed(os, co.output_file.empty() ? (&os == &std::cerr ? "stderr" : "stdout") : co.output_file, "the report");
}

// The findings of every machine, in a stable order across machines (by path, then position), in `format`.
void render_report(std::ostream* os, const SourceManager& sm, Totals& t, const CheckOptions& co,
                   const std::string& format, const std::string& docs_base) {
  static const std::string kNoPath;
  auto path = [&](const Diagnostic& d) -> const std::string& {
    return d.loc.file == kNoFile ? kNoPath : sm.get(d.loc.file).display_path();
  };
  auto before = [&](const Diagnostic& a, const Diagnostic& b) {
    const std::string &fa = path(a), &fb = path(b);
    if (fa != fb) return fa < fb;
    return std::tie(a.loc.span.begin, a.code) < std::tie(b.loc.span.begin, b.code);
  };
  // One machine's findings come sorted already; a stable sort would take a buffer of half of them.
  if (!std::is_sorted(t.diags.begin(), t.diags.end(), before)) std::stable_sort(t.diags.begin(), t.diags.end(), before);
  std::error_code ec;
  RenderOptions ro;
  ro.rules = &builtin_rules();
  ro.docs_base = docs_base;
  ro.files_checked = t.files;
  ro.fixed = t.fixed;
  ro.machines = std::move(t.machines);
  ro.unsafe_fixes_enabled = co.unsafe_fixes;
  ro.threads = co_threads(co);
  ro.cwd = fs::current_path(ec);
  ro.uri_base = repo_root(ro.cwd).value_or(ro.cwd);
  if (!co.output_file.empty()) ro.color = co.color == "always";
  else ro.color = use_color(co.color, os == &std::cerr ? fileno(stderr) : fileno(stdout));
  if (co.statistics) render_statistics(*os, t.diags, ro, format == "json");
  else render_report_as(format, *os, sm, t.diags, ro);
  os->flush();
}

}  // namespace

std::string truncated_warning(const std::string& title, size_t nodes) {
  const std::string count = nodes >= 1'000'000 ? fmt::format("{} million", nodes / 1'000'000) : std::to_string(nodes);
  return fmt::format(
      "{}: the files run to more than {} commands in all (a macro called many times over, or a very "
      "large file): the machine rules followed those only, and say nothing of the rest",
      title, count);
}

int run_check(const CliOptions& cli, const CheckOptions& co) {
  if (const std::string why = conflicting_options(co); !why.empty()) {
    error(why);
    return kExitError;
  }
  Settings settings(cli);
  std::vector<Job> jobs;
  bool io_error = false;
  std::vector<std::string> paths = co.paths;
  if (paths.empty()) paths.push_back(".");
  GitIgnore gitignore;
  PlanStats stats;
  plan(paths, co.plan, settings, gitignore, jobs, io_error, &stats);
  if (settings.config_error()) {
    error(settings.config_error()->str());
    return kExitError;
  }

  std::string format = co.format;
  if (!co.format_given)
    if (const char* gh = std::getenv("GITHUB_ACTIONS"); gh && std::string(gh) == "true") format = "github";

  SourceManager sm;
  Totals t;
  t.roots = stats.roots;
  if (!run_jobs(jobs, co, settings, gitignore, sm, t)) return kExitError;
  io_error = io_error || t.io_error;
  if (t.lone_hint)
    std::cerr
        << "rrflint: note: a file with no SD card around it (no sys/config.g) is linted on its own, as a macro "
           "that runs after boot; to lint it as a config.g, run `rrflint check --stdin-filename config.g - < FILE`\n";
  // Never a pass over nothing.
  if (t.linted == 0) return nothing_linted(t, stats, io_error);
  for (const std::string& why : stats.empty) warning(why);

  if (co.add_suppressions) {
    if (t.stdout_text) std::cout << *t.stdout_text;
    std::cerr << fmt::format("rrflint: added {} suppression{} to {} file{}\n", t.suppressions,
                             t.suppressions == 1 ? "" : "s", t.suppressed_files, t.suppressed_files == 1 ? "" : "s");
    return io_error ? kExitError : kExitClean;
  }

  std::ofstream file_out;
  std::ostream* os = &std::cout;
  if (!co.output_file.empty()) {
    if (std::string err; !open_report_file(co.output_file, t.inputs, file_out, &err)) {
      error(err);
      return kExitError;
    }
    os = &file_out;
  }

  if (co.diff) {
    const int rc = report_diff(*os, t, co, io_error);
    return written(*os, co) ? rc : kExitError;
  }

  // The fixed stdin text owns stdout, with -o too (an editor must get its text back); the report goes elsewhere.
  if (t.stdout_text) {
    std::cout << *t.stdout_text;
    std::cout.flush();
    if (co.output_file.empty()) os = &std::cerr;
  }

  // One report, one docs base: that of the first machine's settings (the command line's order), else the
  // working directory's.
  Effective first;
  Job none;
  if (!job_settings(jobs.empty() ? none : jobs.front(), settings, 1, first)) first.docs_base = default_docs_base();
  render_report(os, sm, t, co, format, first.docs_base);
  trace::mark("rendered");
  if (!written(*os, co) || io_error) return kExitError;
  return t.failing && !co.exit_zero ? kExitFindings : kExitClean;
}

}  // namespace rrflint::cli
