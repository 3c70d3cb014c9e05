// Renderers: one format per file. Each takes the diagnostics of a run and the sources they point into.
//   text.cc        the default human format: snippets with carets, notes, fix preview, summary, rule links
//   text.cc        `concise`: one gcc-style line per finding
//   json.cc        `json`: one versioned document        json_lines.cc  `json-lines`: one object per line
//   sarif.cc       `sarif`: SARIF 2.1.0 for GitHub code scanning and editors
//   github.cc      `github`: GitHub Actions workflow commands (annotations)
//   gitlab.cc      `gitlab`: a GitLab Code Quality report
//   statistics.cc  `check --statistics`: the number of findings per rule, as text or json
//   fingerprint.cc what sarif and gitlab share: paths relative to the repository, stable fingerprints
//   rule_docs.cc   the Markdown pages of docs/rules/ and the README's rule list
#pragma once

#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "lint/base/diagnostic.h"
#include "lint/base/source.h"
#include "lint/boot/infer.h"

namespace rrflint {

/// A rule's page: `<docs_base><name>.md`. The front end sets the base (the `docs-url` setting, else the default
/// of the build: the installed docs or the source tree's docs/rules/, see cli/docs_url.cc); an empty base gives
/// the page's path in the repository, docs/rules/<name>.md.
std::string rule_url(std::string_view docs_base, std::string_view name);
/// Is `url` a web address (http:// or https://)? Only those go where a viewer elsewhere follows the link
/// (SARIF's helpUri, GitHub annotations); a file:// page exists on this machine only.
bool is_web_url(std::string_view url);

class RuleSet;

/// A linted machine and its firmware target, for the `machines` field of `--format json`.
struct MachineTarget {
  std::string title;  // the folder or file as the user named it
  Target target;
};

struct RenderOptions {
  /// The rules that exist (SARIF lists them all in tool.driver.rules); null: none listed.
  const RuleSet* rules = nullptr;
  bool color = false;
  bool show_fix_hint = true;  // the "N fixable with --fix" part of the summary
  bool unsafe_fixes_enabled = false;
  std::string docs_base;  // where rule pages live, for rule_url(); ends with '/'
  size_t files_checked = 0;
  std::vector<MachineTarget> machines;  // json: each machine's target, its source and evidence
  size_t fixed = 0;                     // findings fixed by --fix before this report (text summary)
  /// json, json-lines: a report of many findings is written in pieces on up to this many threads (the bytes are
  /// the same for any number).
  unsigned threads = 1;
  // SARIF: artifact URIs are relative to `uri_base` (the git top-level, else the working directory); display
  // paths are relative to `cwd`. Both absolute; empty means the current directory.
  std::filesystem::path uri_base;
  std::filesystem::path cwd;
};

struct Counts {
  size_t errors = 0, warnings = 0, infos = 0, fixable = 0, unsafe_fixable = 0, files = 0;
};
Counts count(const std::vector<Diagnostic>& diags);
/// The text formats' summary, without colour: "2 errors, 1 warning, 0 infos in 3 files" (no fix hint), and for no
/// findings "No problems found in 3 files" (no count when `files_checked` is 0). Neither ends in a newline.
std::string summary_line(const Counts& c);
std::string no_problems_line(size_t files_checked);

/// 1-based line/column (code points) of a location, and of its exclusive end.
struct Range {
  LineCol start, end;
};
Range range_of(const SourceManager& sm, const Location& loc);

void render_text(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                 const RenderOptions& o);
void render_concise(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                    const RenderOptions& o);
void render_json(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                 const RenderOptions& o);
void render_json_lines(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                       const RenderOptions& o);
void render_sarif(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                  const RenderOptions& o);
void render_github(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                   const RenderOptions& o);
void render_gitlab(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                   const RenderOptions& o);
/// The report formats of `check --format`, and the report in one of them (an unknown name: text).
inline constexpr std::string_view kReportFormats[] = {"text",  "concise", "json",  "json-lines",
                                                      "sarif", "github",  "gitlab"};
void render_report_as(std::string_view format, std::ostream& os, const SourceManager& sm,
                      const std::vector<Diagnostic>& diags, const RenderOptions& o);
/// `check --statistics` (as ruff's): the number of findings per rule instead of the findings, most first, as text
/// (a line per rule and the text summary) or, with `json`, as a versioned document (statistics.cc).
void render_statistics(std::ostream& os, const std::vector<Diagnostic>& diags, const RenderOptions& o, bool json);
class JsonWriter;
/// The "summary" member of `json` and of `--statistics --format json`: the counts of a report.
void write_summary_json(JsonWriter& w, const std::vector<Diagnostic>& diags, const RenderOptions& o);
/// The sanitized display path of each file, worked out once per file for a whole report.
class JsonPaths {
 public:
  explicit JsonPaths(const SourceManager& sm) : sm_(sm) {}
  const std::string& of(FileId id);  // "-" for kNoFile
  const SourceManager& sources() const { return sm_; }

 private:
  const SourceManager& sm_;
  std::map<FileId, std::string> paths_;
};

/// One diagnostic as the object `json` and `json-lines` print; its "url" is rule_url(docs_base, name).
void write_diagnostic_json(JsonWriter& w, JsonPaths& paths, const Diagnostic& d, std::string_view docs_base);
/// Every diagnostic through write_diagnostic_json to `os`, in order, by writers `depth` containers deep (json: 2,
/// inside its "diagnostics" array, `first`: none written there yet; json-lines: 0, a line each). Thousands of
/// findings are written in pieces on up to o.threads threads, a few pieces at a time, each to a buffer of its own.
void write_diagnostics_json(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                            const RenderOptions& o, size_t depth, bool first);

/// Text with invalid UTF-8 replaced by U+FFFD and control characters escaped, safe for terminals and JSON.
std::string sanitize(std::string_view s);
/// Text with invalid UTF-8 replaced by U+FFFD but every other byte kept, line endings and control characters too:
/// a fix's replacement text in JSON, which escapes them (sanitize() made the line ending of an inserted line U+FFFD).
std::string valid_utf8(std::string_view s);

/// The source line of an edit's start after applying the fix's edits to it (for the `help:` preview), with its
/// 1-based line number; nullopt when the fix has no edit in a known file. `lines`: what that line (and any line an
/// edit starting on it reaches into) becomes, one entry per line: two or more when the fix splits it. `removed`:
/// the line is gone.
struct FixPreview {
  uint32_t line = 0;
  std::vector<std::string> lines;
  bool removed = false;
};
std::optional<FixPreview> fix_preview(const SourceManager& sm, const Fix& fix);

}  // namespace rrflint
