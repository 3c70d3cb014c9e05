// Suppression comments as text: reading the directives of a file (parse_directives) and writing new ones
// (suppression_edits). Applying them to a run's diagnostics, and RRF900/RRF901, are in suppress.cc.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <optional>

#include "lint/engine/linter.h"
#include "lint/engine/rule.h"
#include "lint/engine/suppress.h"

namespace rrflint {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

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

// Where the directive after the ';' at `semi` starts (just after `rrflint:`), if that ';' starts one.
std::optional<uint32_t> directive_start(std::string_view text, uint32_t semi, uint32_t end) {
  uint32_t p = semi + 1;
  while (p < end && blank(text[p])) ++p;
  if (end - p < 7 || !iequals(text.substr(p, 7), "rrflint")) return std::nullopt;
  p += 7;
  while (p < end && blank(text[p])) ++p;
  if (p >= end || text[p] != ':') return std::nullopt;  // `rrflint-options:` and prose are not directives
  return p + 1;
}

// The keyword from `p` (moved past it) into d.keyword and d.kind. False when it is no directive's keyword:
// d.bad_keyword and d.problem say why.
bool parse_keyword(std::string_view text, uint32_t end, uint32_t& p, Directive& d) {
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
                           : fmt::format(
                                 "unknown suppression directive '{}': use disable, disable-next-line, "
                                 "disable-file or enable",
                                 clip(text.substr(kw_begin, p - kw_begin)));
    return false;
  }
  return true;
}

// A keyword with no '=' after it (at `p`): `enable` alone (or with a reason) closes every open range; anything
// else needs a list.
void parse_without_list(std::string_view text, uint32_t end, uint32_t p, Directive& d) {
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
    d.problem = fmt::format("expected '=' and a rule list after '{}'",
                            clip(text.substr(d.keyword.begin, d.keyword.end - d.keyword.begin)));
  }
}

// The reason after the list (which ends at `list_end`: a ';', ` --` or the end of the comment), trimmed.
Span parse_reason(std::string_view text, uint32_t list_end, uint32_t end) {
  uint32_t reason_begin = list_end;
  if (reason_begin < end) reason_begin += text[reason_begin] == ';' ? 1 : 2;
  while (reason_begin < end && blank(text[reason_begin])) ++reason_begin;
  uint32_t reason_end = end;
  while (reason_end > reason_begin && blank(text[reason_end - 1])) --reason_end;
  return Span{std::min(reason_begin, end), std::max(std::min(reason_begin, end), reason_end)};
}

// The rules named in d.list, comma- or blank-separated.
void parse_entries(std::string_view text, const RuleSet& rules, Directive& d) {
  const uint32_t lb = d.list.begin, le = d.list.end;
  for (uint32_t q = lb; q < le;) {
    while (q < le && (blank(text[q]) || text[q] == ',')) ++q;
    const uint32_t nb = q;
    while (q < le && !blank(text[q]) && text[q] != ',') ++q;
    if (q == nb) break;
    SuppressionEntry e;
    e.span = Span{nb, q};
    e.text = std::string(text.substr(nb, q - nb));
    if (iequals(e.text, "all")) e.all = true;
    else e.rule = rules.find(e.text);
    if (!e.rule && !e.all && e.text.size() >= 4 && istarts_with(e.text, "rrf"))
      for (const Rule* r : rules.all())
        if (istarts_with(r->meta.code, e.text)) e.prefix = to_lower(e.text);
    d.entries.push_back(std::move(e));
  }
}

// The list after '=' (from `p`) and the reason after it. The list ends at ';', at ` --` or at the end of the
// comment.
void parse_list(std::string_view text, const RuleSet& rules, uint32_t end, uint32_t p, Directive& d) {
  uint32_t list_end = p;
  while (list_end < end && text[list_end] != ';' &&
         !(text[list_end] == '-' && list_end + 1 < end && text[list_end + 1] == '-' &&
           (list_end == p || blank(text[list_end - 1]))))
    ++list_end;
  d.reason = parse_reason(text, list_end, end);
  uint32_t lb = p, le = list_end;
  while (lb < le && blank(text[lb])) ++lb;
  while (le > lb && blank(text[le - 1])) --le;
  d.list = Span{lb, le};
  parse_entries(text, rules, d);
}

// Parses the directive in one comment, if it has one. `comment` starts at its ';'.
std::optional<Directive> parse_comment(const ParsedFile& pf, const RuleSet& rules, const Line& line) {
  const std::string_view text = pf.source->text();
  const uint32_t end = line.comment.end;
  for (uint32_t semi = line.comment.begin; semi < end; ++semi) {
    const void* next = std::memchr(text.data() + semi, ';', end - semi);
    if (!next) break;
    semi = static_cast<uint32_t>(static_cast<const char*>(next) - text.data());
    const std::optional<uint32_t> start = directive_start(text, semi, end);
    if (!start) continue;
    uint32_t p = *start;
    Directive d;
    d.span = Span{semi, end};
    d.starts_comment = semi == line.comment.begin;
    d.own_line = line.code.empty();
    d.line = pf.source->line_of(semi);
    if (!parse_keyword(text, end, p, d)) return d;
    while (p < end && blank(text[p])) ++p;
    if (p >= end || text[p] != '=') parse_without_list(text, end, p, d);
    else parse_list(text, rules, end, p + 1, d);
    return d;
  }
  return std::nullopt;
}

}  // namespace

bool entry_names(const SuppressionEntry& e, std::string_view code) {
  if (e.all) return true;
  if (e.rule) return e.rule->meta.code == code;
  return !e.prefix.empty() && istarts_with(code, e.prefix);
}

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
  for (const uint32_t li :
       pf.prefilters.colon_comment_lines) {  // a directive has a ':'; most comments are prose without one
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
        case DirectiveKind::Line: e.first_line = e.last_line = d.line; break;
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
            const bool same =
                e.all || (e.rule && s.rule == e.rule) || (!e.rule && !s.all && !s.rule && iequals(e.text, s.text));
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

std::vector<Edit> suppression_edits(const ParsedFile& pf, const RuleSet& rules,
                                    const std::map<uint32_t, std::vector<std::string>>& by_line,
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
      if (!add.empty())
        edits.push_back(Edit::insert(Location{f.id(), Span{existing->list.end, existing->list.end}}, add));
      continue;
    }
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ",") + n;
    const Span ls = f.line_span(line0);
    // A line with a parse error (an unterminated string or `{`) may swallow an appended `;`: put the directive
    // on a line of its own above it instead, with the same indentation (so it stays inside its block).
    const uint32_t next_line = line0 + 1 < f.line_count() ? f.line_span(line0 + 1).begin : f.size();
    const bool broken = pf.any_error_from(ls.begin, next_line);
    if (broken) {
      uint32_t ind = ls.begin;
      while (ind < ls.end && blank(text[ind])) ++ind;
      const std::string_view eol = f.line_ending(line0);
      edits.push_back(Edit::insert(
          Location{f.id(), Span{ls.begin, ls.begin}},
          fmt::format("{}; rrflint: disable-next-line={}{}{}", text.substr(ls.begin, ind - ls.begin), list, why, eol)));
      continue;
    }
    uint32_t at = ls.end;
    while (at > ls.begin && blank(text[at - 1])) --at;
    edits.push_back(Edit::insert(Location{f.id(), Span{at, at}}, fmt::format(" ; rrflint: disable={}{}", list, why)));
  }
  if (!file_level.empty()) {
    std::string list;
    for (const std::string& n : file_level) list += (list.empty() ? "" : ",") + n;
    edits.push_back(file_suppression_edit(f, list, reason));
  }
  return edits;
}

Edit file_suppression_edit(const SourceFile& f, std::string_view list, std::string_view reason) {
  const std::string why = reason.empty() ? "" : fmt::format(" -- {}", reason);
  const std::string_view eol = f.line_count() > 0 ? f.line_ending(0) : f.usual_ending();
  return Edit::insert(Location{f.id(), Span{0, 0}}, fmt::format("; rrflint: disable-file={}{}{}", list, why, eol));
}

}  // namespace rrflint
