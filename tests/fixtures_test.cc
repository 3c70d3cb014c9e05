// The fixture runner: every fixtures/<rule-name>/ case is linted with only that rule enabled, and its findings
// must match the `; expect:` comments exactly (rule name, start line and, when given, column; both ways); its
// `.fixed.g` files must match the text after the rule's fixes; and fixtures/<rule-name>/snapshot.txt must match
// the text rendering of the rule's findings on every case (RRFLINT_UPDATE_SNAPSHOTS=1 rewrites it).
// The format is documented in docs/fixtures.md; reading it is tests/fixture_format.h, linting a case in memory
// tests/fixture_lint.h.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "cli/cli.h"
#include "lint/engine/linter.h"
#include "rules/registry.h"
#include "tests/fixture_format.h"
#include "tests/fixture_lint.h"

namespace fs = std::filesystem;
using namespace rrflint;
using namespace rrflint::fixture;

namespace {

/// Rules that have no fixtures yet because they are not implemented. Keep it empty when possible.
const std::set<std::string> kRulesWithoutFixtures = {};

const fs::path kFixtureRoot = fixture_root();

std::string display(const FixtureCase& c, const std::string& sd_path) {
  for (const CardFile& f : c.files)
    if (f.sd_path == sd_path) return rel(f.disk);
  return rel(c.path) + ":" + sd_path;
}

/// Does the finding match the expectation in everything but its column?
bool matches_but_column(const Expectation& x, const Finding& f) {
  return x.sd_path == f.sd_path && x.line == f.line && x.item.rule == f.rule &&
         (x.item.substring.empty() || f.message.find(x.item.substring) != std::string::npos);
}

bool matches(const Expectation& x, const Finding& f) {
  return matches_but_column(x, f) && (!x.item.column || *x.item.column == f.column);
}

/// `rule-name@5 "part"` as it was written.
std::string spelled(const ExpectItem& x) {
  return x.rule + (x.column ? "@" + std::to_string(*x.column) : "") +
         (x.substring.empty() ? "" : " \"" + x.substring + "\"");
}

/// One round of the rule's fixes applied to `texts` (by SD path) as `rrflint check --fix` applies them
/// (cli::apply_fixes: whole fixes in order, none overlapping one taken before it, the file's line endings). The
/// card was linted with its expectation comments blanked, which keeps every offset, so the edits apply to the text
/// with the comments. Returns whether a text changed.
bool apply_rule_fixes(const LintRun& run, const std::string& rule, bool unsafe,
                      std::map<std::string, std::string>& texts) {
  std::vector<Diagnostic> mine;
  for (const Finding& f : run.findings)
    if (f.rule == rule && f.diag->fix) mine.push_back(*f.diag);
  std::map<FileId, std::string> by_id;
  for (FileId id = 0; id < run.sources.size(); ++id)
    if (auto it = texts.find(run.sources.get(id).sd_path()); it != texts.end()) by_id.emplace(id, it->second);
  cli::FixOptions fo;
  fo.unsafe = unsafe;
  cli::apply_fixes(
      run.sources, mine, fo, [&](FileId id) { return by_id.count(id) > 0; }, by_id);
  bool changed = false;
  for (const auto& [id, text] : by_id) {
    std::string& t = texts[run.sources.get(id).sd_path()];
    changed = changed || t != text;
    t = text;
  }
  return changed;
}

std::map<std::string, std::string> blanked_card(const std::map<std::string, std::string>& texts, const FixtureCase& c) {
  std::map<std::string, std::string> out;
  for (const auto& [sd, text] : texts) out[sd] = read_expectations(text, sd, rel(c.path)).blanked;
  return out;
}

/// Shows where two texts first differ (the whole file comparison of a .fixed.g).
std::string first_difference(const std::string& want, const std::string& got) {
  const auto wl = split_lines(want), gl = split_lines(got);
  for (size_t n = 0; n < std::max(wl.size(), gl.size()); ++n) {
    std::string_view w =
        n < wl.size() ? std::string_view(want).substr(wl[n].first, wl[n].second - wl[n].first) : "<eof>";
    std::string_view g =
        n < gl.size() ? std::string_view(got).substr(gl[n].first, gl[n].second - gl[n].first) : "<eof>";
    if (w != g) return fmt::format("line {}: expected '{}', got '{}'", n + 1, w, g);
  }
  return "the line endings differ";
}

void check_fixes(FixtureCase& c, const CaseOptions& opts) {
  std::map<std::string, std::string> texts;
  for (const CardFile& f : c.files) texts[f.sd_path] = f.original;
  for (const auto& [sd, fixed] : c.fixed)
    if (!texts.count(sd)) FAIL_CHECK(rel(fixed) << ": no " << sd << " in the card to compare it with");

  size_t initial_findings = 0, initially_fixable = 0;
  int round = 0;
  for (; round < 10; ++round) {
    auto run = lint_card(blanked_card(texts, c), opts.lint);
    if (round == 0) {
      for (const Finding& f : run->findings) {
        if (f.rule != c.rule) continue;
        ++initial_findings;
        if (f.diag->fix && (f.diag->fix->applicability == Applicability::Safe || opts.unsafe_fixes))
          ++initially_fixable;
      }
    }
    if (!apply_rule_fixes(*run, c.rule, opts.unsafe_fixes, texts)) break;
  }
  if (round == 10) FAIL_CHECK(c.name << ": the fixes did not converge in 10 rounds");

  for (const auto& [sd, fixed] : c.fixed) {
    auto it = texts.find(sd);
    if (it == texts.end()) continue;
    const std::string want = read_bytes(fixed);
    if (it->second != want)
      FAIL_CHECK(rel(fixed) << ": the fixed text differs: " << first_difference(want, it->second));
  }

  // The fixed card must re-lint without the findings the fixes addressed.
  auto after = lint_card(blanked_card(texts, c), opts.lint);
  size_t remaining = 0;
  for (const Finding& f : after->findings) {
    if (f.rule != c.rule) continue;
    ++remaining;
    if (f.diag->fix && (f.diag->fix->applicability == Applicability::Safe || opts.unsafe_fixes))
      FAIL_CHECK(display(c, f.sd_path) << ":" << f.line << ": still reported after fixing: " << f.message);
  }
  if (remaining + initially_fixable > initial_findings)
    FAIL_CHECK(c.name << ": " << initially_fixable << " of " << initial_findings
                      << " findings had fixes, but the fixed card still has " << remaining);
}

void run_case(FixtureCase& c) {
  std::vector<std::string> errors;
  const std::vector<Expectation> expected = read_case_expectations(c, errors);
  CaseOptions opts = read_options(c, errors);
  for (const std::string& e : errors) FAIL_CHECK(e);
  for (const Expectation& x : expected)
    if (x.item.rule != c.rule)
      FAIL_CHECK(display(c, x.sd_path) << ":" << x.line << ": expects '" << x.item.rule
                                       << "', but only the rule under test ('" << c.rule << "') runs here");
  if (std::none_of(c.files.begin(), c.files.end(), [](const CardFile& f) { return f.sd_path == "/sys/config.g"; }))
    FAIL_CHECK(c.name << ": the card has no sys/config.g");

  std::map<std::string, std::string> card;
  for (const CardFile& f : c.files) card[f.sd_path] = f.blanked;
  auto run = lint_card(card, opts.lint);
  {
    // The rule's `on` list must name every command it reports on: calling it on every node changes nothing.
    LintOptions every = opts.lint;
    every.dispatch_every_node = true;
    auto all_nodes = lint_card(card, every);
    const std::vector<std::string> a = finding_lines(*run), b = finding_lines(*all_nodes);
    for (const std::string& x : b)
      if (std::find(a.begin(), a.end(), x) == a.end())
        FAIL_CHECK(c.name << ": found only when every node is checked (add the command to the rule's `on`): " << x);
    for (const std::string& x : a)
      if (std::find(b.begin(), b.end(), x) == b.end())
        FAIL_CHECK(c.name << ": found only with the rule's `on` list: " << x);
  }
  {
    // Threads change nothing: files parsed in parts of a few bytes, file rules beside the forward pass.
    LintOptions split = opts.lint;
    split.threads = 3;
    split.part_bytes = 16;
    auto threaded = lint_card(card, split);
    CHECK(finding_lines(*threaded) == finding_lines(*run));
  }
  {
    // The prefilters only skip work (ParsedFile::Prefilters): with every line set holding every line and every
    // flag true, the rule and the suppression pass find the same.
    LintOptions unfiltered = opts.lint;
    unfiltered.no_prefilters = true;
    auto all_lines = lint_card(card, unfiltered);
    std::vector<std::string> a, b;
    for (const Finding& f : run->findings) a.push_back(f.sd_path + ":" + std::to_string(f.line) + ": " + f.message);
    for (const Finding& f : all_lines->findings)
      b.push_back(f.sd_path + ":" + std::to_string(f.line) + ": " + f.message);
    for (const std::string& x : b)
      if (std::find(a.begin(), a.end(), x) == a.end())
        FAIL_CHECK(c.name << ": found only with the prefilters off (a prefilter hides this finding): " << x);
    for (const std::string& x : a)
      if (std::find(b.begin(), b.end(), x) == b.end())
        FAIL_CHECK(c.name << ": found only with the prefilters on (the rule relies on a prefilter's precision): " << x);
    CHECK(b == a);
  }

  if (c.rule != "syntax-error") {
    const Machine& m = *run->result.machine;
    for (uint32_t i = 0; i < m.unit_count(); ++i) {
      const FileUnit& u = m.unit(i);
      for (const ParseError& e : u.parsed.errors)
        FAIL_CHECK(display(c, u.sd_path) << ":" << u.source->position(e.span.begin).line
                                         << ": the fixture does not parse: " << e.message);
    }
  }

  // A finding that an expectation names but for its column is reported once, as the column mismatch.
  std::vector<bool> explained(run->findings.size(), false);
  for (const Expectation& x : expected) {
    if (x.item.rule != c.rule) continue;
    if (std::any_of(run->findings.begin(), run->findings.end(), [&](const Finding& f) { return matches(x, f); }))
      continue;
    std::string got;
    for (size_t i = 0; i < run->findings.size(); ++i) {
      if (!matches_but_column(x, run->findings[i])) continue;
      got += (got.empty() ? "" : ", ") + std::to_string(run->findings[i].column);
      explained[i] = true;
    }
    if (!got.empty()) {
      FAIL_CHECK(display(c, x.sd_path) << ":" << x.line << ": " << spelled(x.item) << ": expected column "
                                       << *x.item.column << ", got " << got);
      continue;
    }
    std::string also;
    for (const Finding& f : run->findings)
      if (f.sd_path == x.sd_path && f.line == x.line)
        also += fmt::format("\n    reported instead at column {}: {}", f.column, f.message);
    FAIL_CHECK(display(c, x.sd_path) << ":" << x.line << ": missing " << x.item.rule << " finding"
                                     << (x.item.column ? " at column " + std::to_string(*x.item.column) : "")
                                     << (x.item.substring.empty() ? "" : " with \"" + x.item.substring + "\"") << also);
  }
  for (size_t i = 0; i < run->findings.size(); ++i) {
    const Finding& f = run->findings[i];
    if (explained[i] ||
        std::any_of(expected.begin(), expected.end(), [&](const Expectation& x) { return matches(x, f); }))
      continue;
    FAIL_CHECK(display(c, f.sd_path) << ":" << f.line << ":" << f.column << ": unexpected " << f.rule << ": "
                                     << f.message);
  }
  // A fix from a rule whose metadata says it has none (the README's "fix" column and the docs say so too).
  for (const Finding& f : run->findings) {
    const Rule* r = builtin_rules().find(f.rule);
    if (f.diag && f.diag->fix && r && r->meta.fix == FixAvailability::None)
      FAIL_CHECK(display(c, f.sd_path) << ":" << f.line << ": " << f.rule << " offers a fix, but its RuleMeta says "
                                       << "FixAvailability::None");
  }

  if (!c.fixed.empty()) check_fixes(c, opts);
}

bool has_expectations(FixtureCase& c) {
  std::vector<std::string> errors;
  return !read_case_expectations(c, errors).empty();
}

/// Removes the blanks at the end of every line (the blanked expectation comments leave runs of them).
std::string trim_line_ends(std::string_view s) {
  std::string out;
  size_t b = 0;
  while (b < s.size()) {
    size_t e = s.find('\n', b);
    const bool nl = e != std::string_view::npos;
    if (!nl) e = s.size();
    std::string_view line = s.substr(b, e - b);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    out += line;
    if (nl) out += '\n';
    b = e + 1;
  }
  return out;
}

/// What fixtures/<rule-name>/snapshot.txt must hold: a `## <case>` header and the text report of each case.
std::string render_snapshot(const fs::path& dir) {
  const std::string rule = dir.filename().string();
  std::string out = fmt::format(
      "# The text rendering (rrflint check, no colour) of {}'s findings on each fixture case; docs/fixtures.md.\n"
      "# Regenerate: RRFLINT_UPDATE_SNAPSHOTS=1 ctest --test-dir build -R snapshots\n",
      rule);
  for (FixtureCase& c : discover_cases(dir)) {
    std::vector<std::string> errors;  // reported by the fixture test of the case
    read_case_expectations(c, errors);
    const CaseOptions opts = read_options(c, errors);
    std::map<std::string, std::string> card;
    for (const CardFile& f : c.files) card[f.sd_path] = f.blanked;
    auto run = lint_card(card, opts.lint);
    out += "\n## " + c.label + "\n" + trim_line_ends(render_text_report(*run, opts.unsafe_fixes));
  }
  return out;
}

bool updating_snapshots() {
  const char* v = std::getenv("RRFLINT_UPDATE_SNAPSHOTS");
  return v && *v && std::string_view(v) != "0";
}

/// The first lines of a unified diff, for a failure message.
std::string diff_excerpt(const std::string& want, const std::string& got, const fs::path& path) {
  const std::string diff = cli::unified_diff(want, got, rel(path));
  constexpr size_t kMaxLines = 60;
  std::string out;
  size_t lines = 0, b = 0;
  for (; b < diff.size() && lines < kMaxLines; ++lines) {
    size_t e = diff.find('\n', b);
    if (e == std::string::npos) e = diff.size() - 1;
    out.append(diff, b, e - b + 1);
    b = e + 1;
  }
  if (b < diff.size())
    out += fmt::format("… ({} more lines)\n", std::count(diff.begin() + static_cast<ptrdiff_t>(b), diff.end(), '\n'));
  return out;
}

}  // namespace

TEST_CASE("fixtures match the findings of their rule", "[fixtures]") {
  const auto dirs = fixture_dirs();
  REQUIRE_FALSE(dirs.empty());
  for (const fs::path& dir : dirs) {
    const std::string rule = dir.filename().string();
    const Rule* r = builtin_rules().find(rule);
    if (!r || r->meta.name != rule) {
      DYNAMIC_SECTION(rule) { FAIL(rel(dir) << ": '" << rule << "' is not the name of a rule"); }
      continue;
    }
    for (FixtureCase& c : discover_cases(dir)) {
      DYNAMIC_SECTION(c.name) { run_case(c); }
    }
  }
}

TEST_CASE("fixture snapshots match the text rendering", "[fixtures][snapshots]") {
  // RRFLINT_UPDATE_SNAPSHOTS=1 rewrites every snapshot that differs (or is missing) instead of failing.
  const auto dirs = fixture_dirs();
  REQUIRE_FALSE(dirs.empty());
  const bool update = updating_snapshots();
  for (const fs::path& dir : dirs) {
    const Rule* r = builtin_rules().find(dir.filename().string());
    if (!r || r->meta.name != dir.filename().string()) continue;  // reported by the fixture test
    DYNAMIC_SECTION(dir.filename().string()) {
      const fs::path path = snapshot_path(dir);
      const std::string got = render_snapshot(dir);
      const bool exists = fs::exists(path);
      const std::string want = exists ? read_bytes(path) : std::string();
      if (got == want) continue;
      if (update) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out << got;
        out.close();
        if (!out) FAIL_CHECK(rel(path) << ": could not be written");
        else WARN(rel(path) << (exists ? ": updated" : ": created"));
        continue;
      }
      if (!exists)
        FAIL_CHECK(rel(path) << ": missing; create it with RRFLINT_UPDATE_SNAPSHOTS=1 ctest --test-dir build -R "
                                "snapshots, and read it before committing it");
      if (!exists) continue;
      // The diff goes to stderr as it is: Catch wraps its messages at 80 columns, which mangles a diff.
      std::cout.flush();
      std::cerr << rel(path) << ": the text rendering differs from the snapshot (- snapshot, + now):\n"
                << diff_excerpt(want, got, path) << std::flush;
      FAIL_CHECK(rel(path) << ": the text rendering of the rule's findings differs from the snapshot (the diff is "
                              "on stderr). If the change is intended, regenerate the snapshots with "
                              "RRFLINT_UPDATE_SNAPSHOTS=1 ctest --test-dir build -R snapshots (or "
                              "RRFLINT_UPDATE_SNAPSHOTS=1 build/rrflint_tests '[snapshots]') and review git diff "
                              "fixtures/");
    }
  }
}

TEST_CASE("every node rule has a well-formed `on` list", "[fixtures]") {
  for (const Rule* r : builtin_rules().all()) {
    Triggers t;
    std::string bad;
    const bool ok = parse_triggers(r->on, t, &bad);
    INFO(r->meta.code << " " << r->meta.name);
    CHECK(ok);
    if (!ok) INFO("bad token: " << bad);
    // A node rule that names no command would never run; `on` without check_node means nothing.
    CHECK((r->check_node != nullptr) == (!t.codes.empty() || t.any_t));
  }
  Triggers t;
  CHECK(parse_triggers(" G10  M563 T ", t));
  CHECK(t.codes == std::vector<std::pair<char, int>>{{'G', 10}, {'M', 563}});
  CHECK(t.any_t);
  std::string bad;
  CHECK_FALSE(parse_triggers("G10 X5", t, &bad));
  CHECK(bad == "X5");
  CHECK_FALSE(parse_triggers("M", t));
}

TEST_CASE("a file rule that reads the machine is marked whole_card", "[fixtures]") {
  // A large machine runs the other file rules while the graph is built and may still load files (lint_machine):
  // a check_file that reads FileContext::machine must wait for the graph (Rule::whole_card). Read from the
  // sources: the rule file, and the rules' shared headers it includes.
  const std::filesystem::path dir = std::filesystem::path(RRFLINT_SOURCE_DIR) / "rules";
  auto read = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  size_t file_rules = 0, marked = 0;
  for (const Rule* r : builtin_rules().all()) {
    if (!r->check_file) continue;
    ++file_rules;
    marked += r->whole_card;
    std::string file(r->meta.name);
    std::replace(file.begin(), file.end(), '-', '_');
    std::replace(file.begin(), file.end(), '.', '_');
    const std::string text = read(dir / (file + ".cc"));
    INFO(r->meta.name);
    REQUIRE_FALSE(text.empty());
    // The check itself names the machine, or hands its FileContext to a shared helper that does.
    bool reads = text.find("machine.") != std::string::npos;
    for (const char* h : {"lex_common.h", "tool_helpers.h", "macro_common.h"})
      if (text.find(h) != std::string::npos) {
        const std::string header = read(dir / h);
        for (size_t at = header.find("FileContext& cx"); at != std::string::npos;
             at = header.find("FileContext& cx", at + 1))
          reads = reads || header.find("cx.machine", at) < header.find("\n}", at);
      }
    CHECK(reads == r->whole_card);
  }
  CHECK(file_rules > 20);
  CHECK(marked == 3);
}

TEST_CASE("every rule has fixtures with two positive and two negative cases", "[fixtures]") {
  for (const Rule* r : builtin_rules().all()) {
    const std::string name(r->meta.name);
    if (kRulesWithoutFixtures.count(name)) continue;
    const fs::path dir = kFixtureRoot / name;
    INFO("rule " << r->meta.code << " " << name);
    if (!fs::is_directory(dir)) {
      FAIL_CHECK("no fixture directory fixtures/" << name << "/");
      continue;
    }
    int positive = 0, negative = 0;
    for (FixtureCase& c : discover_cases(dir)) (has_expectations(c) ? positive : negative) += 1;
    CHECK(positive >= 2);
    CHECK(negative >= 2);
  }
  for (const std::string& name : kRulesWithoutFixtures) {
    INFO("allowlisted rule " << name);
    CHECK(builtin_rules().find(name) != nullptr);
  }
}
