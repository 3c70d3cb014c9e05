// The configuration file, `.rrflint.toml`: discovery, `extend` chains, validation with file:line errors, and
// where every setting came from (for `rrflint config`).
//
//   extend = "../base.toml"            # another config file to start from (relative to this one)
//   select = ["RRF1", "RRF3"]          # replaces the default rule set (codes, names, prefixes, "ALL")
//   extend-select = ["RRF331"]         # added to the selection
//   ignore = ["line-too-long"]         # removed from the selection
//   firmware = "3.5"                   # the firmware target
//   board = "duet3-6hc"
//   fail-on = "error"                  # lowest severity that makes the exit code 1
//   exclude = ["old/**", "*.bak.g"]    # paths not to lint (relative to this file; no '/' = any folder level)
//   docs-url = "https://example.org/rrflint/docs/rules/"   # where rule pages are linked: <docs-url><name>.md
//   [severity]
//   RRF306 = "error"                   # or by name: g10-missing-z = "error"
//   [machine]
//   tool-changer = true
//   [per-file-ignores]
//   "macros/**" = ["RRF101"]           # relative to this file, or an SD path such as "sys/tpost*.g"
//
// Like the rest of lint/ except disk.cc, nothing here is used by the core linter: the front ends read the file
// and turn it into LintOptions. Unknown keys are errors (typo protection).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lint/base/diagnostic.h"
#include "lint/boot/firmware.h"

namespace rrflint {

inline constexpr const char* kConfigFileName = ".rrflint.toml";

/// Where a setting came from.
struct Origin {
  enum class Kind : uint8_t { Default, File, CommandLine } kind = Kind::Default;
  std::filesystem::path file;
  uint32_t line = 0;
  static Origin command_line() { return Origin{Kind::CommandLine, {}, 0}; }
  /// "default", "command line", or "path:line" (path relative to the working directory when below it).
  std::string str() const;
};

template <class T>
struct Setting {
  std::optional<T> value;
  Origin origin;
};

/// One step of rule selection, applied in order: the extended files first, then this file, then the command
/// line. `select` (when given) replaces what came before, `extend-select` adds, `ignore` removes.
struct SelectionLayer {
  Setting<std::vector<std::string>> select;
  Setting<std::vector<std::string>> extend_select;
  Setting<std::vector<std::string>> ignore;
};

/// An `exclude` or `per-file-ignores` pattern, and the folder it is relative to.
struct PathPattern {
  std::string glob;
  std::filesystem::path base;      // absolute folder of the config file that defined it
  std::vector<std::string> codes;  // per-file-ignores: the rule codes it switches off
  Origin origin;
};

struct Config {
  std::vector<std::filesystem::path> files;  // every file read, extended ones first; the last is the one found
  std::vector<SelectionLayer> selection;
  std::map<std::string, Setting<Severity>> severity;  // by rule code
  Setting<Version> firmware;
  std::vector<std::string> warnings;  // things to tell the user that do not stop the run (a firmware newer than known)
  Setting<Board> board;
  Setting<Severity> fail_on;
  Setting<bool> tool_changer;
  Setting<std::string> docs_url;  // http(s):// or file:/// folder of the rule pages, ending with '/'
  std::vector<PathPattern> per_file_ignores;
  std::vector<PathPattern> exclude;
};

struct ConfigError {
  std::filesystem::path file;
  uint32_t line = 0, column = 0;
  std::string message;
  /// "path:line:col: message".
  std::string str() const;
};

/// Reads a config file and the files it extends. Nullopt with `err` set on any problem.
std::optional<Config> load_config(const std::filesystem::path& file, ConfigError* err);

/// The nearest `.rrflint.toml` from `dir` upward. The search stops after a folder holding `.git` (the
/// repository root) or at the file-system root.
std::optional<std::filesystem::path> find_config(const std::filesystem::path& dir);

/// Checks a `docs-url` value: an http://, https:// or file:/// (absolute) URL of a folder, with no query,
/// fragment or blank. Returns the value with a trailing '/' added, or nullopt with `why` set.
std::optional<std::string> parse_docs_url(std::string_view url, std::string* why);

/// Is this a rule selector rrflint knows: a code, a name, a code prefix ("RRF3") or "ALL"?
bool rule_selector_known(std::string_view selector);
/// What follows "unknown rule 'x'" in an error: "; did you mean 'g10-missing-z' (RRF302)?" for a misspelt name,
/// else " (see `rrflint rule --all`)".
std::string unknown_rule_hint(std::string_view selector);
/// The codes a list of selectors names.
std::vector<std::string> selector_codes(const std::vector<std::string>& selectors);

/// Glob matching on '/'-separated paths: `*` and `?` stay inside a segment, `**` spans segments, `[…]` classes.
bool glob_match(std::string_view pattern, std::string_view path);

/// Does a pattern apply to `rel`, a path relative to the pattern's base? Like .gitignore: a pattern without '/'
/// matches a file or folder name at any depth; one with '/' is anchored to the base; a match on a folder also
/// covers everything below it.
bool pattern_applies(std::string_view glob, std::string_view rel);

/// The path of `abs` relative to `base` ('/'-separated), or nullopt when `abs` is not below `base`.
std::optional<std::string> relative_below(const std::filesystem::path& abs, const std::filesystem::path& base);

}  // namespace rrflint
