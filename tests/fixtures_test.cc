// The fixture runner: every fixtures/<rule-name>/ case is linted with only that rule enabled, and its findings
// must match the `; expect:` comments exactly (rule name and start line, both ways).
//
//   fixtures/<rule-name>/<case>.g        a one-file SD card: the file is /sys/config.g
//   fixtures/<rule-name>/<case>/         a whole SD card (sys/config.g, macros/x.g, …)
//   <case>.fixed.g, X.fixed.g beside X.g  the expected text after applying the rule's fixes
//
// Expectations: `; expect: a, b "message part"` at the end of a code line, or on a line of its own where it
// applies to the next line that is not itself an expect line. Line 1 (of the file, or of sys/config.g) may be
// `; rrflint-options: --firmware 3.3 --board duet2 --tool-changer --unsafe-fixes`. The expectation text is
// blanked to spaces before linting (the ';' stays), so every offset and line number is unchanged.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "lint/engine/linter.h"
#include "rules/registry.h"
#include "rules/registry.h"

namespace fs = std::filesystem;
using namespace rrflint;

namespace {

/// Rules that have no fixtures yet because they are not implemented. Keep it empty when possible.
const std::set<std::string> kRulesWithoutFixtures = {};

const fs::path kFixtureRoot = fs::path(RRFLINT_SOURCE_DIR) / "fixtures";

struct Expectation {
  std::string sd_path;
  uint32_t line = 0;  // 1-based
  std::string rule;
  std::string substring;  // empty: any message
};

struct CardFile {
  std::string sd_path;
  fs::path disk;         // where the fixture file lives, for messages
  std::string original;  // with the expectation comments
  std::string blanked;   // expectation text replaced by spaces
};

struct FixtureCase {
  std::string rule;  // the rule under test (directory name)
  std::string name;  // "<rule>/<case>"
  fs::path path;     // the .g file or the folder
  std::vector<CardFile> files;
  std::map<std::string, fs::path> fixed;  // sd_path -> its .fixed.g file
};

struct CaseOptions {
  LintOptions lint;
  bool unsafe_fixes = false;
};

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string rel(const fs::path& p) { return fs::relative(p, fs::path(RRFLINT_SOURCE_DIR)).generic_string(); }

bool is_fixed_file(const fs::path& p) { return p.filename().string().ends_with(".fixed.g"); }

/// Lines as rrflint counts them (LF, CRLF and lone CR), as [begin, end) offsets without the terminator.
std::vector<std::pair<size_t, size_t>> split_lines(std::string_view t) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t b = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] != '\n' && t[i] != '\r') continue;
    out.emplace_back(b, i);
    if (t[i] == '\r' && i + 1 < t.size() && t[i + 1] == '\n') ++i;
    b = i + 1;
  }
  if (b < t.size() || out.empty()) out.emplace_back(b, t.size());
  return out;
}

/// Finds `; expect:` (blanks allowed after ';') in a line. Returns the offset of the ';' or npos.
size_t find_expect(std::string_view line) {
  for (size_t k = line.find(';'); k != std::string_view::npos; k = line.find(';', k + 1)) {
    size_t q = k + 1;
    while (q < line.size() && (line[q] == ' ' || line[q] == '\t')) ++q;
    if (line.substr(q).starts_with("expect:")) return k;
  }
  return std::string_view::npos;
}

/// Parses `name, name "text", …` after `expect:`. Returns false with `err` set when malformed.
bool parse_expect_list(std::string_view s, std::vector<std::pair<std::string, std::string>>& out, std::string& err) {
  size_t i = 0;
  auto blanks = [&] {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  };
  for (;;) {
    blanks();
    size_t b = i;
    // Rule names are kebab-case and may hold a version with dots (`m568-before-3.3`).
    while (i < s.size() && ((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= '0' && s[i] <= '9') || s[i] == '-' ||
                            (s[i] == '.' && i > b && i + 1 < s.size() && s[i + 1] >= '0' && s[i + 1] <= '9')))
      ++i;
    if (i == b) {
      err = "expected a rule name";
      return false;
    }
    std::string name(s.substr(b, i - b));
    std::string text;
    blanks();
    if (i < s.size() && s[i] == '"') {
      size_t close = s.find('"', i + 1);
      if (close == std::string_view::npos) {
        err = "unterminated message substring";
        return false;
      }
      text = std::string(s.substr(i + 1, close - i - 1));
      i = close + 1;
      blanks();
    }
    out.emplace_back(std::move(name), std::move(text));
    if (i >= s.size()) return true;
    if (s[i] != ',') {
      err = "expected ',' between expectations";
      return false;
    }
    ++i;
  }
}

/// Collects the expectations of one file and blanks their text. Problems go to `errors`.
void read_expectations(CardFile& f, std::vector<Expectation>& out, std::vector<std::string>& errors) {
  f.blanked = f.original;
  const auto lines = split_lines(f.original);
  std::vector<size_t> pending;  // own-line expectations waiting for their line (indices into out)
  for (size_t n = 0; n < lines.size(); ++n) {
    const auto [b, e] = lines[n];
    std::string_view line = std::string_view(f.original).substr(b, e - b);
    const size_t semi = find_expect(line);
    if (semi == std::string_view::npos) {
      for (size_t k : pending) out[k].line = static_cast<uint32_t>(n + 1);
      pending.clear();
      continue;
    }
    const bool own_line = line.substr(0, semi).find_first_not_of(" \t") == std::string_view::npos;
    std::string_view list = line.substr(line.find("expect:", semi) + 7);
    std::vector<std::pair<std::string, std::string>> items;
    std::string err;
    if (!parse_expect_list(list, items, err))
      errors.push_back(fmt::format("{}:{}: malformed expectation: {}", rel(f.disk), n + 1, err));
    for (auto& [rule, text] : items) {
      out.push_back(Expectation{f.sd_path, static_cast<uint32_t>(n + 1), rule, text});
      if (own_line) pending.push_back(out.size() - 1);
    }
    std::fill(f.blanked.begin() + static_cast<ptrdiff_t>(b + semi + 1), f.blanked.begin() + static_cast<ptrdiff_t>(e),
              ' ');
  }
  if (!pending.empty())
    errors.push_back(fmt::format("{}: an own-line expectation at the end of the file has no line to apply to",
                                 rel(f.disk)));
}

/// Reads `; rrflint-options:` from line 1 of config.g.
CaseOptions read_options(const FixtureCase& c, const std::string& rule, std::vector<std::string>& errors) {
  CaseOptions o;
  o.lint.select = {rule};
  const CardFile* config = nullptr;
  for (const CardFile& f : c.files)
    if (f.sd_path == "/sys/config.g") config = &f;
  if (!config) return o;
  std::string_view text = config->original;
  std::string_view first = text.substr(0, split_lines(text).front().second);
  const size_t at = first.find("rrflint-options:");
  if (at == std::string_view::npos || first.substr(0, at).find(';') == std::string_view::npos) return o;
  std::string_view rest = first.substr(at + 16);
  rest = rest.substr(0, rest.find(';'));  // an expectation may follow on the same line
  std::istringstream words{std::string(rest)};
  std::string w;
  while (words >> w) {
    std::string arg;
    if (w == "--tool-changer") {
      o.lint.tool_changer = true;
    } else if (w == "--unsafe-fixes") {
      o.unsafe_fixes = true;
    } else if (w == "--extend-select" && words >> arg) {
      o.lint.extend_select.push_back(arg);  // another rule on as well (RRF900 needs a rule to suppress)
    } else if (w == "--firmware" && words >> arg) {
      if (auto v = Version::parse(arg)) o.lint.firmware = *v;
      else errors.push_back(fmt::format("{}:1: bad --firmware '{}'", rel(config->disk), arg));
    } else if (w == "--board" && words >> arg) {
      if (auto b = parse_board(arg)) o.lint.board = *b;
      else errors.push_back(fmt::format("{}:1: bad --board '{}'", rel(config->disk), arg));
    } else {
      errors.push_back(fmt::format("{}:1: unknown rrflint-options word '{}'", rel(config->disk), w));
    }
  }
  return o;
}

/// Every case of one fixture directory, sorted by name.
std::vector<FixtureCase> discover_cases(const fs::path& dir) {
  std::vector<FixtureCase> cases;
  const std::string rule = dir.filename().string();
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(dir)) entries.push_back(e.path());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& p : entries) {
    FixtureCase c;
    c.rule = rule;
    c.path = p;
    if (fs::is_directory(p)) {
      c.name = rule + "/" + p.filename().string();
      std::vector<fs::path> files;
      for (const auto& e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const fs::path& f : files) {
        const std::string sd = "/" + fs::relative(f, p).generic_string();
        if (is_fixed_file(f)) {
          c.fixed[sd.substr(0, sd.size() - 8) + ".g"] = f;  // "X.fixed.g" -> "X.g"
          continue;
        }
        c.files.push_back(CardFile{sd, f, read_bytes(f), {}});
      }
    } else if (p.extension() == ".g" && !is_fixed_file(p)) {
      c.name = rule + "/" + p.filename().string();
      c.files.push_back(CardFile{"/sys/config.g", p, read_bytes(p), {}});
      fs::path fixed = p;
      fixed.replace_extension(".fixed.g");
      if (fs::exists(fixed)) c.fixed["/sys/config.g"] = fixed;
    } else {
      continue;
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

std::vector<fs::path> fixture_dirs() {
  std::vector<fs::path> dirs;
  if (!fs::is_directory(kFixtureRoot)) return dirs;
  for (const auto& e : fs::directory_iterator(kFixtureRoot))
    if (e.is_directory()) dirs.push_back(e.path());
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

/// A finding reduced to what the fixtures compare.
struct Finding {
  std::string sd_path;
  uint32_t line = 0;
  std::string rule;
  std::string message;
  const Diagnostic* diag = nullptr;
};

struct LintRun {
  SourceManager sources;
  MachineResult result;
  std::vector<Finding> findings;
};

/// Lints a card given as sd_path -> text.
std::unique_ptr<LintRun> lint_card(const std::map<std::string, std::string>& card, const LintOptions& options) {
  auto run = std::make_unique<LintRun>();
  MemoryReader reader;
  for (const auto& [sd, text] : card) reader.add(sd, text);
  run->result = lint_machine(run->sources, reader, builtin_rules(), options);
  for (const Diagnostic& d : run->result.diagnostics) {
    Finding f;
    f.rule = std::string(d.name);
    f.message = d.message;
    f.diag = &d;
    if (d.loc.file != kNoFile && d.loc.file < run->sources.size()) {
      const SourceFile& src = run->sources.get(d.loc.file);
      f.sd_path = src.sd_path();
      f.line = src.position(d.loc.span.begin).line;
    }
    run->findings.push_back(std::move(f));
  }
  return run;
}

std::string display(const FixtureCase& c, const std::string& sd_path) {
  for (const CardFile& f : c.files)
    if (f.sd_path == sd_path) return rel(f.disk);
  return rel(c.path) + ":" + sd_path;
}

bool matches(const Expectation& x, const Finding& f) {
  return x.sd_path == f.sd_path && x.line == f.line && x.rule == f.rule &&
         (x.substring.empty() || f.message.find(x.substring) != std::string::npos);
}

/// The fixes of `rule` in a lint run, by sd_path, at the allowed applicability.
std::map<std::string, std::vector<Edit>> applicable_edits(const LintRun& run, const std::string& rule, bool unsafe) {
  std::map<std::string, std::vector<Edit>> edits;
  for (const Finding& f : run.findings) {
    const Diagnostic& d = *f.diag;
    if (f.rule != rule || !d.fix) continue;
    if (d.fix->applicability == Applicability::Unsafe && !unsafe) continue;
    for (const Edit& e : d.fix->edits) {
      if (e.loc.file == kNoFile || e.loc.file >= run.sources.size()) continue;
      edits[run.sources.get(e.loc.file).sd_path()].push_back(e);
    }
  }
  return edits;
}

std::map<std::string, std::string> blanked_card(const std::map<std::string, std::string>& texts, FixtureCase& c) {
  std::map<std::string, std::string> out;
  for (const auto& [sd, text] : texts) {
    CardFile f{sd, c.path, text, {}};
    std::vector<Expectation> ignored;
    std::vector<std::string> errors;
    read_expectations(f, ignored, errors);
    out[sd] = f.blanked;
  }
  return out;
}

/// Shows where two texts first differ (the whole file comparison of a .fixed.g).
std::string first_difference(const std::string& want, const std::string& got) {
  const auto wl = split_lines(want), gl = split_lines(got);
  for (size_t n = 0; n < std::max(wl.size(), gl.size()); ++n) {
    std::string_view w = n < wl.size() ? std::string_view(want).substr(wl[n].first, wl[n].second - wl[n].first) : "<eof>";
    std::string_view g = n < gl.size() ? std::string_view(got).substr(gl[n].first, gl[n].second - gl[n].first) : "<eof>";
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
    auto edits = applicable_edits(*run, c.rule, opts.unsafe_fixes);
    bool changed = false;
    for (auto& [sd, list] : edits) {
      auto it = texts.find(sd);
      if (it == texts.end()) continue;
      std::string before = it->second;
      apply_edits(it->second, list);
      changed = changed || before != it->second;
    }
    if (!changed) break;
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
  std::vector<Expectation> expected;
  for (CardFile& f : c.files) read_expectations(f, expected, errors);
  CaseOptions opts = read_options(c, c.rule, errors);
  for (const std::string& e : errors) FAIL_CHECK(e);
  for (const Expectation& x : expected)
    if (x.rule != c.rule)
      FAIL_CHECK(display(c, x.sd_path) << ":" << x.line << ": expects '" << x.rule
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
    std::vector<std::string> a, b;
    for (const Finding& f : run->findings) a.push_back(f.sd_path + ":" + std::to_string(f.line) + ": " + f.message);
    for (const Finding& f : all_nodes->findings)
      b.push_back(f.sd_path + ":" + std::to_string(f.line) + ": " + f.message);
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
    auto list = [](const auto& findings) {
      std::vector<std::string> out;
      for (const Finding& f : findings) out.push_back(f.sd_path + ":" + std::to_string(f.line) + ": " + f.message);
      return out;
    };
    CHECK(list(threaded->findings) == list(run->findings));
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

  for (const Expectation& x : expected) {
    if (x.rule != c.rule) continue;
    if (std::none_of(run->findings.begin(), run->findings.end(), [&](const Finding& f) { return matches(x, f); })) {
      std::string also;
      for (const Finding& f : run->findings)
        if (f.sd_path == x.sd_path && f.line == x.line) also += "\n    reported instead: " + f.message;
      FAIL_CHECK(display(c, x.sd_path) << ":" << x.line << ": missing " << x.rule << " finding"
                                       << (x.substring.empty() ? "" : " with \"" + x.substring + "\"") << also);
    }
  }
  for (const Finding& f : run->findings) {
    if (std::none_of(expected.begin(), expected.end(), [&](const Expectation& x) { return matches(x, f); }))
      FAIL_CHECK(display(c, f.sd_path) << ":" << f.line << ": unexpected " << f.rule << ": " << f.message);
  }

  if (!c.fixed.empty()) check_fixes(c, opts);
}

bool has_expectations(FixtureCase& c) {
  std::vector<Expectation> expected;
  std::vector<std::string> errors;
  for (CardFile& f : c.files) read_expectations(f, expected, errors);
  return !expected.empty();
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
    for (const char* h : {"lex_common.h", "g10_common.h", "tool_common.h", "macro_common.h"})
      if (text.find(h) != std::string::npos) {
        const std::string header = read(dir / h);
        for (size_t at = header.find("FileContext& cx"); at != std::string::npos; at = header.find("FileContext& cx", at + 1))
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
