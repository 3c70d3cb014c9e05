#include "lint/engine/suppress.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <tuple>

#include "lint/engine/linter.h"
#include "lint/engine/rule.h"

namespace rrflint {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

struct FileDirectives {
  const FileUnit* unit = nullptr;
  std::vector<Directive> directives;
};

// Per-file ignores (config file): is rule `code` switched off for the file `file`?
struct FileIgnores {
  const std::map<FileId, const FileUnit*>& units;
  const LintOptions& options;
  bool operator()(FileId file, std::string_view code) const {
    if (!options.ignored_in_file) return false;
    auto it = units.find(file);
    return it != units.end() && options.ignored_in_file(*it->second->source, code);
  }
};

// Drops the diagnostics of rules switched off for their file.
void drop_per_file_ignores(std::vector<Diagnostic>& diags, const FileIgnores& ignored) {
  if (ignored.options.ignored_in_file)
    diags.erase(
        std::remove_if(diags.begin(), diags.end(),
                       [&](const Diagnostic& d) { return d.loc.file != kNoFile && ignored(d.loc.file, d.code); }),
        diags.end());
}

// The directives of every file that has any, by file. `directives`: see apply_suppressions.
std::map<FileId, FileDirectives> read_directives(const std::map<FileId, const FileUnit*>& units, const RuleSet& rules,
                                                 std::vector<std::vector<Directive>>* directives) {
  std::map<FileId, FileDirectives> files;
  for (const auto& [id, u] : units) {
    FileDirectives fd;
    fd.unit = u;
    fd.directives = directives ? std::move((*directives)[u->index]) : parse_directives(u->parsed, rules);
    if (!fd.directives.empty()) files.emplace(id, std::move(fd));
  }
  return files;
}

// What an unused directive of kind `k` failed to find.
std::string_view unused_where(DirectiveKind k) {
  switch (k) {
    case DirectiveKind::Line: return "no such finding on this line";
    case DirectiveKind::NextLine: return "no such finding on the next line";
    case DirectiveKind::RangeStart: return "no such finding in the range it opens";
    case DirectiveKind::File: return "no such finding in this file";
    case DirectiveKind::RangeEnd: return "it closes no 'disable' range";
  }
  return "";
}

// The fix of an RRF900 finding: remove the whole comment (`whole`: every entry is unused), or the unused entries
// from its list.
Fix unused_fix(const SourceFile& src, const Directive& d, const std::vector<const SuppressionEntry*>& unused,
               bool whole, const std::string& names) {
  const std::string_view text = src.text();
  Fix fix = Fix::safe(whole ? std::string("remove the suppression comment")
                            : fmt::format("remove {} from the suppression", names));
  if (whole) {
    const uint32_t line0 = d.line;
    const Span ls = src.line_span(line0);
    if (d.own_line && d.starts_comment) {
      uint32_t e = ls.end + static_cast<uint32_t>(src.terminator(line0).size());
      fix.edits.push_back(Edit::remove(Location{src.id(), Span{ls.begin, e}}));
    } else {
      uint32_t b = d.span.begin;
      while (b > ls.begin && blank(text[b - 1])) --b;
      fix.edits.push_back(Edit::remove(Location{src.id(), Span{b, d.span.end}}));
    }
  } else {
    std::string kept;
    for (const SuppressionEntry& e : d.entries)
      if (std::find(unused.begin(), unused.end(), &e) == unused.end()) kept += (kept.empty() ? "" : ",") + e.text;
    fix.edits.push_back(Edit::replace(Location{src.id(), d.list}, kept));
  }
  return fix;
}

// The directives of a run's files judged against its diagnostics: what they suppress, RRF901 and RRF900.
class SuppressionPass {
 public:
  SuppressionPass(std::map<FileId, FileDirectives>& files, const FileIgnores& ignored, const RuleSet& rules,
                  const std::vector<const Rule*>& enabled, const LintOptions& options)
      : files_(files), ignored_(ignored), rules_(rules), options_(options) {
    for (const Rule* r : enabled) on_.insert(r->meta.code);
  }

  /// Is the rule with this code on in this run?
  bool on(std::string_view code) const { return on_.count(code) != 0; }

  // Removes the findings a directive covers, and marks `used` each entry that covers one. By file and code: the
  // entries naming the code, sorted by first line with the farthest last line so far, say by a binary search
  // whether a finding's line is covered; an entry is used when some finding of the code lies in its lines (a
  // binary search in their sorted lines). Every finding against every entry took seconds for a file of 20,000
  // suppression comments.
  void filter(std::vector<Diagnostic>& list) {
    std::map<std::pair<FileId, std::string_view>, std::vector<size_t>> groups;  // findings by file and code
    for (size_t i = 0; i < list.size(); ++i)
      if (files_.count(list[i].loc.file)) groups[{list[i].loc.file, list[i].code}].push_back(i);
    std::vector<char> drop(list.size(), 0);
    for (const auto& [key, found] : groups) {
      FileDirectives& fd = files_.at(key.first);
      std::vector<SuppressionEntry*> entries;
      for (Directive& dir : fd.directives) {
        if (dir.kind == DirectiveKind::RangeEnd) continue;
        for (SuppressionEntry& e : dir.entries)
          if (e.first_line <= e.last_line && entry_names(e, key.second)) entries.push_back(&e);
      }
      if (entries.empty()) continue;
      std::stable_sort(entries.begin(), entries.end(), [](const SuppressionEntry* x, const SuppressionEntry* y) {
        return x->first_line < y->first_line;
      });
      std::vector<uint32_t> reach(entries.size());  // the farthest last line among entries [0, k]
      for (size_t k = 0; k < entries.size(); ++k) reach[k] = std::max(entries[k]->last_line, k ? reach[k - 1] : 0u);
      std::vector<uint32_t> lines;
      for (const size_t i : found) {
        const uint32_t line = fd.unit->source->line_of(list[i].loc.span.begin);
        lines.push_back(line);
        auto after = std::upper_bound(entries.begin(), entries.end(), line,
                                      [](uint32_t l, const SuppressionEntry* e) { return l < e->first_line; });
        if (after != entries.begin() && reach[static_cast<size_t>(after - entries.begin()) - 1] >= line) drop[i] = 1;
      }
      std::sort(lines.begin(), lines.end());
      for (SuppressionEntry* e : entries) {
        auto it = std::lower_bound(lines.begin(), lines.end(), e->first_line);
        if (it != lines.end() && *it <= e->last_line) e->used = true;
      }
    }
    size_t kept = 0;
    for (size_t i = 0; i < list.size(); ++i)
      if (!drop[i]) {
        if (kept != i) list[kept] = std::move(list[i]);
        ++kept;
      }
    list.resize(kept);
  }

  /// RRF901: directives that name no known rule, or are not directives at all.
  void report_unknown_rules(std::vector<Diagnostic>& diags) {
    const Rule* unknown_rule = &unknown_rule_in_suppression;
    std::vector<Diagnostic> found;
    for (auto& [id, fd] : files_) {
      if (ignored_(id, unknown_rule->meta.code)) continue;
      const std::string_view text = fd.unit->source->text();
      for (const Directive& d : fd.directives) {
        if (d.bad_keyword) {
          found.push_back(make(unknown_rule, *fd.unit, d.keyword.empty() ? d.span : d.keyword, d.problem));
          continue;
        }
        if (d.entries.empty()) {
          found.push_back(
              make(unknown_rule, *fd.unit, d.span,
                   fmt::format("'{}=' names no rule", clip(text.substr(d.keyword.begin, d.keyword.size())))));
          continue;
        }
        for (const SuppressionEntry& e : d.entries)
          if (!e.rule && !e.all && e.prefix.empty())
            found.push_back(make(unknown_rule, *fd.unit, e.span,
                                 fmt::format("unknown rule '{}' in suppression comment{}", clip(e.text),
                                             near_miss_hint(e.text, rules_))));
      }
    }
    filter(found);
    diags.insert(diags.end(), found.begin(), found.end());
  }

  /// RRF900: entries for rules of this run that suppressed nothing. Entries that name RRF900 itself (or `all`)
  /// are judged last, after they had the chance to suppress the other RRF900 findings.
  void report_unused(std::vector<Diagnostic>& diags) {
    std::vector<Diagnostic> first = unused_findings(false);
    filter(first);
    std::vector<Diagnostic> second = unused_findings(true);
    diags.insert(diags.end(), first.begin(), first.end());
    diags.insert(diags.end(), second.begin(), second.end());
  }

 private:
  Diagnostic make(const Rule* rule, const FileUnit& u, Span span, std::string message) const {
    Diagnostic d;
    d.code = rule->meta.code;
    d.name = rule->meta.name;
    d.severity = rule->meta.severity;
    if (auto it = options_.severity.find(std::string(d.code)); it != options_.severity.end()) d.severity = it->second;
    d.loc = Location{u.source->id(), span};
    d.message = std::move(message);
    return d;
  }

  // Does the entry name a rule of this run that is on for the file?
  bool counted(FileId file, const SuppressionEntry& e) const {
    for (std::string_view code : on_)
      if (entry_names(e, code) && !ignored_(file, code)) return true;
    return false;
  }

  static bool self(const SuppressionEntry& e) { return entry_names(e, unused_suppression.meta.code); }

  // The RRF900 findings of the first pass (entries not naming RRF900) or of the second (`self_pass`).
  std::vector<Diagnostic> unused_findings(bool self_pass) const {
    std::vector<Diagnostic> found;
    for (auto& [id, fd] : files_) {
      if (ignored_(id, unused_suppression.meta.code)) continue;
      for (const Directive& d : fd.directives) {
        if (d.bad_keyword) continue;
        std::vector<const SuppressionEntry*> unused;
        bool any_other_pass_unused = false;
        for (const SuppressionEntry& e : d.entries) {
          if (e.used || !counted(id, e)) continue;
          if (self(e) == self_pass) unused.push_back(&e);
          else any_other_pass_unused = true;
        }
        if (unused.empty()) continue;
        // In the first pass, leave a directive that also has a self entry still to judge for the second.
        if (!self_pass && any_other_pass_unused) continue;
        if (self_pass) {
          // Collect the first-pass unused entries of this directive too, so one finding lists them all.
          for (const SuppressionEntry& e : d.entries)
            if (!e.used && counted(id, e) && !self(e)) unused.push_back(&e);
        }
        found.push_back(unused_finding(*fd.unit, d, unused));
      }
    }
    return found;
  }

  // One RRF900 finding: the unused entries of directive `d`, with the fix that removes them.
  Diagnostic unused_finding(const FileUnit& u, const Directive& d,
                            const std::vector<const SuppressionEntry*>& unused) const {
    const SourceFile& src = *u.source;
    const std::string_view text = src.text();
    std::string names;
    for (const SuppressionEntry* e : unused) names += fmt::format("{}'{}'", names.empty() ? "" : ", ", e->text);
    const bool whole = unused.size() == d.entries.size();
    const Span at = whole || unused.size() > 1 ? d.span : unused.front()->span;
    Diagnostic diag = make(&unused_suppression, u, at,
                           fmt::format("unused suppression {} in '{}': {}", names,
                                       text.substr(d.keyword.begin, d.keyword.size()), unused_where(d.kind)));
    // No fix when the comment's ';' also cut an expression short (RRF113): the "comment" then holds the rest of the
    // expression, text meant as code, which removing the comment would delete.
    const Span ls = src.line_span(d.line);
    if (!whole || d.own_line || !u.parsed.any_cut_from(ls.begin, d.span.begin + 1))
      diag.fix = unused_fix(src, d, unused, whole, names);
    return diag;
  }

  std::map<FileId, FileDirectives>& files_;
  const FileIgnores& ignored_;
  const RuleSet& rules_;
  const LintOptions& options_;
  std::set<std::string_view> on_;
};

}  // namespace

std::vector<const Rule*> engine_rules() { return {&unused_suppression, &unknown_rule_in_suppression}; }

bool is_suppression_finding(const Diagnostic& d) {
  return d.code == unused_suppression.meta.code || d.code == unknown_rule_in_suppression.meta.code;
}

void apply_suppressions(MachineResult& res, const RuleSet& rules, const std::vector<const Rule*>& enabled,
                        const LintOptions& options, std::vector<std::vector<Directive>>* directives) {
  Machine& m = *res.machine;
  std::map<FileId, const FileUnit*> units;
  for (uint32_t i = 0; i < m.unit_count(); ++i) units[m.unit(i).source->id()] = &m.unit(i);
  auto& diags = res.diagnostics;

  // Per-file ignores (config file) first: those rules are off for that file.
  const FileIgnores ignored{units, options};
  drop_per_file_ignores(diags, ignored);
  if (!options.inline_suppressions) return;

  std::map<FileId, FileDirectives> files = read_directives(units, rules, directives);
  if (files.empty()) return;
  SuppressionPass pass(files, ignored, rules, enabled, options);
  pass.filter(diags);
  if (pass.on(unknown_rule_in_suppression.meta.code)) pass.report_unknown_rules(diags);
  if (pass.on(unused_suppression.meta.code)) pass.report_unused(diags);

  std::stable_sort(diags.begin(), diags.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.loc.file, a.loc.span.begin, a.code, a.loc.span.end) <
           std::tie(b.loc.file, b.loc.span.begin, b.code, b.loc.span.end);
  });
}

std::string near_miss_hint(std::string_view written, const RuleSet& rules) {
  const Rule* r = rules.near_miss(written);
  return r ? fmt::format("; did you mean '{}' ({})?", r->meta.name, r->meta.code) : "";
}

}  // namespace rrflint
