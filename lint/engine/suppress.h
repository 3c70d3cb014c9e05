// Suppression comments: `; rrflint: disable=…` and friends, read from each file's comments, applied to the
// diagnostics of a run, and checked themselves (RRF900 unused-suppression, RRF901 unknown-rule-in-suppression).
//
// Syntax (README.md, "Suppressing findings"). Rules are named by code or name, case-insensitively, comma-separated:
//   G1 X0 ; rrflint: disable=RRF101          a code line: that line only
//   ; rrflint: disable-next-line=a,b         own line: the next line that holds code
//   ; rrflint: disable=a  …  ; rrflint: enable=a    own line: a range (to the end of the file without enable)
//   ; rrflint: disable-file=a                anywhere: the whole file
// A reason may follow the list after ` -- ` (or after a second `;`). `all` names every rule, and a code prefix
// (`RRF3`) a block of rules, as in --select.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "lint/base/diagnostic.h"
#include "lint/syntax/parser.h"

namespace rrflint {

struct Rule;
class RuleSet;
struct LintOptions;
struct MachineResult;

/// "; did you mean 'g10-missing-z' (RRF306)?" for a misspelt rule name (RuleSet::near_miss), else "": the one wording
/// of the hint, for suppression comments, the command line and the config file.
std::string near_miss_hint(std::string_view written, const RuleSet& rules);

enum class DirectiveKind : uint8_t { Line, NextLine, RangeStart, RangeEnd, File };
std::string_view directive_keyword(DirectiveKind k);

/// One rule named in a directive, and the lines it covers.
struct SuppressionEntry {
  Span span;                   // the name as written
  std::string text;            // the name as written
  const Rule* rule = nullptr;  // nullptr: unknown, `all` or a code prefix
  bool all = false;
  std::string prefix;       // a code prefix such as "rrf3" (lower case), as --select accepts
  uint32_t first_line = 0;  // 0-based, inclusive; first > last: covers nothing
  uint32_t last_line = 0;
  bool used = false;
};

struct Directive {
  DirectiveKind kind = DirectiveKind::Line;
  Span span;                    // from the ';' before `rrflint:` to the end of the comment
  Span keyword;                 // "disable", "disable-next-line", …
  Span list;                    // the rule list, trimmed (may be empty)
  Span reason;                  // after ` -- ` or the second ';' (may be empty)
  uint32_t line = 0;            // 0-based line of the comment
  bool own_line = false;        // no code on the line
  bool starts_comment = false;  // the directive's ';' opens the line's comment
  bool bad_keyword = false;     // `rrflint:` followed by something that is not a directive
  std::string problem;          // why, for RRF901
  std::vector<SuppressionEntry> entries;
};

/// Does a directive entry name the rule with this code?
bool entry_names(const SuppressionEntry& e, std::string_view code);

/// Every directive of one parsed file, with the lines each entry covers resolved.
std::vector<Directive> parse_directives(const ParsedFile& pf, const RuleSet& rules);

/// Removes suppressed diagnostics, drops those of rules switched off for their file (per-file ignores), and
/// adds RRF900/RRF901 findings. `enabled` are the rules of this run. Called at the end of lint_machine.
/// `directives`, when given, holds parse_directives() of each unit of the machine, by unit index (worked out
/// beforehand on other threads); otherwise they are parsed here.
void apply_suppressions(MachineResult& res, const RuleSet& rules, const std::vector<const Rule*>& enabled,
                        const LintOptions& options, std::vector<std::vector<Directive>>* directives = nullptr);

/// The edits that add same-line suppressions to `pf`: `by_line` maps 0-based lines to rule names. Each is
/// appended to its line (after any comment), or merged into a `disable=` directive already on that line. Lines
/// without code get one `disable-file=` line at the top of the file instead (an own-line `disable=` would open
/// a range), and a line with a parse error (where an appended `;` could end up inside a string) gets a
/// `disable-next-line=` line above it. A non-empty `reason` is added after ` -- ` to new directives.
std::vector<Edit> suppression_edits(const ParsedFile& pf, const RuleSet& rules,
                                    const std::map<uint32_t, std::vector<std::string>>& by_line,
                                    std::string_view reason);
/// The edit that adds `; rrflint: disable-file=LIST` (and ` -- REASON` when not empty) as a line at the top of
/// `f`, with the file's line ending.
Edit file_suppression_edit(const SourceFile& f, std::string_view list, std::string_view reason);

/// The two rules of the suppression pass itself (their metadata and docs sit beside this file:
/// unused_suppression.cc, unknown_rule_in_suppression.cc). They are not in rules/: the engine produces them.
extern const Rule unused_suppression;           // RRF900
extern const Rule unknown_rule_in_suppression;  // RRF901
/// Both, for a registry to add to its rule set.
std::vector<const Rule*> engine_rules();
/// Is `d` a finding of the suppression pass (RRF900/RRF901)? Those are never suppressed by --add-suppressions.
bool is_suppression_finding(const Diagnostic& d);

}  // namespace rrflint
