// The command-line front end, shared declarations. Argument parsing and dispatch are in main.cc; the
// subcommands and their helpers live one concern per file:
//   settings.cc  config files + command line -> LintOptions per machine; `rrflint config`
//   inputs.cc    command-line paths -> jobs (one per machine): repository walk, .gitignore, exclude
//   check.cc     `rrflint check`: lint, --fix/--diff/--add-suppressions, render, exit code
//   fix.cc       the fix loop, atomic writes, unified diffs
//   rules_cmd.cc `rrflint rule`: docs, JSON metadata, --generate-docs
//   docs_url.cc  where the printed rule links point by default
//   server/      `rrflint server`: the language server (protocol, text positions, documents and machines)
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "frontend/config.h"
#include "frontend/disk.h"
#include "lint/engine/linter.h"
#include "rules/registry.h"

namespace rrflint::cli {

namespace fs = std::filesystem;

constexpr int kExitClean = 0, kExitFindings = 1, kExitError = 2;

void error(const std::string& msg);
void warning(const std::string& msg);
/// Flushes `os`: true when all of it was written; otherwise says "NAME: cannot write WHAT" (a full disk, a closed
/// output) and returns false. Output that did not arrive is an I/O error, never a pass.
bool flushed(std::ostream& os, std::string_view name, std::string_view what);

/// What the command line says, before any config file is read.
struct CliOptions {
  std::string firmware, board, fail_on;  // empty: not given
  std::vector<std::string> select, extend_select, ignore;
  bool select_given = false, extend_select_given = false, ignore_given = false;
  bool tool_changer = false;
  std::string config_path;  // --config
  bool isolated = false;    // --isolated
  bool no_inline_suppressions = false;
  // Beneath the config files (the language server's editor settings, cli/server/options.h): a config file's value
  // wins where both set one. The firmware of a config file replaces base_firmware; base_selection is applied
  // before a config file's selection layers (so its `select` replaces the base's), without its `ignore` when a
  // config file sets one. The command-line options above win over both.
  std::string base_firmware;
  SelectionLayer base_selection;
};

/// Checks and normalises what the command line names before any file is read: --firmware parsed (and written
/// back in its normal form), --board known, --select/--extend-select/--ignore split at commas and every name
/// known. False with `err` on a bad value; `warn` gets what to tell the user anyway (a firmware newer than known).
bool check_options(CliOptions& c, std::string& err, std::string& warn);

/// The settings of one machine (or lone file): LintOptions plus what only the front end uses.
struct Effective {
  LintOptions lint;
  Severity fail_on = Severity::Warning;
  std::shared_ptr<const Config> config;  // null: no config file
  std::string docs_base;                 // rule pages: `docs-url`, else default_docs_base()
  std::vector<std::string> problems;     // unknown rule names on the command line
};

/// Resolves config files (discovery, --config, --isolated) and merges them with the command line.
class Settings {
 public:
  explicit Settings(const CliOptions& cli) : cli_(cli) {}
  /// The config that governs files in `dir` (null when none). Sets error() on a bad config file.
  std::shared_ptr<const Config> config_for(const std::string& dir);
  /// The settings for a machine whose files start at `dir`. False on a config or option error.
  bool effective(const fs::path& dir, Effective& out);
  /// Is `abs` (absolute, normal) excluded by the `exclude` patterns of the config that governs it? `why` gets
  /// the pattern.
  bool excluded(const std::string& abs, std::string* why = nullptr);
  const std::optional<ConfigError>& config_error() const { return error_; }
  const CliOptions& cli() const { return cli_; }

 private:
  void resolve(std::shared_ptr<const Config> config, Effective& out);  // effective() for a config
  const CliOptions& cli_;
  std::map<std::string, std::shared_ptr<const Config>> loaded_;               // config file -> contents
  std::unordered_map<std::string, std::shared_ptr<const Config>> by_folder_;  // folder -> config_for(folder)
  std::map<const Config*, Effective> effective_;                              // config (or none) -> settings
  std::optional<ConfigError> error_;
};

/// Rule selection explained: for each rule, on or off and the setting that decided it.
struct RuleDecision {
  const Rule* rule;
  bool on;
  Origin origin;
  std::string why;  // "default", "select", "extend-select", "ignore"
};
std::vector<RuleDecision> decide_rules(const Config* cfg, const CliOptions& cli);

/// The folder of the rule pages when no `docs-url` is set (docs_url.cc): RRFLINT_DOCS_URL of the build, else the
/// installed docs, else (running from the build tree, or nothing installed) the source tree's docs/rules/. A URL
/// ending with '/'.
std::string default_docs_base();
/// A folder as a file:/// URL ending with '/', percent-encoded.
std::string file_url(const fs::path& dir);

/// `rrflint config [PATH]`.
int run_config(const CliOptions& cli, const std::string& path);

/// One machine to lint: a card on disk, or a lone file (or stdin).
struct Job {
  std::optional<CardLocation> card;
  fs::path standalone;                    // a lone file
  std::set<std::string> only;             // lower-cased SD paths to report, unless report_all
  bool report_all = false;                // every file of the card (minus exclusions and .gitignore)
  bool named_despite_exclusion = false;   // report_all although the card's folder is excluded: exclusions off
  std::optional<TextBuffer> stdin_bytes;  // content for `-` (shared with the reader and the source file)
  std::string stdin_sd_path;
  std::string title;
  bool explicit_path = false;                // named on the command line (exclusions only with --force-exclude)
  bool excluded = false;                     // stdin excluded by --force-exclude: not linted (--fix echoes it)
  std::map<std::string, std::string> named;  // files of the card named on the command line: lower SD path -> as named
  std::shared_ptr<DirCache> dirs;            // the folder listings the plan made, for the card's reader
};

/// What a job could not lint (unlinted.cc), said as errors: a config.g that cannot be linted, a file named on the
/// command line that was not linted (not G-code, unreadable). True when one was said (the run exits 2). Sets
/// `lone_hint` when a lone file other than config.g was linted (a note on how to lint it as one follows the run).
bool note_unlinted(const Job& job, const Effective& eff, const Machine& m, bool& lone_hint);

struct PlanOptions {
  std::string stdin_filename;
  bool force_exclude = false;
  bool respect_gitignore = true;
};

/// Is this file ignored by git (or, without git, by the .gitignore files above it)? Paths are absolute and
/// lexically normal (absolute_normal).
class GitIgnore {
 public:
  /// Answers for many files at once (one `git check-ignore` per repository).
  void prefetch(const std::vector<std::string>& files);
  bool ignored(const std::string& abs);

 private:
  struct Pattern {
    std::string glob;
    bool negated = false, dir_only = false, anchored = false;
  };
  // What the fallback matcher knows of a folder, worked out once per folder (files share their folders).
  struct Folder {
    std::vector<std::string> chain;  // the folders whose .gitignore applies: the repository top down to this one
    bool patterns = false;           // one of them has patterns
    bool ignored = false;            // this folder, or one above it below the top, is ignored
  };
  const std::vector<Pattern>& patterns(const std::string& dir);
  const Folder& folder(const std::string& dir);
  bool verdict(const std::string& path, bool is_dir, const std::vector<std::string>& chain);
  std::unordered_map<std::string, bool> cache_;  // file -> git check-ignore's answer
  std::set<std::string> no_git_;                 // repositories where git check-ignore gave no answer
  std::unordered_map<std::string, std::vector<Pattern>> patterns_;  // folder -> its .gitignore
  std::unordered_map<std::string, Folder> folders_;
};

/// What the plan saw besides the jobs: how many paths or files it left out on purpose, and the paths named on
/// the command line that led to no file at all.
struct PlanStats {
  size_t excluded = 0;             // files and folders left out by `exclude` or .gitignore
  size_t force_excluded = 0;       // paths named on the command line and left out by --force-exclude
  size_t named = 0;                // paths named on the command line (stdin included)
  std::vector<std::string> empty;  // paths (as named) under which nothing was found to lint, with the reason
  std::vector<fs::path> roots;     // what was named: each folder, and each named file's card or folder (absolute,
                                   // normal): --fix writes through a symbolic link only to a file below one of them
};

/// Turns command-line paths into jobs, one per machine. Sets `io_error` for unusable paths. `gitignore` keeps
/// its answers for the rest of the run.
void plan(const std::vector<std::string>& paths, const PlanOptions& po, Settings& settings, GitIgnore& gitignore,
          std::vector<Job>& jobs, bool& io_error, PlanStats* stats = nullptr);

/// Where `rrflint check FILE` puts a file: its card (root and sys folder, absolute and normal) and its SD path there.
struct FilePlace {
  CardLocation card;
  std::string sd_path;
};
/// The card of a file (absolute, normal; it need not exist yet), as plan() decides it for a file named on the
/// command line; nullopt for a lone file (no card around it, or outside the card's sys/, macros/ and filaments/).
std::optional<FilePlace> place_file(const std::string& abs);

/// The FileReader of a job, with in-memory replacements (fixed text) on top.
class JobReader : public FileReader {
 public:
  explicit JobReader(const Job& job);
  ReadResult read(std::string_view sd_path) override;
  std::vector<std::string> list(std::string_view sd_dir) override;
  void set(const std::string& sd_path, TextBuffer bytes) { overlay_[to_lower(sd_path)] = std::move(bytes); }
  /// The file on disk behind an SD path (nullopt for stdin or unknown); absolute and normal in a card.
  std::optional<std::string> disk_path(std::string_view sd_path) const;

 private:
  const Job& job_;
  std::unique_ptr<DiskReader> disk_;
  std::string lone_sd_, lone_display_;
  std::map<std::string, TextBuffer> overlay_;
};

// ---- fix.cc ----

struct FixOptions {
  bool unsafe = false;
  int max_rounds = 10;
};

/// Picks non-overlapping fixes (whole fixes, never part of one) among `diags` that `allowed` accepts, applies
/// them to `texts` (by FileId), keeping each file's line-ending style. Returns how many fixes were applied;
/// `per_file` gets them by the file of each fix's first edit.
/// `applied` gets the findings whose fixes were applied.
size_t apply_fixes(const SourceManager& sm, const std::vector<Diagnostic>& diags, const FixOptions& fo,
                   const std::function<bool(FileId)>& allowed, std::map<FileId, std::string>& texts,
                   std::map<FileId, size_t>* per_file = nullptr, std::vector<const Diagnostic*>* applied = nullptr);

/// Does `after` (the text of `before` with fixes applied) parse with more errors, or more expressions a ';' cuts
/// open, than `before`? Both are parsed on their own, in the same mode. The editor's fix-all (one round of --fix)
/// is not offered when it does; `rrflint check --fix` compares whole lints instead (run_fix_rounds).
bool parses_worse(const SourceFile& before, std::string after);

/// What the fix rounds of one machine did (run_fix_rounds), by SD path.
struct FixRounds {
  std::map<std::string, std::string> original, current;  // the text before the first round, and after the last
  std::map<std::string, std::string> display;            // the name to show
  std::map<std::string, size_t> fixed_in;                // fixes kept, by the file each starts in
  size_t fixed = 0;                                      // fixes kept in all
  /// The files a round's fixes left with more parse errors than before (a bug in a rule's fix): that round was
  /// undone, and these files were fixed no further. Each with the codes of the rules whose fixes were undone.
  std::map<std::string, std::vector<std::string>> reverted;
  /// False when fixes still applied after the last round (FixOptions::max_rounds): another --fix would change more.
  bool settled = true;
};

/// `rrflint check --fix`'s rounds: applies the fixes of `r` to the files `allowed` accepts (apply_fixes), hands
/// each changed text to `set_text` (by SD path) and re-lints with `relint`, until no fix applies or after
/// fo.max_rounds rounds; `r` is then the lint of the fixed texts. The safety net: a round that leaves any file with
/// more parse errors (syntax errors and expressions a ';' cuts open) than it had is undone, whole, and the files it
/// made worse are not fixed again (FixRounds::reverted); the other files go on to the next round.
FixRounds run_fix_rounds(const SourceManager& sm, MachineResult& r, const FixOptions& fo,
                         const std::function<bool(FileId)>& allowed,
                         const std::function<void(const std::string& sd_path, const std::string& text)>& set_text,
                         const std::function<MachineResult()>& relint);

/// Why --fix may not write `path` (empty when it may): it is reached through a symbolic link (itself, or a folder on
/// its way) and the file it leads to lies below none of `roots` (the folders the run linted). `*real`: that file.
std::string outside_roots(const fs::path& path, const std::vector<fs::path>& roots, fs::path* real = nullptr);

/// Writes `bytes` to `path` without ever leaving it half written: a temporary file in the same folder, then a
/// rename, keeping the file's mode, owner and group. Refuses (returns false with `err`, writing nothing) when the
/// file changed on disk since `expected` was read, when it is read-only (no write bit) or, without root, not
/// writable in place, when its owner cannot be kept, and when outside_roots() says so.
bool write_atomic(const fs::path& path, const std::string& expected, const std::string& bytes,
                  const std::vector<fs::path>& roots, std::string* err);

/// Opens `path` for the report (`rrflint check -o`), unless it is one of `inputs`, the files the run read (a linted
/// file, a macro, a settings file; the same file under any name or link), which the report would replace. False,
/// with `err`, then or when it cannot be opened.
bool open_report_file(const std::string& path, const std::vector<std::string>& inputs, std::ofstream& out,
                      std::string* err);

/// A unified diff (`--- a/x`, `+++ b/x`, 3 lines of context); empty when the texts are equal.
std::string unified_diff(std::string_view before, std::string_view after, const std::string& path);
/// The name --diff gives a file on disk (`disk`; nullopt for stdin) shown as `shown`: `shown`, unless the file is
/// reached through a symbolic link (itself, or a folder on its way: git apply refuses to patch through one, and one
/// file could get two names): then the file it leads to, relative to the current folder when it lies below it.
std::string diff_name(const std::optional<std::string>& disk, const std::string& shown);

// ---- check.cc ----

struct CheckOptions {
  std::vector<std::string> paths;
  std::string format = "text";
  bool format_given = false;
  std::string color = "auto";
  std::string output_file;
  bool exit_zero = false, verbose = false;
  bool fix = false, unsafe_fixes = false, diff = false;
  bool statistics = false;                      // the number of findings per rule instead of the findings
  std::optional<std::string> add_suppressions;  // the reason (may be empty)
  unsigned jobs = 0;                            // machines linted at once; 0 = the CPU count, at most 8
  PlanOptions plan;
};

/// The threads a run uses without --jobs: the CPU count, at most 8.
unsigned default_threads();
/// The settings of a job's machine (its sys folder, or a lone file's folder, finds the governing config), to lint
/// on `threads` threads. False on a config or option error.
bool job_settings(const Job& job, Settings& settings, unsigned threads, Effective& eff);

int run_check(const CliOptions& cli, const CheckOptions& co);
/// Options of `check` that do not go together (--add-suppressions with --fix, --statistics with --diff or a format
/// it does not print…): the error, else "".
std::string conflicting_options(const CheckOptions& co);
/// What check (on stderr) and the language server (as a window message) say when a machine's graph stopped at its
/// node limit (Graph::truncated), `nodes`: the machine rules then judged only the commands before it. `title`: the
/// card.
std::string truncated_warning(const std::string& title, size_t nodes);
/// Colour for `--color MODE` on file descriptor `fd`: always/never, else FORCE_COLOR, NO_COLOR, TERM=dumb, a tty.
bool use_color(const std::string& mode, int fd);

// ---- rules_cmd.cc ----

struct RuleOptions {
  std::string name;
  bool all = false;
  std::string format = "text";
  std::string generate_dir;  // --generate-docs DIR
  std::string readme;        // --readme FILE: also rewrite its rule list
  bool check = false;        // --check: only report stale files (exit 1)
};
/// `cli` gives --config / --isolated: the `docs-url` of the config found from the working directory is used.
int run_rule(const RuleOptions& ro, const CliOptions& cli);

// ---- server/ ----

/// `rrflint server`: the language server on stdin and stdout (server/server.cc). The exit code: 0 after shutdown
/// and exit, 1 on an exit (or the end of the input) without shutdown.
int run_server();

/// The git top-level folder holding `dir`, found by looking for `.git`; nullopt outside a repository.
std::optional<fs::path> repo_root(const fs::path& dir);

}  // namespace rrflint::cli
