// The rule documentation generated from the registry: one Markdown page per rule (docs/rules/<name>.md), an
// index (docs/rules/README.md) and the rule list of the top-level README (between `<!-- rules:begin -->` and
// `<!-- rules:end -->`). `rrflint rule --generate-docs` writes them; a test fails when a checked-in copy is stale.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace rrflint {

struct Rule;
class RuleSet;

inline constexpr std::string_view kRulesBegin = "<!-- rules:begin -->";
inline constexpr std::string_view kRulesEnd = "<!-- rules:end -->";

/// A rule's docs as published (its page, `rrflint rule --format json`, SARIF help): a code fence's info string
/// is cut to its language, so the tests' own tag (```gcode no-test, tests/rule_docs_test.cc) does not show.
std::string published_docs(std::string_view docs);
/// The page of one rule (also what `rrflint rule NAME` prints).
std::string rule_page(const Rule& r);
/// docs/rules/README.md: every rule, grouped by code block, linking to the pages.
std::string rule_index(const RuleSet& rules);
/// The README's rule list (the text between the markers, markers excluded).
std::string readme_rule_list(const RuleSet& rules);
/// Every generated file of docs/rules, by file name.
std::map<std::string, std::string> generated_rule_docs(const RuleSet& rules);
/// `readme` with the text between the markers replaced by `list`; nullopt when the markers are missing.
std::optional<std::string> replace_rule_list(std::string_view readme, std::string_view list);

}  // namespace rrflint
