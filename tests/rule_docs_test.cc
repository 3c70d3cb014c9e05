// The rule docs run as tests: every ```gcode block under a rule's `## Example` heading, linted with only that rule
// enabled, must produce at least one finding of the rule, and every block under `## Use instead` none.
//
// A block is an SD card:
//   - its first line may be `; rrflint-options: --firmware 3.2 --board duet2 --tool-changer --extend-select X`
//     (the words of the fixture runner, tests/fixtures_test.cc);
//   - a line `; file: sys/tpost0.g` starts another file (an SD path from the card's root); the part before the
//     first marker is /sys/config.g;
//   - the fence ```gcode no-test opts a prose sketch out (the published docs show it as ```gcode).
// Every block must parse (as the fixtures must), except for syntax-error; every rule has at least one tested
// Example, except those in kRulesWithoutTestedExample.
#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "lint/engine/rule.h"
#include "lint/render/rule_docs.h"
#include "rules/registry.h"
#include "tests/fixture_format.h"
#include "tests/fixture_lint.h"

using namespace rrflint;
using namespace rrflint::fixture;

namespace {

/// Rules whose Example cannot be a text block: the mistake is in the file's bytes (CR-only line endings, bytes
/// that are not UTF-8, a macro saved as UTF-16). Their Examples are prose or a ```gcode no-test sketch.
const std::set<std::string> kRulesWithoutTestedExample = {"cr-line-endings", "invalid-utf8", "unreadable-macro"};

enum class Section { Example, UseInstead };

struct DocBlock {
  Section section = Section::Example;
  int index = 0;         // 1-based, per section kind
  size_t docs_line = 0;  // of the opening fence, 1-based in the docs string
  bool no_test = false;
  std::string bad_tag;  // a fence word the test does not know
  std::string text;
};

std::string_view section_name(Section s) { return s == Section::Example ? "Example" : "Use instead"; }

/// The ```gcode blocks under the Example and Use instead headings of a rule's docs.
std::vector<DocBlock> doc_blocks(std::string_view docs) {
  std::vector<DocBlock> out;
  std::optional<Section> section;
  int counts[2] = {0, 0};
  DocBlock* open = nullptr;
  bool in_other_fence = false;
  size_t n = 0;
  while (!docs.empty()) {
    const size_t nl = docs.find('\n');
    const std::string_view line = docs.substr(0, nl);
    docs = nl == std::string_view::npos ? std::string_view{} : docs.substr(nl + 1);
    ++n;
    if (open || in_other_fence) {
      if (line.starts_with("```")) {
        open = nullptr;
        in_other_fence = false;
      } else if (open) {
        open->text.append(line).append("\n");
      }
      continue;
    }
    if (line.starts_with("## ")) {
      const std::string_view title = line.substr(3);
      section = title.starts_with("Example")       ? std::optional(Section::Example)
                : title.starts_with("Use instead") ? std::optional(Section::UseInstead)
                                                   : std::nullopt;
      continue;
    }
    if (!line.starts_with("```")) continue;
    std::vector<std::string> words;
    {
      std::string_view info = line.substr(3);
      while (!info.empty()) {
        const size_t b = info.find_first_not_of(' ');
        if (b == std::string_view::npos) break;
        info.remove_prefix(b);
        const size_t e = info.find(' ');
        words.emplace_back(info.substr(0, e));
        info = e == std::string_view::npos ? std::string_view{} : info.substr(e);
      }
    }
    if (!section || words.empty() || words[0] != "gcode") {
      in_other_fence = true;
      continue;
    }
    DocBlock b;
    b.section = *section;
    b.index = ++counts[static_cast<int>(*section)];
    b.docs_line = n;
    for (size_t i = 1; i < words.size(); ++i) {
      if (words[i] == "no-test") b.no_test = true;
      else b.bad_tag = words[i];
    }
    out.push_back(std::move(b));
    open = &out.back();
  }
  return out;
}

/// A marker line `; file: sys/tpost0.g` -> "/sys/tpost0.g"; empty when the line is no marker.
std::string file_marker(std::string_view line) {
  const size_t b = line.find_first_not_of(" \t");
  if (b == std::string_view::npos || line[b] != ';') return {};
  line.remove_prefix(b + 1);
  line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size()));
  if (!line.starts_with("file:")) return {};
  line.remove_prefix(5);
  while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
  while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r')) line.remove_suffix(1);
  if (line.empty()) return {};
  return line.front() == '/' ? std::string(line) : "/" + std::string(line);
}

/// A block's files by SD path. Problems (a file named twice) go to `problems`.
std::map<std::string, std::string> block_card(const std::string& text, std::vector<std::string>& problems) {
  std::map<std::string, std::string> card;
  std::string current = "/sys/config.g", body;
  bool marked = false;
  auto flush = [&] {
    // The part before the first marker is config.g only when it holds something.
    if (!marked && body.find_first_not_of(" \t\r\n") == std::string::npos) return;
    if (card.count(current)) problems.push_back(fmt::format("{} is given twice", current));
    card[current] = body;
  };
  for (const auto& [b, e] : split_lines(text)) {
    const std::string_view line = std::string_view(text).substr(b, e - b);
    const std::string marker = file_marker(line);
    if (marker.empty()) {
      body.append(line).append("\n");
      continue;
    }
    flush();
    current = marker;
    body.clear();
    marked = true;
  }
  flush();
  return card;
}

std::string describe(const LintRun& run) {
  if (run.findings.empty()) return "(none)";
  std::string out;
  for (const Finding& f : run.findings) out += fmt::format("\n    {}:{}: {} {}", f.sd_path, f.line, f.rule, f.message);
  return out;
}

}  // namespace

TEST_CASE("docs: every Example fires its rule and every Use instead stays silent", "[docs]") {
  size_t tested = 0;
  for (const Rule* r : builtin_rules().all()) {
    const RuleMeta& m = r->meta;
    const std::string rule(m.name);
    const std::vector<DocBlock> blocks = doc_blocks(m.docs);
    size_t examples_tested = 0;
    for (const DocBlock& b : blocks) {
      const std::string where = fmt::format("{} {}: {} block {} (docs line {})", m.code, m.name,
                                            section_name(b.section), b.index, b.docs_line);
      if (!b.bad_tag.empty()) {
        FAIL_CHECK(where << ": unknown fence tag '" << b.bad_tag << "' (only `no-test` is known)");
        continue;
      }
      if (b.no_test) continue;
      std::vector<std::string> problems;
      const auto card = block_card(b.text, problems);
      CaseOptions o;
      o.lint.select = {rule};
      const std::string_view first = std::string_view(b.text).substr(0, b.text.find('\n'));
      read_options_line(first, o, where, problems);
      if (b.text.find("rrflint-options:", first.size()) != std::string::npos)
        problems.push_back("`; rrflint-options:` counts only on the block's first line");
      if (card.empty()) problems.push_back("the block is empty");
      for (const std::string& p : problems) FAIL_CHECK(where << ": " << p);
      if (!problems.empty()) continue;

      const auto run = lint_card(card, o.lint);
      const Machine& machine = *run->result.machine;
      for (uint32_t i = 0; i < machine.unit_count() && rule != "syntax-error"; ++i) {
        const FileUnit& u = machine.unit(i);
        for (const ParseError& e : u.parsed.errors)
          FAIL_CHECK(where << ": " << u.sd_path << ":" << u.source->position(e.span.begin).line
                           << ": the block does not parse: " << e.message);
      }
      size_t own = 0;
      for (const Finding& f : run->findings) own += f.rule == rule;
      ++tested;
      if (b.section == Section::Example) {
        ++examples_tested;
        if (own == 0) FAIL_CHECK(where << ": no " << rule << " finding; findings: " << describe(*run));
      } else if (own != 0) {
        FAIL_CHECK(where << ": " << own << " " << rule << " finding(s), expected none; findings: " << describe(*run));
      }
    }
    if (examples_tested == 0 && !kRulesWithoutTestedExample.count(rule))
      FAIL_CHECK(m.code << " " << m.name << ": no tested ```gcode block under ## Example");
    if (examples_tested != 0 && kRulesWithoutTestedExample.count(rule))
      FAIL_CHECK(m.code << " " << m.name << ": has a tested Example now; take it off kRulesWithoutTestedExample");
  }
  CHECK(tested > 50);
}

TEST_CASE("docs: doc blocks split into files at their file markers", "[docs]") {
  std::vector<std::string> problems;
  auto card = block_card(
      "; rrflint-options: --firmware 3.2\nM563 P0 S\"T0\"\nT0\n; file: sys/tpost0.g\nG1 X0\n"
      "; file: /macros/park.g\nG1 Y0\n",
      problems);
  CHECK(problems.empty());
  CHECK(card == std::map<std::string, std::string>{
                    {"/sys/config.g", "; rrflint-options: --firmware 3.2\nM563 P0 S\"T0\"\nT0\n"},
                    {"/sys/tpost0.g", "G1 X0\n"},
                    {"/macros/park.g", "G1 Y0\n"}});
  card = block_card("\n; file: sys/tpost0.g\nG1 X0\n", problems);
  CHECK(card == std::map<std::string, std::string>{{"/sys/tpost0.g", "G1 X0\n"}});
  card = block_card("G1 X0\n; file: sys/config.g\nG1 Y0\n", problems);
  CHECK(problems.size() == 1);
  CHECK(file_marker("G1 X0 ; file: x.g").empty());  // a marker is a line of its own
  CHECK(file_marker("  ;file: sys/tfree0.g ") == "/sys/tfree0.g");

  const auto blocks = doc_blocks(
      "## Example\n```gcode\nT0\n```\n```gcode no-test\nsketch\n```\n## Fix safety\n"
      "```gcode\nignored\n```\n## Use instead\n```gcode\nT0 P0\n```\n");
  REQUIRE(blocks.size() == 3);
  CHECK((blocks[0].text == "T0\n" && !blocks[0].no_test && blocks[0].index == 1 && blocks[0].docs_line == 2));
  CHECK((blocks[1].no_test && blocks[1].index == 2));
  CHECK((blocks[2].section == Section::UseInstead && blocks[2].text == "T0 P0\n" && blocks[2].index == 1));
}

TEST_CASE("docs: the no-test tag never reaches the published docs", "[docs]") {
  CHECK(published_docs("## Example\n```gcode no-test\nT0\n```\n") == "## Example\n```gcode\nT0\n```\n");
  CHECK(published_docs("a\n```gcode\nb\n```") == "a\n```gcode\nb\n```");
  for (const Rule* r : builtin_rules().all()) {
    INFO(r->meta.name);
    CHECK(rule_page(*r).find("no-test") == std::string::npos);
  }
}
