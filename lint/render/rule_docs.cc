#include "lint/render/rule_docs.h"

#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "lint/render/render.h"

namespace rrflint {
namespace {

constexpr std::string_view kBanner =
    "<!-- Generated from the rule registry by `rrflint rule --generate-docs docs/rules --readme README.md`. "
    "Do not edit by hand. -->";

struct Block {
  char digit;
  std::string_view title;
};
constexpr Block kBlocks[] = {
    {'1', "RRF1xx: syntax and lexical traps"}, {'2', "RRF2xx: order and existence"},
    {'3', "RRF3xx: tools, G10 and offsets"},   {'4', "RRF4xx: config-override.g and M501"},
    {'5', "RRF5xx: files and macros"},         {'9', "RRF9xx: rrflint itself"},
};

std::string_view fix_word(FixAvailability f) {
  switch (f) {
    case FixAvailability::None: return "none";
    case FixAvailability::Sometimes: return "sometimes";
    case FixAvailability::Always: return "always";
  }
  return "none";
}

// Escapes '|' for a Markdown table cell.
std::string cell(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else if (c == '\n') out += ' ';
    else out += c;
  }
  return out;
}

std::string tables(const RuleSet& rules, std::string_view link_prefix, std::string_view heading) {
  std::string out;
  for (const Block& b : kBlocks) {
    std::string rows;
    for (const Rule* r : rules.all()) {
      const RuleMeta& m = r->meta;
      if (m.code.size() < 4 || m.code[3] != b.digit) continue;
      rows +=
          fmt::format("| {} | [{}]({}{}.md) | {} | {} | {} | {} |\n", m.code, m.name, link_prefix, m.name,
                      severity_name(m.severity), m.default_enabled ? "on" : "off", fix_word(m.fix), cell(m.summary));
    }
    if (rows.empty()) continue;
    out += fmt::format("{} {}\n\n| code | name | severity | default | fix | summary |\n|---|---|---|---|---|---|\n{}\n",
                       heading, b.title, rows);
  }
  // Rules outside the known blocks, so nothing is ever left out.
  std::string rest;
  for (const Rule* r : rules.all()) {
    const RuleMeta& m = r->meta;
    bool known = false;
    for (const Block& b : kBlocks) known = known || (m.code.size() >= 4 && m.code[3] == b.digit);
    if (!known)
      rest +=
          fmt::format("| {} | [{}]({}{}.md) | {} | {} | {} | {} |\n", m.code, m.name, link_prefix, m.name,
                      severity_name(m.severity), m.default_enabled ? "on" : "off", fix_word(m.fix), cell(m.summary));
  }
  if (!rest.empty())
    out += fmt::format(
        "{} Other rules\n\n| code | name | severity | default | fix | summary |\n|---|---|---|---|---|---|\n{}\n",
        heading, rest);
  return out;
}

}  // namespace

std::string published_docs(std::string_view docs) {
  std::string out;
  out.reserve(docs.size());
  while (!docs.empty()) {
    const size_t nl = docs.find('\n');
    std::string_view line = docs.substr(0, nl);
    docs = nl == std::string_view::npos ? std::string_view{} : docs.substr(nl + 1);
    if (line.starts_with("```")) line = line.substr(0, line.find(' '));  // "```gcode no-test" -> "```gcode"
    out += line;
    if (nl != std::string_view::npos) out += '\n';
  }
  return out;
}

namespace {

// What an editor shows of a tagged rule's findings (docs/editors.md, "Diagnostic tags").
std::string tag_sentence(RuleTag t) {
  if (t == RuleTag::None) return "";
  return fmt::format(
      "In an editor (`rrflint server`) its findings carry the LSP tag *{}*, which most editors show as {}.\n\n",
      t == RuleTag::Unnecessary ? "Unnecessary" : "Deprecated",
      t == RuleTag::Unnecessary ? "faded text: the command, or the part of it, has no effect" : "struck-through text");
}

}  // namespace

std::string rule_page(const Rule& r) {
  const RuleMeta& m = r.meta;
  std::string docs = published_docs(m.docs);
  while (!docs.empty() && docs.front() == '\n') docs.erase(docs.begin());
  while (!docs.empty() && (docs.back() == '\n' || docs.back() == ' ')) docs.pop_back();
  std::string fix;
  switch (m.fix) {
    case FixAvailability::None: fix = "none"; break;
    case FixAvailability::Sometimes: fix = "sometimes (`--fix`; see Fix safety)"; break;
    case FixAvailability::Always: fix = "always (`--fix`; see Fix safety)"; break;
  }
  return fmt::format(
      "{banner}\n# {name} ({code})\n\n{summary}\n\n"
      "| code | name | default severity | enabled by default | fix |\n|---|---|---|---|---|\n"
      "| `{code}` | `{name}` | {sev} | {on} | {fix} |\n\n{tag}{docs}\n\n"
      "## Configuration\n"
      "Suppress one finding with a comment on its line, `; rrflint: disable={name}` (see the README, "
      "\"Suppressing findings\"). Switch the rule off with `ignore = [\"{name}\"]` in `.rrflint.toml`, "
      "{enable}, or change its severity with `[severity]` `{name} = \"error\"`. On the command line: "
      "`--ignore {code}`, `--select {code}`.\n",
      fmt::arg("banner", kBanner), fmt::arg("name", m.name), fmt::arg("code", m.code), fmt::arg("summary", m.summary),
      fmt::arg("sev", severity_name(m.severity)), fmt::arg("on", m.default_enabled ? "yes" : "no (opt-in)"),
      fmt::arg("fix", fix), fmt::arg("docs", docs), fmt::arg("tag", tag_sentence(m.tag)),
      fmt::arg("enable", m.default_enabled ? "switch it back on with `extend-select`"
                                           : "switch it on with `extend-select = [\"" + std::string(m.name) + "\"]`"));
}

std::string rule_index(const RuleSet& rules) {
  return fmt::format(
      "{}\n# Rules\n\nEvery rule has a stable code and a name; both work everywhere a rule is named (`--select`, "
      "`--ignore`, `.rrflint.toml`, suppression comments). `default` says whether the rule runs without "
      "`--select`/`extend-select`; `fix` whether `--fix` can repair its findings.\n\n{}",
      kBanner, tables(rules, "", "##"));
}

std::string readme_rule_list(const RuleSet& rules) {
  return fmt::format(
      "\n{} rules; each links to its page under `docs/rules/` (`rrflint rule CODE` prints the same).\n\n{}",
      rules.all().size(), tables(rules, "docs/rules/", "###"));
}

std::map<std::string, std::string> generated_rule_docs(const RuleSet& rules) {
  std::map<std::string, std::string> out;
  for (const Rule* r : rules.all()) out[std::string(r->meta.name) + ".md"] = rule_page(*r);
  out["README.md"] = rule_index(rules);
  return out;
}

std::optional<std::string> replace_rule_list(std::string_view readme, std::string_view list) {
  const size_t b = readme.find(kRulesBegin);
  if (b == std::string_view::npos) return std::nullopt;
  const size_t e = readme.find(kRulesEnd, b);
  if (e == std::string_view::npos) return std::nullopt;
  std::string out(readme.substr(0, b + kRulesBegin.size()));
  out += list;
  out += readme.substr(e);
  return out;
}

}  // namespace rrflint
