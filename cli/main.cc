// rrflint: the command-line front end. Argument parsing, input discovery and exit codes only; the work is
// done by the core library (lint/).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "lint/disk.h"
#include "lint/linter.h"
#include "lint/render/model_render.h"
#include "lint/render/render.h"

namespace fs = std::filesystem;
using namespace rrflint;

namespace {

constexpr int kExitClean = 0, kExitFindings = 1, kExitError = 2;

struct CommonOptions {
  std::string firmware, board;
  std::vector<std::string> select, ignore, extend_select;
  bool tool_changer = false;
};

struct Job {
  std::optional<CardLocation> card;       // a machine on disk
  fs::path standalone;                    // or a lone file
  std::set<std::string> only;             // SD paths to report (empty = everything)
  std::optional<std::string> stdin_bytes; // content for `-`
  std::string stdin_sd_path;
  std::string title;
};

void error(const std::string& msg) { std::cerr << "rrflint: error: " << msg << "\n"; }

bool build_options(const CommonOptions& c, LintOptions& o) {
  if (!c.firmware.empty()) {
    auto v = Version::parse(c.firmware);
    if (!v) {
      error(fmt::format("--firmware: '{}' is not a version (use e.g. 3.5 or 3.4.6)", c.firmware));
      return false;
    }
    o.firmware = *v;
  }
  if (!c.board.empty()) {
    auto b = parse_board(c.board);
    if (!b) {
      error(fmt::format("--board: unknown board '{}' (duet2, duet3-6hc, duet3-mini, maestro)", c.board));
      return false;
    }
    o.board = *b;
  }
  auto split = [](const std::vector<std::string>& in) {
    std::vector<std::string> out;
    for (const auto& s : in) {
      std::stringstream ss(s);
      std::string item;
      while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    }
    return out;
  };
  o.select = split(c.select);
  o.ignore = split(c.ignore);
  o.extend_select = split(c.extend_select);
  o.tool_changer = c.tool_changer;
  std::vector<std::string> unknown;
  enabled_rules(o, &unknown);
  if (!unknown.empty()) {
    error(fmt::format("unknown rule '{}' (see `rrflint rule --all`)", unknown.front()));
    return false;
  }
  return true;
}

// Turns command-line paths into jobs, one per machine. Returns false on an unusable path.
bool plan(const std::vector<std::string>& paths, const std::string& stdin_name, std::vector<Job>& jobs, bool& io_error) {
  std::map<std::string, size_t> by_root;
  auto job_for_card = [&](const CardLocation& c, const std::string& title) -> Job& {
    std::string key = fs::weakly_canonical(c.sys_dir).string();
    if (auto it = by_root.find(key); it != by_root.end()) return jobs[it->second];
    Job j;
    j.card = c;
    j.title = title;
    jobs.push_back(j);
    by_root[key] = jobs.size() - 1;
    return jobs.back();
  };
  for (const std::string& p : paths) {
    if (p == "-") {
      std::string bytes((std::istreambuf_iterator<char>(std::cin)), {});
      fs::path name = stdin_name.empty() ? fs::path("stdin.g") : fs::path(stdin_name);
      std::error_code ec;
      if (!stdin_name.empty()) {
        if (auto card = card_containing(name)) {
          DiskReader probe(card->root, card->sys_dir, fs::current_path());
          if (auto sd = probe.sd_path_of(fs::absolute(name, ec))) {
            Job& j = job_for_card(*card, stdin_name);
            j.only.insert(to_lower(*sd));
            j.stdin_bytes = bytes;
            j.stdin_sd_path = *sd;
            continue;
          }
        }
      }
      Job j;
      j.standalone = name;
      j.stdin_bytes = bytes;
      j.title = name.string();
      jobs.push_back(j);
      continue;
    }
    fs::path path(p);
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      error(fmt::format("{}: no such file or directory", p));
      io_error = true;
      continue;
    }
    if (fs::is_directory(path, ec)) {
      if (auto card = card_at(path)) {
        job_for_card(*card, p);
        continue;
      }
      // A folder holding several cards (a printer-config repository): every folder with sys/config.g.
      bool found = false;
      for (fs::recursive_directory_iterator it(path, fs::directory_options::skip_permission_denied, ec), end;
           !ec && it != end; it.increment(ec)) {
        if (it.depth() > 6) it.disable_recursion_pending();
        if (!it->is_directory(ec)) continue;
        std::string name = it->path().filename().string();
        if (name.starts_with(".") || name == "node_modules") {
          it.disable_recursion_pending();
          continue;
        }
        if (auto card = card_at(it->path()); card && to_lower(it->path().filename().string()) != "sys") {
          job_for_card(*card, it->path().lexically_relative(fs::current_path()).string());
          it.disable_recursion_pending();
          found = true;
        }
      }
      if (!found) {
        // No config.g anywhere: lint the folder's macros as a card without a boot sequence.
        job_for_card(CardLocation{path, path}, p);
      }
      continue;
    }
    std::string err;
    if (!read_file(path, &err)) {
      error(fmt::format("{}: {}", p, err));
      io_error = true;
      continue;
    }
    if (auto card = card_containing(path)) {
      DiskReader probe(card->root, card->sys_dir, fs::current_path());
      if (auto sd = probe.sd_path_of(fs::absolute(path, ec))) {
        job_for_card(*card, p).only.insert(to_lower(*sd));
        continue;
      }
    }
    Job j;
    j.standalone = path;
    j.title = p;
    jobs.push_back(j);
  }
  return true;
}

struct RunResult {
  std::vector<Diagnostic> diags;
  std::vector<MachineResult> machines;
  std::vector<std::string> titles;
  size_t files = 0;
  bool io_error = false;
};

void run_job(const Job& job, const LintOptions& opts, SourceManager& sm, RunResult& out, bool keep_machine) {
  std::unique_ptr<FileReader> reader;
  std::string only_sd;
  if (job.card) {
    auto dr = std::make_unique<DiskReader>(job.card->root, job.card->sys_dir, fs::current_path());
    if (job.stdin_bytes) dr->overlay(job.stdin_sd_path, *job.stdin_bytes);
    reader = std::move(dr);
  } else {
    auto mr = std::make_unique<MemoryReader>();
    std::string bytes;
    if (job.stdin_bytes) {
      bytes = *job.stdin_bytes;
    } else {
      std::string err;
      auto b = read_file(job.standalone, &err);
      if (!b) {
        error(fmt::format("{}: {}", job.standalone.string(), err));
        out.io_error = true;
        return;
      }
      bytes = std::move(*b);
    }
    std::string name = job.standalone.filename().string();
    if (name.empty()) name = "stdin.g";
    only_sd = to_lower(name) == "config.g" ? "/sys/config.g" : "/sys/" + name;
    mr->add(only_sd, std::move(bytes));
    reader = std::move(mr);
  }
  MachineResult r = lint_machine(sm, *reader, opts);
  for (const LoadProblem& p : r.machine->problems()) {
    std::cerr << "rrflint: warning: " << p.display << ": " << p.message << "\n";
    bool asked = job.only.count(to_lower(p.sd_path)) || (!only_sd.empty() && to_lower(only_sd) == to_lower(p.sd_path));
    if (asked) out.io_error = true;
  }
  if (!job.card) {
    // The lone file keeps the name the user gave.
    for (uint32_t i = 0; i < r.machine->unit_count(); ++i) (void)i;
  }
  for (uint32_t i = 0; i < r.machine->unit_count(); ++i)
    if (job.only.empty() || job.only.count(to_lower(r.machine->unit(i).sd_path))) ++out.files;
  for (Diagnostic& d : r.diagnostics) {
    if (!job.only.empty()) {
      const SourceFile& f = sm.get(d.loc.file);
      if (!job.only.count(to_lower(f.sd_path()))) continue;
    }
    out.diags.push_back(d);
  }
  if (keep_machine) {
    out.titles.push_back(job.title);
    out.machines.push_back(std::move(r));
  }
}

bool use_color(const std::string& mode) {
  if (mode == "always") return true;
  if (mode == "never") return false;
  if (const char* f = std::getenv("FORCE_COLOR"); f && *f && std::string(f) != "0") return true;
  if (const char* n = std::getenv("NO_COLOR"); n && *n) return false;
  if (const char* t = std::getenv("TERM"); t && std::string(t) == "dumb") return false;
  return isatty(fileno(stdout));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rrflint: a static analyser for RepRapFirmware configuration (config.g and its macros)"};
  app.set_version_flag("--version", std::string("rrflint ") + RRFLINT_VERSION);
  app.require_subcommand(1);
  app.failure_message(CLI::FailureMessage::help);

  CommonOptions common;
  auto add_common = [&](CLI::App* sub) {
    sub->add_option("--firmware", common.firmware, "Target firmware version, e.g. 3.5 (default: inferred)");
    sub->add_option("--board", common.board, "Target board: duet2, duet3-6hc, duet3-mini, maestro (default: inferred)");
    sub->add_option("--select", common.select, "Rules to enable (codes, names, prefixes like RRF3, or ALL); replaces the default set")->delimiter(',')->allow_extra_args(false);
    sub->add_option("--extend-select", common.extend_select, "Rules to enable in addition to the default set")->delimiter(',')->allow_extra_args(false);
    sub->add_option("--ignore", common.ignore, "Rules to disable (codes or names)")->delimiter(',')->allow_extra_args(false);
    sub->add_flag("--tool-changer", common.tool_changer, "The machine is a tool changer (evidence for RRF305)");
  };

  // check
  CLI::App* check = app.add_subcommand("check", "Lint SD-card folders, sys folders or single files");
  std::vector<std::string> paths;
  std::string format = "text", fail_on = "warning", color = "auto", stdin_filename, output_file;
  bool exit_zero = false, verbose = false;
  check->add_option("paths", paths, "SD-card roots (folders holding sys/), sys folders, .g files, or - for stdin");
  check->add_option("--format", format, "Output format: text, concise, json")->check(CLI::IsMember({"text", "concise", "json"}));
  check->add_option("--fail-on", fail_on, "Lowest severity that makes the exit code 1: error, warning, info")
      ->check(CLI::IsMember({"error", "warning", "info"}));
  check->add_option("--color", color, "Colour: auto, always, never (NO_COLOR and FORCE_COLOR are honoured)")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  check->add_option("--stdin-filename", stdin_filename, "The name of the file read from stdin (for messages and discovery)");
  check->add_option("-o,--output-file", output_file, "Write the report to this file instead of stdout");
  check->add_flag("--exit-zero", exit_zero, "Exit 0 even when findings reach --fail-on");
  check->add_flag("-v,--verbose", verbose, "Print the firmware target and the evidence for it (to stderr)");
  add_common(check);

  // model
  CLI::App* model = app.add_subcommand("model", "Print the machine model the boot sequence builds");
  std::string model_path, model_format = "text";
  model->add_option("path", model_path, "SD-card root, sys folder or config.g")->required();
  model->add_option("--format", model_format, "text or json")->check(CLI::IsMember({"text", "json"}));
  add_common(model);

  // rule
  CLI::App* rule = app.add_subcommand("rule", "Print a rule's documentation");
  std::string rule_name, rule_format = "text";
  bool rule_all = false;
  rule->add_option("rule", rule_name, "Rule code or name");
  rule->add_flag("--all", rule_all, "Every rule");
  rule->add_option("--format", rule_format, "text or json")->check(CLI::IsMember({"text", "json"}));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? kExitClean : kExitError;
  }

  if (rule->parsed()) {
    using nlohmann::json;
    std::vector<const Rule*> list;
    if (rule_all) list = all_rules();
    else if (const Rule* r = find_rule(rule_name)) list.push_back(r);
    else {
      error(rule_name.empty() ? "name a rule or pass --all" : fmt::format("unknown rule '{}'", rule_name));
      return kExitError;
    }
    if (rule_format == "json") {
      json arr = json::array();
      for (const Rule* r : list)
        arr.push_back({{"code", r->meta.code}, {"name", r->meta.name}, {"severity", severity_name(r->meta.severity)},
                       {"default_enabled", r->meta.default_enabled},
                       {"fix", r->meta.fix == FixAvailability::None ? "none" : r->meta.fix == FixAvailability::Always ? "always" : "sometimes"},
                       {"summary", r->meta.summary}, {"docs", r->meta.docs}});
      std::cout << (rule_all ? arr : arr[0]).dump(2) << "\n";
    } else {
      for (const Rule* r : list)
        std::cout << "# " << r->meta.code << " " << r->meta.name << "\n\n" << r->meta.summary << "\n\nDefault severity: "
                  << severity_name(r->meta.severity) << (r->meta.default_enabled ? "" : " (off by default)") << "\n"
                  << r->meta.docs << "\n";
    }
    return kExitClean;
  }

  LintOptions opts;
  if (!build_options(common, opts)) return kExitError;

  if (model->parsed()) {
    std::vector<Job> jobs;
    bool io_error = false;
    plan({model_path}, "", jobs, io_error);
    if (io_error || jobs.empty()) return kExitError;
    SourceManager sm;
    RunResult rr;
    run_job(jobs.front(), opts, sm, rr, true);
    if (rr.machines.empty()) return kExitError;
    if (model_format == "json") render_model_json(std::cout, sm, rr.machines.front(), rr.titles.front());
    else render_model_text(std::cout, sm, rr.machines.front(), rr.titles.front());
    return rr.io_error ? kExitError : kExitClean;
  }

  // check
  if (paths.empty()) paths.push_back(".");
  std::vector<Job> jobs;
  bool io_error = false;
  plan(paths, stdin_filename, jobs, io_error);
  SourceManager sm;
  RunResult rr;
  for (const Job& j : jobs) {
    run_job(j, opts, sm, rr, verbose);
  }
  if (verbose)
    for (size_t i = 0; i < rr.machines.size(); ++i) {
      const auto& t = rr.machines[i].target;
      std::cerr << "rrflint: " << rr.titles[i] << ": " << t.reason << "; " << t.board_reason << "\n";
      for (const Evidence& e : t.evidence)
        std::cerr << fmt::format("rrflint:   evidence: {} ({}:{})\n", e.what, sm.get(e.loc.file).display_path(),
                                 sm.get(e.loc.file).position(e.loc.span.begin).line);
    }
  // Stable order across machines: by path, then position.
  std::stable_sort(rr.diags.begin(), rr.diags.end(), [&](const Diagnostic& a, const Diagnostic& b) {
    const auto& fa = sm.get(a.loc.file).display_path();
    const auto& fb = sm.get(b.loc.file).display_path();
    if (fa != fb) return fa < fb;
    return std::tie(a.loc.span.begin, a.code) < std::tie(b.loc.span.begin, b.code);
  });
  RenderOptions ro;
  ro.files_checked = rr.files;
  std::ofstream file_out;
  std::ostream* os = &std::cout;
  if (!output_file.empty()) {
    file_out.open(output_file, std::ios::binary);
    if (!file_out) {
      error(fmt::format("{}: cannot write", output_file));
      return kExitError;
    }
    os = &file_out;
  }
  ro.color = output_file.empty() && use_color(color);
  if (format == "json") render_json(*os, sm, rr.diags, ro);
  else if (format == "concise") render_concise(*os, sm, rr.diags, ro);
  else render_text(*os, sm, rr.diags, ro);
  os->flush();
  if (io_error || rr.io_error) return kExitError;
  const Severity threshold = *parse_severity(fail_on);
  bool failing = false;
  for (const Diagnostic& d : rr.diags) failing = failing || d.severity >= threshold;
  return failing && !exit_zero ? kExitFindings : kExitClean;
}
