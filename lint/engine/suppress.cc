#include "lint/engine/suppress.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <set>
#include <tuple>

#include "lint/engine/linter.h"
#include "lint/engine/rule.h"

namespace rrflint {
namespace {


bool blank(char c) { return c == ' ' || c == '\t'; }

char ascii_lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; }

// Case-insensitive (ASCII) equality, without the copies of to_lower (it runs on every comment).
bool ieq(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (ascii_lower(a[i]) != ascii_lower(b[i])) return false;
  return true;
}

// Which editor lines hold code (a command or meta command), from the parser's logical lines.
std::vector<bool> code_lines(const ParsedFile& pf) {
  const SourceFile& f = *pf.source;
  std::vector<bool> has(f.line_count(), false);
  // Logical lines are editor lines, except that a NUL byte splits one: walk both in step.
  uint32_t editor = 0;
  for (const Line& l : pf.lines) {
    while (editor + 1 < f.line_count() && f.line_span(editor + 1).begin <= l.span.begin) ++editor;
    if (!l.code.empty()) has[editor] = true;
  }
  return has;
}

// Parses the directive in one comment, if it has one. `comment` starts at its ';'.
std::optional<Directive> parse_comment(const ParsedFile& pf, const RuleSet& rules, const Line& line) {
  const std::string_view text = pf.source->text();
  const uint32_t end = line.comment.end;
  for (uint32_t semi = line.comment.begin; semi < end; ++semi) {
    const void* next = std::memchr(text.data() + semi, ';', end - semi);
    if (!next) break;
    semi = static_cast<uint32_t>(static_cast<const char*>(next) - text.data());
    uint32_t p = semi + 1;
    while (p < end && blank(text[p])) ++p;
    if (end - p < 7 || !ieq(text.substr(p, 7), "rrflint")) continue;
    p += 7;
    while (p < end && blank(text[p])) ++p;
    if (p >= end || text[p] != ':') continue;  // `rrflint-options:` and prose are not directives
    ++p;
    Directive d;
    d.span = Span{semi, end};
    d.starts_comment = semi == line.comment.begin;
    d.own_line = line.code.empty();
    d.line = pf.source->line_of(semi);
    while (p < end && blank(text[p])) ++p;
    const uint32_t kw_begin = p;
    while (p < end && (std::isalpha(static_cast<unsigned char>(text[p])) || text[p] == '-')) ++p;
    d.keyword = Span{kw_begin, p};
    const std::string kw = to_lower(text.substr(kw_begin, p - kw_begin));
    if (kw == "disable") d.kind = d.own_line ? DirectiveKind::RangeStart : DirectiveKind::Line;
    else if (kw == "disable-next-line") d.kind = DirectiveKind::NextLine;
    else if (kw == "disable-file") d.kind = DirectiveKind::File;
    else if (kw == "enable") d.kind = DirectiveKind::RangeEnd;
    else {
      d.bad_keyword = true;
      d.problem = kw.empty() ? std::string("empty suppression directive: write e.g. '; rrflint: disable=RRF101'")
                             : fmt::format("unknown suppression directive '{}': use disable, disable-next-line, "
                                           "disable-file or enable",
                                           text.substr(kw_begin, p - kw_begin));
      return d;
    }
    while (p < end && blank(text[p])) ++p;
    if (p >= end || text[p] != '=') {
      // `enable` alone (or with a reason) closes every open range; anything else needs a list.
      const bool rest_ok = p >= end || text[p] == ';' || (text[p] == '-' && p + 1 < end && text[p + 1] == '-');
      d.list = Span{p, p};
      if (d.kind == DirectiveKind::RangeEnd && rest_ok) {
        SuppressionEntry all;
        all.all = true;
        all.span = d.keyword;
        all.text = "all";
        d.entries.push_back(all);
      } else {
        d.bad_keyword = true;
        d.problem = fmt::format("expected '=' and a rule list after '{}'", text.substr(kw_begin, d.keyword.end - kw_begin));
      }
      return d;
    }
    ++p;
    // The list ends at ';', at ` --` or at the end of the comment.
    uint32_t list_end = p;
    while (list_end < end && text[list_end] != ';' &&
           !(text[list_end] == '-' && list_end + 1 < end && text[list_end + 1] == '-' &&
             (list_end == p || blank(text[list_end - 1]))))
      ++list_end;
    uint32_t reason_begin = list_end;
    if (reason_begin < end) reason_begin += text[reason_begin] == ';' ? 1 : 2;
    while (reason_begin < end && blank(text[reason_begin])) ++reason_begin;
    uint32_t reason_end = end;
    while (reason_end > reason_begin && blank(text[reason_end - 1])) --reason_end;
    d.reason = Span{std::min(reason_begin, end), std::max(std::min(reason_begin, end), reason_end)};
    uint32_t lb = p, le = list_end;
    while (lb < le && blank(text[lb])) ++lb;
    while (le > lb && blank(text[le - 1])) --le;
    d.list = Span{lb, le};
    for (uint32_t q = lb; q < le;) {
      while (q < le && (blank(text[q]) || text[q] == ',')) ++q;
      const uint32_t nb = q;
      while (q < le && !blank(text[q]) && text[q] != ',') ++q;
      if (q == nb) break;
      SuppressionEntry e;
      e.span = Span{nb, q};
      e.text = std::string(text.substr(nb, q - nb));
      if (ieq(e.text, "all")) e.all = true;
      else e.rule = rules.find(e.text);
      if (!e.rule && !e.all && e.text.size() >= 4 && to_lower(e.text).starts_with("rrf"))
        for (const Rule* r : rules.all())
          if (to_lower(r->meta.code).starts_with(to_lower(e.text))) e.prefix = to_lower(e.text);
      d.entries.push_back(std::move(e));
    }
    return d;
  }
  return std::nullopt;
}

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// "did you mean 'g10-missing-z'?" for a near miss, else "".
std::string suggestion(std::string_view written, const RuleSet& rules) {
  const std::string w = to_lower(written);
  // A code-like word ("RRF999") has no meaningful near miss: codes one digit apart are unrelated rules.
  if (w.size() >= 4 && w.starts_with("rrf") && std::isdigit(static_cast<unsigned char>(w[3]))) return "";
  const Rule* best = nullptr;
  size_t best_d = SIZE_MAX;
  for (const Rule* r : rules.all()) {
    const size_t d = edit_distance(w, to_lower(r->meta.name));
    if (d < best_d) {
      best_d = d;
      best = r;
    }
  }
  if (!best || best_d > std::max<size_t>(2, w.size() / 4)) return "";
  return fmt::format("; did you mean '{}' ({})?", best->meta.name, best->meta.code);
}

struct FileDirectives {
  const FileUnit* unit = nullptr;
  std::vector<Directive> directives;
};

}  // namespace

bool entry_names(const SuppressionEntry& e, std::string_view code) {
  if (e.all) return true;
  if (e.rule) return e.rule->meta.code == code;
  return !e.prefix.empty() && to_lower(code).starts_with(e.prefix);
}

std::vector<const Rule*> engine_rules() { return {&unused_suppression, &unknown_rule_in_suppression}; }

std::string_view directive_keyword(DirectiveKind k) {
  switch (k) {
    case DirectiveKind::Line: return "disable";
    case DirectiveKind::NextLine: return "disable-next-line";
    case DirectiveKind::RangeStart: return "disable";
    case DirectiveKind::RangeEnd: return "enable";
    case DirectiveKind::File: return "disable-file";
  }
  return "?";
}

std::vector<Directive> parse_directives(const ParsedFile& pf, const RuleSet& rules) {
  std::vector<Directive> out;
  const SourceFile& f = *pf.source;
  if (f.line_count() == 0) return out;
  // A directive has a ':'; most comments are prose without one.
  for (const uint32_t li : pf.prefilters.colon_comment_lines) {
    if (auto d = parse_comment(pf, rules, pf.lines[li])) out.push_back(std::move(*d));
  }
  if (out.empty()) return out;
  const std::vector<bool> has_code = code_lines(pf);
  const uint32_t last = f.line_count() - 1;
  // Open ranges, in order, as (directive, entry) indices.
  std::vector<std::pair<size_t, size_t>> open;
  for (size_t di = 0; di < out.size(); ++di) {
    Directive& d = out[di];
    if (d.bad_keyword) continue;
    for (size_t ei = 0; ei < d.entries.size(); ++ei) {
      SuppressionEntry& e = d.entries[ei];
      switch (d.kind) {
        case DirectiveKind::Line:
          e.first_line = e.last_line = d.line;
          break;
        case DirectiveKind::NextLine: {
          uint32_t n = d.line + 1;
          while (n <= last && !has_code[n]) ++n;
          if (n <= last) e.first_line = e.last_line = n;
          else e.first_line = 1, e.last_line = 0;
          break;
        }
        case DirectiveKind::File:
          e.first_line = 0;
          e.last_line = last;
          break;
        case DirectiveKind::RangeStart:
          e.first_line = d.line + 1;
          e.last_line = last;
          if (e.first_line > last) e.first_line = 1, e.last_line = 0;
          open.emplace_back(di, ei);
          break;
        case DirectiveKind::RangeEnd: {
          // Closes the open ranges for the same rule (`all` closes every one).
          e.first_line = 1;
          e.last_line = 0;
          for (auto it = open.begin(); it != open.end();) {
            SuppressionEntry& s = out[it->first].entries[it->second];
            const bool same = e.all || (e.rule && s.rule == e.rule) || (!e.rule && !s.all && !s.rule && ieq(e.text, s.text));
            if (same) {
              s.last_line = d.line;
              e.used = true;  // an enable that closes a range does its job
              it = open.erase(it);
            } else {
              ++it;
            }
          }
          break;
        }
      }
    }
  }
  return out;
}

void apply_suppressions(MachineResult& res, const RuleSet& rules, const std::vector<const Rule*>& enabled,
                        const LintOptions& options,
                        std::vector<std::vector<Directive>>* directives) {
  Machine& m = *res.machine;
  std::map<FileId, const FileUnit*> units;
  for (uint32_t i = 0; i < m.unit_count(); ++i) units[m.unit(i).source->id()] = &m.unit(i);
  auto& diags = res.diagnostics;

  // Per-file ignores (config file) first: those rules are off for that file.
  auto ignored = [&](FileId file, std::string_view code) {
    if (!options.ignored_in_file) return false;
    auto it = units.find(file);
    return it != units.end() && options.ignored_in_file(*it->second->source, code);
  };
  if (options.ignored_in_file)
    diags.erase(std::remove_if(diags.begin(), diags.end(),
                               [&](const Diagnostic& d) { return d.loc.file != kNoFile && ignored(d.loc.file, d.code); }),
                diags.end());
  if (!options.inline_suppressions) return;

  std::map<FileId, FileDirectives> files;
  for (const auto& [id, u] : units) {
    FileDirectives fd;
    fd.unit = u;
    fd.directives = directives ? std::move((*directives)[u->index]) : parse_directives(u->parsed, rules);
    if (!fd.directives.empty()) files.emplace(id, std::move(fd));
  }
  if (files.empty()) return;

  std::set<std::string_view> on;
  for (const Rule* r : enabled) on.insert(r->meta.code);
  const Rule* unused_rule = &unused_suppression;
  const Rule* unknown_rule = &unknown_rule_in_suppression;
  const std::string_view kUnusedCode = unused_rule->meta.code, kUnknownCode = unknown_rule->meta.code;

  // Removes the diagnostics a directive covers and marks those directives used.
  auto filter = [&](std::vector<Diagnostic>& list) {
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](const Diagnostic& d) {
                                auto it = files.find(d.loc.file);
                                if (it == files.end()) return false;
                                const uint32_t line = it->second.unit->source->line_of(d.loc.span.begin);
                                bool hit = false;
                                for (Directive& dir : it->second.directives) {
                                  if (dir.kind == DirectiveKind::RangeEnd) continue;
                                  for (SuppressionEntry& e : dir.entries) {
                                    if (!entry_names(e, d.code)) continue;
                                    if (line < e.first_line || line > e.last_line) continue;
                                    e.used = true;
                                    hit = true;
                                  }
                                }
                                return hit;
                              }),
               list.end());
  };
  auto make = [&](const Rule* rule, const FileUnit& u, Span span, std::string message) {
    Diagnostic d;
    d.code = rule->meta.code;
    d.name = rule->meta.name;
    d.severity = rule->meta.severity;
    if (auto it = options.severity.find(std::string(d.code)); it != options.severity.end()) d.severity = it->second;
    d.loc = Location{u.source->id(), span};
    d.message = std::move(message);
    return d;
  };

  filter(diags);

  // RRF901: directives that name no known rule, or are not directives at all.
  if (on.count(kUnknownCode)) {
    std::vector<Diagnostic> found;
    for (auto& [id, fd] : files) {
      if (ignored(id, kUnknownCode)) continue;
      const std::string_view text = fd.unit->source->text();
      for (const Directive& d : fd.directives) {
        if (d.bad_keyword) {
          found.push_back(make(unknown_rule, *fd.unit, d.keyword.empty() ? d.span : d.keyword, d.problem));
          continue;
        }
        if (d.entries.empty()) {
          found.push_back(make(unknown_rule, *fd.unit, d.span,
                               fmt::format("'{}=' names no rule", text.substr(d.keyword.begin, d.keyword.size()))));
          continue;
        }
        for (const SuppressionEntry& e : d.entries)
          if (!e.rule && !e.all && e.prefix.empty())
            found.push_back(make(unknown_rule, *fd.unit, e.span,
                                 fmt::format("unknown rule '{}' in suppression comment{}", e.text, suggestion(e.text, rules))));
      }
    }
    filter(found);
    diags.insert(diags.end(), found.begin(), found.end());
  }

  // RRF900: entries for rules of this run that suppressed nothing. Entries that name RRF900 itself (or `all`)
  // are judged last, after they had the chance to suppress the other RRF900 findings.
  if (on.count(kUnusedCode)) {
    auto counted = [&](FileId file, const SuppressionEntry& e) {
      for (std::string_view code : on)
        if (entry_names(e, code) && !ignored(file, code)) return true;
      return false;
    };
    auto self = [&](const SuppressionEntry& e) { return entry_names(e, kUnusedCode); };
    auto report = [&](bool self_pass) {
      std::vector<Diagnostic> found;
      for (auto& [id, fd] : files) {
        if (ignored(id, kUnusedCode)) continue;
        const SourceFile& src = *fd.unit->source;
        const std::string_view text = src.text();
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
          std::string names;
          for (const SuppressionEntry* e : unused) names += fmt::format("{}'{}'", names.empty() ? "" : ", ", e->text);
          std::string where;
          switch (d.kind) {
            case DirectiveKind::Line: where = "no such finding on this line"; break;
            case DirectiveKind::NextLine: where = "no such finding on the next line"; break;
            case DirectiveKind::RangeStart: where = "no such finding in the range it opens"; break;
            case DirectiveKind::File: where = "no such finding in this file"; break;
            case DirectiveKind::RangeEnd: where = "it closes no 'disable' range"; break;
          }
          const bool whole = unused.size() == d.entries.size();
          const Span at = whole || unused.size() > 1 ? d.span : unused.front()->span;
          Diagnostic diag = make(unused_rule, *fd.unit, at,
                                 fmt::format("unused suppression {} in '{}': {}", names,
                                             text.substr(d.keyword.begin, d.keyword.size()), where));
          Fix fix;
          fix.applicability = Applicability::Safe;
          if (whole) {
            fix.title = "remove the suppression comment";
            const uint32_t line0 = d.line;
            const Span ls = src.line_span(line0);
            if (d.own_line && d.starts_comment) {
              uint32_t e = ls.end + static_cast<uint32_t>(src.terminator(line0).size());
              fix.edits.push_back(Edit{Location{src.id(), Span{ls.begin, e}}, ""});
            } else {
              uint32_t b = d.span.begin;
              while (b > ls.begin && blank(text[b - 1])) --b;
              fix.edits.push_back(Edit{Location{src.id(), Span{b, d.span.end}}, ""});
            }
          } else {
            fix.title = fmt::format("remove {} from the suppression", names);
            std::string kept;
            for (const SuppressionEntry& e : d.entries)
              if (std::find(unused.begin(), unused.end(), &e) == unused.end())
                kept += (kept.empty() ? "" : ",") + e.text;
            fix.edits.push_back(Edit{Location{src.id(), d.list}, kept});
          }
          diag.fix = std::move(fix);
          found.push_back(std::move(diag));
        }
      }
      return found;
    };
    std::vector<Diagnostic> first = report(false);
    filter(first);
    std::vector<Diagnostic> second = report(true);
    diags.insert(diags.end(), first.begin(), first.end());
    diags.insert(diags.end(), second.begin(), second.end());
  }

  std::stable_sort(diags.begin(), diags.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.loc.file, a.loc.span.begin, a.code, a.loc.span.end) <
           std::tie(b.loc.file, b.loc.span.begin, b.code, b.loc.span.end);
  });
}

std::vector<Edit> suppression_edits(const ParsedFile& pf, const RuleSet& rules, const std::map<uint32_t, std::vector<std::string>>& by_line,
                                    std::string_view reason) {
  std::vector<Edit> edits;
  const SourceFile& f = *pf.source;
  const std::string_view text = f.text();
  const std::vector<bool> has_code = code_lines(pf);
  const std::vector<Directive> directives = parse_directives(pf, rules);
  const std::string why = reason.empty() ? "" : fmt::format(" -- {}", reason);
  std::vector<std::string> file_level;
  for (const auto& [line0, names] : by_line) {
    if (line0 >= f.line_count()) continue;
    if (!has_code[line0]) {
      for (const std::string& n : names)
        if (std::find(file_level.begin(), file_level.end(), n) == file_level.end()) file_level.push_back(n);
      continue;
    }
    const Directive* existing = nullptr;
    for (const Directive& d : directives)
      if (d.line == line0 && d.kind == DirectiveKind::Line && !d.bad_keyword) existing = &d;
    if (existing) {
      std::string add;
      for (const std::string& n : names) {
        const Rule* r = rules.find(n);
        bool have = std::any_of(existing->entries.begin(), existing->entries.end(),
                                [&](const SuppressionEntry& e) { return r && entry_names(e, r->meta.code); });
        if (!have) add += (existing->entries.empty() && add.empty() ? "" : ",") + n;
      }
      if (!add.empty()) edits.push_back(Edit{Location{f.id(), Span{existing->list.end, existing->list.end}}, add});
      continue;
    }
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ",") + n;
    const Span ls = f.line_span(line0);
    // A line with a parse error (an unterminated string or `{`) may swallow an appended `;`: put the directive
    // on a line of its own above it instead, with the same indentation (so it stays inside its block).
    // (`ln`: clang 14 cannot capture a structured binding.)
    const bool broken = std::any_of(pf.errors.begin(), pf.errors.end(), [&, ln = line0](const ParseError& e) {
      return e.span.begin < f.size() && f.line_of(e.span.begin) == ln;
    });
    if (broken) {
      uint32_t ind = ls.begin;
      while (ind < ls.end && blank(text[ind])) ++ind;
      std::string eol(f.terminator(line0));
      if (eol.empty()) eol = f.endings().crlf > f.endings().lf ? "\r\n" : "\n";
      edits.push_back(Edit{Location{f.id(), Span{ls.begin, ls.begin}},
                           fmt::format("{}; rrflint: disable-next-line={}{}{}", text.substr(ls.begin, ind - ls.begin),
                                       list, why, eol)});
      continue;
    }
    uint32_t at = ls.end;
    while (at > ls.begin && blank(text[at - 1])) --at;
    edits.push_back(Edit{Location{f.id(), Span{at, at}}, fmt::format(" ; rrflint: disable={}{}", list, why)});
  }
  if (!file_level.empty()) {
    std::string list;
    for (const std::string& n : file_level) list += (list.empty() ? "" : ",") + n;
    std::string eol = f.line_count() > 0 ? std::string(f.terminator(0)) : "";
    if (eol.empty()) eol = f.endings().crlf > f.endings().lf ? "\r\n" : "\n";
    edits.push_back(Edit{Location{f.id(), Span{0, 0}}, fmt::format("; rrflint: disable-file={}{}{}", list, why, eol)});
  }
  return edits;
}

}  // namespace rrflint
