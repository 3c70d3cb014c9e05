// rrflint: the command-line front end. Argument parsing and dispatch only; the subcommands are in the other
// files of cli/ (see cli.h) and the work is done by the core library (lint/).
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include "frontend/win32.h"
#else
#include <signal.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/cli.h"
#include "cli/generate.h"
#include "frontend/disk.h"
#include "lint/base/trace.h"
#include "lint/render/model_render.h"
#include "lint/render/render.h"

using namespace rrflint;
using namespace rrflint::cli;

namespace {

#ifdef _WIN32
// Windows: files are read, never mapped (lint/base/huge_pages.h maps on Linux only). Standard input and output
// are binary, so `--fix -` and the LSP keep the bytes (no CRLF translation), and the console is asked to
// understand the ANSI colour codes (Windows 10 and later; where it cannot, --color auto sees no terminal).
void map_large_inputs() {
  _setmode(_fileno(stdin), _O_BINARY);
  _setmode(_fileno(stdout), _O_BINARY);
  for (DWORD id : {STD_OUTPUT_HANDLE, STD_ERROR_HANDLE}) {
    const HANDLE h = GetStdHandle(id);
    DWORD mode = 0;
    if (h != INVALID_HANDLE_VALUE && GetConsoleMode(h, &mode))
      SetConsoleMode(h, mode | ENABLE_VIRTUAL_TERMINAL_PROCESSING);
  }
}
#else
// Large input files are mapped rather than copied (read_text). If another program cuts such a file short while
// it is linted, reading the lost part raises SIGBUS: report that as an I/O error (exit 2), not as a crash.
extern "C" void on_sigbus(int) {
  static const char msg[] = "rrflint: error: an input file was truncated by another program while it was read\n";
  [[maybe_unused]] const ssize_t n = ::write(2, msg, sizeof msg - 1);
  ::_exit(kExitError);
}

void map_large_inputs() {
  struct sigaction sa {};
  sa.sa_handler = on_sigbus;
  sigemptyset(&sa.sa_mask);
  if (::sigaction(SIGBUS, &sa, nullptr) == 0) map_large_files(true);
}
#endif

// Checks what the command line names before any file is read. False (with a message) on a bad value.
bool validate(CliOptions& c) {
  std::string err, warn;
  const bool ok = check_options(c, err, warn);
  if (!warn.empty()) warning(warn);
  if (!ok) error(err);
  return ok;
}

// Takes `--add-suppressions[=REASON]` out of `args`: the reason must be attached with '=', so a path after the
// flag stays a path. Its reason ("" without one), if it was given.
std::optional<std::string> take_add_suppressions(std::vector<std::string>& args) {
  std::optional<std::string> add_suppressions;
  for (auto it = args.begin() + 1; it != args.end();) {
    if (*it == "--") break;
    if (*it == "--add-suppressions" || it->starts_with("--add-suppressions=")) {
      add_suppressions = it->size() > 19 ? it->substr(19) : "";
      it = args.erase(it);
      continue;
    }
    ++it;
  }
  return add_suppressions;
}

// An unknown command gets its own message (CLI11 would say that a subcommand is required), and so does an option
// before any command (`rrflint --select X`: the options belong to a command). False after it.
bool known_command(const std::vector<std::string>& args) {
  if (args.size() > 1 && args[1].starts_with("-") && args[1] != "-h" && args[1] != "--help" && args[1] != "--version") {
    error(
        fmt::format("unknown option '{}' before a command: options follow the command, as in `rrflint check {} …` "
                    "(see `rrflint --help`)",
                    args[1], args[1]));
    return false;
  }
  if (args.size() > 1 && !args[1].starts_with("-")) {
    static const char* const kCommands[][2] = {{"check", "lint SD cards, sys folders, repositories or files"},
                                               {"config", "print the effective settings and where each came from"},
                                               {"model", "print the machine model the boot sequence builds"},
                                               {"rule", "print a rule's documentation"},
                                               {"server", "run the language server (LSP over stdio)"}};
    if (std::none_of(std::begin(kCommands), std::end(kCommands), [&](const auto& c) { return args[1] == c[0]; })) {
      std::string list;
      for (const auto& c : kCommands) list += fmt::format("\n  {:<8}{}", c[0], c[1]);
      error(fmt::format("unknown command '{}'; the commands are:{}\n(see `rrflint --help`)", args[1], list));
      return false;
    }
  }
  return true;
}

// The subcommands, and the variables CLI11 writes their options to (it keeps pointers to them: never moved).
struct Commands {
  CliOptions cli;
  CheckOptions co;
  bool no_gitignore = false;
  std::string model_path, model_format = "text";
  RuleOptions ro;
  std::string config_path;
  std::string man_file, completion_file;  // rule --generate-man, --generate-completion
  CLI::App* check = nullptr;
  CLI::Option* format_opt = nullptr;  // check's --format
  CLI::App* model = nullptr;
  CLI::App* rule = nullptr;
  CLI::App* config = nullptr;
  CLI::App* server = nullptr;
};

// The options that check, model and config share.
void add_common(CLI::App* sub, CliOptions& cli) {
  sub->add_option("--firmware", cli.firmware, "Target firmware version, e.g. 3.5 (default: config file, else inferred)")
      ->type_name("VERSION");
  sub->add_option("--board", cli.board, "Target board: duet2, duet3-6hc, duet3-mini, maestro (default: inferred)")
      ->type_name("BOARD");
  sub->add_option("--select", cli.select,
                  "Rules to enable (codes, names, prefixes like RRF3, or ALL); replaces the set so far")
      ->type_name("RULES")
      ->delimiter(',')
      ->allow_extra_args(false);
  sub->add_option("--extend-select", cli.extend_select, "Rules to enable in addition")
      ->type_name("RULES")
      ->delimiter(',')
      ->allow_extra_args(false);
  sub->add_option("--ignore", cli.ignore, "Rules to disable (codes, names, prefixes)")
      ->type_name("RULES")
      ->delimiter(',')
      ->allow_extra_args(false);
  sub->add_flag("--tool-changer", cli.tool_changer, "The machine is a tool changer (evidence for RRF305)");
  CLI::Option* config =
      sub->add_option("--config", cli.config_path, "Use this config file instead of discovering .rrflint.toml")
          ->type_name("FILE");
  sub->add_flag("--isolated", cli.isolated, "Ignore every config file")->excludes(config);
  sub->add_flag("--no-inline-suppressions", cli.no_inline_suppressions,
                "Ignore `; rrflint: disable…` comments (for CI that forbids them)");
}

void add_check(CLI::App& app, Commands& c) {
  CLI::App* check = c.check =
      app.add_subcommand("check", "Lint SD-card folders, sys folders, repositories or single files");
  CheckOptions& co = c.co;
  CliOptions& cli = c.cli;
  check
      ->add_option("paths", co.paths, "SD-card roots, sys folders, repositories, .g files, or - for stdin (default: .)")
      ->type_name("PATH");
  c.format_opt =
      check->add_option("--format", co.format, "Output format: text, concise, json, json-lines, sarif, github, gitlab")
          ->type_name("FORMAT")
          ->check(CLI::IsMember(std::vector<std::string>(std::begin(kReportFormats), std::end(kReportFormats))));
  check->add_option("--fail-on", cli.fail_on, "Lowest severity that makes the exit code 1: error, warning, info")
      ->type_name("SEVERITY")
      ->check(CLI::IsMember({"error", "warning", "info"}));
  check->add_option("--color", co.color, "Colour: auto, always, never (NO_COLOR, FORCE_COLOR, TERM=dumb are honoured)")
      ->type_name("WHEN")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  check
      ->add_option("--stdin-filename", co.plan.stdin_filename,
                   "The name of the file read from stdin (messages, config, card)")
      ->type_name("FILE");
  check->add_option("-o,--output-file", co.output_file, "Write the report to this file instead of stdout ('-': stdout)")
      ->type_name("FILE");
  check->add_flag("--exit-zero", co.exit_zero, "Exit 0 even when findings reach --fail-on");
  check->add_option("-j,--jobs", co.jobs, "Lint up to N machines at once (default: the CPU count, at most 8)")
      ->type_name("N")
      ->check(CLI::Range(1u, 256u));
  check->add_flag("-v,--verbose", co.verbose, "Print the firmware target, its evidence and the config file (stderr)");
  check->add_flag("--fix", co.fix, "Apply safe fixes (rounds until stable, at most 10) and report what is left");
  check->add_flag("--unsafe-fixes", co.unsafe_fixes, "With --fix or --diff, apply unsafe fixes too");
  check->add_flag("--diff", co.diff, "Print the fixes as a unified diff and write nothing (exit 1 if there are any)");
  check->add_flag("--statistics", co.statistics,
                  "Print how many findings each rule has instead of the findings (text, concise or json)");
  check->add_flag("--force-exclude", co.plan.force_exclude,
                  "Apply exclude and .gitignore to paths named on the command line");
  check->add_flag("--no-respect-gitignore", c.no_gitignore, "Lint files that .gitignore excludes");
  // Documented here; parsed before CLI11 sees the arguments (see take_add_suppressions).
  check->footer(
      "  --add-suppressions[=REASON]  Add `; rrflint: disable=…` to every line with a finding (reason after ' -- ')");
  add_common(check, cli);
}

void add_model_rule_config(CLI::App& app, Commands& c) {
  // model
  CLI::App* model = c.model = app.add_subcommand("model", "Print the machine model the boot sequence builds");
  model->add_option("path", c.model_path, "SD-card root, sys folder or config.g")->type_name("PATH")->required();
  model->add_option("--format", c.model_format, "text or json")
      ->type_name("FORMAT")
      ->check(CLI::IsMember({"text", "json"}));
  add_common(model, c.cli);

  // rule
  CLI::App* rule = c.rule = app.add_subcommand("rule", "Print a rule's documentation, or generate docs/rules");
  RuleOptions& ro = c.ro;
  rule->add_option("rule", ro.name, "Rule code or name")->type_name("RULE");
  rule->add_flag("--all", ro.all, "Every rule");
  rule->add_option("--format", ro.format, "text (Markdown) or json")
      ->type_name("FORMAT")
      ->check(CLI::IsMember({"text", "json"}));
  rule->add_option("--generate-docs", ro.generate_dir, "Write every rule's page and an index to this folder")
      ->type_name("DIR");
  rule->add_option("--readme", ro.readme, "With --generate-docs: also rewrite this README's rule list")
      ->type_name("FILE");
  rule->add_flag("--check", ro.check, "With --generate-docs: write nothing, exit 1 when a file is stale");
  CLI::Option* rule_config = rule->add_option("--config", c.cli.config_path,
                                              "With --format json: the config file whose docs-url the links follow")
                                 ->type_name("FILE");
  rule->add_flag("--isolated", c.cli.isolated, "Ignore every config file")->excludes(rule_config);
  rule->add_option("--generate-man", c.man_file, "Write the man page rrflint.1 to this file (the build does)")
      ->type_name("FILE");
  rule->add_option("--generate-completion", c.completion_file, "Write the bash completion script to this file")
      ->type_name("FILE");

  // config
  CLI::App* config = c.config =
      app.add_subcommand("config", "Print the effective settings for a path and where each came from");
  config->add_option("path", c.config_path, "A file or folder (default: .)")->type_name("PATH");
  add_common(config, c.cli);
  config->add_option("--fail-on", c.cli.fail_on, "error, warning or info")
      ->type_name("SEVERITY")
      ->check(CLI::IsMember({"error", "warning", "info"}));
}

// `rrflint model PATH`: the machine model of the first machine PATH names.
int run_model(const CliOptions& cli, const std::string& model_path, const std::string& model_format) {
  Settings settings(cli);
  std::vector<Job> jobs;
  bool io_error = false;
  GitIgnore gitignore;
  PlanStats stats;
  plan({model_path}, PlanOptions{}, settings, gitignore, jobs, io_error, &stats);
  if (settings.config_error()) {
    error(settings.config_error()->str());
    return kExitError;
  }
  if (jobs.empty() && !io_error) {
    for (const std::string& why : stats.empty) error(why);
    if (stats.empty.empty()) error(fmt::format("{}: no G-code file to build a model from", model_path));
  }
  // One model per run: a folder of several machines (a repository of configs) names none of them.
  if (jobs.size() > 1) {
    std::vector<std::string> titles;
    for (const Job& j : jobs) titles.push_back(j.title);
    std::sort(titles.begin(), titles.end());
    error(fmt::format("{} holds {} machines ({}): name one of them (its folder or its config.g)", model_path,
                      jobs.size(), fmt::join(titles, ", ")));
  }
  if (io_error || jobs.size() != 1) return kExitError;
  const Job& job = jobs.front();
  Effective eff;
  if (!job_settings(job, settings, default_threads(), eff)) {
    error(settings.config_error()->str());
    return kExitError;
  }
  SourceManager sm;
  JobReader reader(job);
  MachineResult r = lint_machine(sm, reader, builtin_rules(), eff.lint);
  bool config_unreadable = false;
  for (const LoadProblem& p : r.machine->problems()) {
    const bool is_config = to_lower(p.sd_path) == to_lower(eff.lint.sys_dir + "/config.g");
    (is_config ? error : warning)(fmt::format("{}: {}", p.display, p.message));
    config_unreadable = config_unreadable || is_config;
  }
  if (config_unreadable || r.machine->unit_count() == 0) {
    if (!config_unreadable) error(fmt::format("{}: no G-code file to build a model from", model_path));
    return kExitError;
  }
  if (model_format == "json") render_model_json(std::cout, sm, r, job.title);
  else render_model_text(std::cout, sm, r, job.title);
  return kExitClean;
}

// A subcommand's exit code, or an I/O error (2) when its output could not be written whole to stdout (a full disk):
// a report that did not arrive is never a pass. (A closed pipe ends the process with SIGPIPE first, as for grep.)
int written(int rc) { return rc == kExitError || flushed(std::cout, "stdout", "the output") ? rc : kExitError; }

// `rrflint rule --generate-man FILE --generate-completion FILE` (generate.h): the build runs it.
int write_generated(const CLI::App& app, const std::string& man_file, const std::string& completion_file) {
  for (const auto& [file, text] : {std::pair{man_file, man_page(app, builtin_rules(), installed_rule_docs())},
                                   std::pair{completion_file, bash_completion(app, builtin_rules())}}) {
    if (file.empty()) continue;
    std::ofstream out(file, std::ios::binary);
    out << text;
    if (!out.flush()) {
      error(fmt::format("{}: cannot write", file));
      return kExitError;
    }
  }
  return kExitClean;
}

}  // namespace

int main(int argc, char** argv) {
  rrflint::trace::mark("main");
  map_large_inputs();
  std::vector<std::string> args(argv, argv + argc);
  const std::optional<std::string> add_suppressions = take_add_suppressions(args);
  if (!known_command(args)) return kExitError;
  std::vector<char*> argv2;
  for (std::string& a : args) argv2.push_back(a.data());

  CLI::App app{"rrflint: a static analyser for RepRapFirmware configuration (config.g and its macros)"};
  app.set_version_flag("--version", std::string("rrflint ") + RRFLINT_VERSION);
  app.require_subcommand(1);
  app.failure_message(CLI::FailureMessage::help);
  Commands c;
  add_check(app, c);
  add_model_rule_config(app, c);
  c.server = app.add_subcommand("server", "Run the language server: LSP 3.17 over stdin and stdout");
  CliOptions& cli = c.cli;

  try {
    app.parse(static_cast<int>(argv2.size()), argv2.data());
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? written(kExitClean) : kExitError;  // --help and --version are output too
  }
  if (add_suppressions && !c.check->parsed()) {
    error("--add-suppressions is an option of `rrflint check`");
    return kExitError;
  }
  // The reason goes into a comment on each line: a line break, NUL or other control byte would end that line early
  // in RRF and make the rest of the reason a command (and DEL makes RRF drop the whole line).
  if (add_suppressions && std::any_of(add_suppressions->begin(), add_suppressions->end(), [](char ch) {
        return (static_cast<unsigned char>(ch) < 0x20 && ch != '\t') || ch == 0x7f;
      })) {
    error(
        "--add-suppressions: the reason must be one line of text, without control characters (it goes into a "
        "comment on each line with a finding)");
    return kExitError;
  }

  if (c.rule->parsed() && (!c.man_file.empty() || !c.completion_file.empty()))
    return write_generated(app, c.man_file, c.completion_file);
  if (c.rule->parsed()) return written(run_rule(c.ro, c.cli));
  if (c.server->parsed()) return run_server();

  for (CLI::App* sub : {c.check, c.model, c.config}) {
    if (!sub->parsed()) continue;
    cli.select_given = sub->get_option("--select")->count() > 0;
    cli.extend_select_given = sub->get_option("--extend-select")->count() > 0;
    cli.ignore_given = sub->get_option("--ignore")->count() > 0;
    // An empty value (`--select "$RULES"` with the variable unset) would turn every rule off, or the option silently
    // back to its default: a usage error, as an unknown value is.
    for (const char* name : {"--select", "--firmware", "--board"})
      if (const CLI::Option* o = sub->get_option(name); o->count() > 0) {
        const auto values = o->as<std::vector<std::string>>();
        if (std::all_of(values.begin(), values.end(),
                        [](const std::string& v) { return v.find_first_not_of(", ") == std::string::npos; })) {
          error(fmt::format("{}: empty value", name));
          return kExitError;
        }
      }
  }
  if (!validate(cli)) return kExitError;

  if (c.config->parsed()) return written(run_config(cli, c.config_path));
  if (c.model->parsed()) return written(run_model(cli, c.model_path, c.model_format));

  c.co.format_given = c.format_opt->count() > 0;
  if (c.co.output_file == "-") c.co.output_file.clear();
  c.co.add_suppressions = add_suppressions;
  c.co.plan.respect_gitignore = !c.no_gitignore;
  const int rc = written(run_check(cli, c.co));
  trace::mark("freed");
  return rc;
}
