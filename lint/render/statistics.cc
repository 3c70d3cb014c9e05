// `check --statistics`, as ruff's: how many findings each rule has, instead of the findings, the most first. For a
// first look at a repository full of findings (what to fix, what to switch off, what to suppress) and for tracking
// the counts in CI. Text: a line per rule (count, code, severity, name, and how many have a fix), then the text
// format's summary. Json: {"statistics": [...], "summary": {...}, "version": 1}, the summary as `json` has it.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <ostream>
#include <string>

#include "lint/render/json_writer.h"
#include "lint/render/render.h"

namespace rrflint {
namespace {

struct RuleCount {
  std::string_view code, name;
  Severity severity = Severity::Info;  // the most severe of its findings ([severity] may differ per machine)
  size_t count = 0, fixable = 0, unsafe_fixable = 0;
};

// Per rule, the most findings first, then by code.
std::vector<RuleCount> per_rule(const std::vector<Diagnostic>& diags) {
  std::map<std::string_view, RuleCount> by_code;
  for (const Diagnostic& d : diags) {
    RuleCount& c = by_code[d.code];
    c.code = d.code;
    c.name = d.name;
    c.severity = std::max(c.severity, d.severity);
    ++c.count;
    if (d.fix) ++(d.fix->applicability == Applicability::Safe ? c.fixable : c.unsafe_fixable);
  }
  std::vector<RuleCount> out;
  for (const auto& [code, c] : by_code) out.push_back(c);
  std::stable_sort(out.begin(), out.end(), [](const RuleCount& a, const RuleCount& b) { return a.count > b.count; });
  return out;
}

}  // namespace

void render_statistics(std::ostream& os, const std::vector<Diagnostic>& diags, const RenderOptions& o, bool json) {
  const std::vector<RuleCount> rules = per_rule(diags);
  if (json) {
    std::string buf;
    JsonWriter w(buf, 2);
    w.begin_object();
    w.key("statistics");
    w.begin_array();
    for (const RuleCount& r : rules) {
      w.begin_object();
      w.member("code", r.code);
      w.member("count", uint64_t{r.count});
      w.member("fixable", uint64_t{r.fixable});
      w.member("name", r.name);
      w.member("severity", severity_name(r.severity));
      w.member("unsafe_fixable", uint64_t{r.unsafe_fixable});
      w.member("url", rule_url(o.docs_base, r.name));
      w.end_object();
    }
    w.end_array();
    write_summary_json(w, diags, o);
    w.member("version", 1);
    w.end_object();
    os << buf << "\n";
    return;
  }
  size_t count_width = 1, name_width = 0;
  for (const RuleCount& r : rules) {
    count_width = std::max(count_width, std::to_string(r.count).size());
    name_width = std::max(name_width, r.name.size());
  }
  for (const RuleCount& r : rules) {
    std::string fixes;
    if (r.fixable) fixes = fmt::format("  {} fixable with --fix", r.fixable);
    if (r.unsafe_fixable)
      fixes += fmt::format("{}{} {}with --fix --unsafe-fixes", r.fixable ? ", " : "  ", r.unsafe_fixable,
                           r.fixable ? "" : "fixable ");
    std::string line = fmt::format("{:>{}}  {}  {:<7}  {:<{}}{}", r.count, count_width, r.code,
                                   severity_name(r.severity), r.name, fixes.empty() ? 0 : name_width, fixes);
    os << line << "\n";
  }
  os << (diags.empty() ? no_problems_line(o.files_checked) + "." : summary_line(count(diags))) << "\n";
}

}  // namespace rrflint
