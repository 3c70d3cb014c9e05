// Suppression comments (lint/engine/suppress.cc): scopes, names, reasons, RRF900/RRF901 and their fixes,
// --no-inline-suppressions, per-file ignores, and the edits of --add-suppressions.
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include "lint/engine/linter.h"
#include "lint/engine/suppress.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

struct Run {
  SourceManager sm;
  MemoryReader reader;
  MachineResult result;
  /// "file:line CODE" for every finding, in order.
  std::vector<std::string> found() const {
    std::vector<std::string> out;
    for (const Diagnostic& d : result.diagnostics) {
      const SourceFile& f = sm.get(d.loc.file);
      out.push_back(fmt::format("{}:{} {}", f.sd_path(), f.line_of(d.loc.span.begin) + 1, d.code));
    }
    return out;
  }
  const Diagnostic& only(std::string_view code) const {
    const Diagnostic* hit = nullptr;
    for (const Diagnostic& d : result.diagnostics)
      if (d.code == code) {
        REQUIRE(hit == nullptr);
        hit = &d;
      }
    REQUIRE(hit != nullptr);
    return *hit;
  }
  /// The text of `sd_path` after applying every fix of `code` once.
  std::string fixed(std::string_view sd_path, std::string_view code) const {
    for (uint32_t i = 0; i < result.machine->unit_count(); ++i) {
      const FileUnit& u = result.machine->unit(i);
      if (u.sd_path != sd_path) continue;
      std::vector<Edit> edits;
      for (const Diagnostic& d : result.diagnostics)
        if (d.code == code && d.fix)
          for (const Edit& e : d.fix->edits)
            if (e.loc.file == u.source->id()) edits.push_back(e);
      std::string text(u.source->text());
      apply_edits(text, edits);
      return text;
    }
    FAIL("no file " << sd_path);
    return "";
  }
};

std::unique_ptr<Run> lint(const std::map<std::string, std::string>& files, LintOptions o = {}) {
  auto r = std::make_unique<Run>();
  for (const auto& [p, t] : files) r->reader.add(p, t);
  if (o.select.empty()) o.select = {"unknown-command", "unused-suppression", "unknown-rule-in-suppression"};
  r->result = lint_machine(r->sm, r->reader, builtin_rules(), o);
  return r;
}

std::unique_ptr<Run> lint(const std::string& config, LintOptions o = {}) {
  return lint(std::map<std::string, std::string>{{"/sys/config.g", config}}, std::move(o));
}

using V = std::vector<std::string>;

}  // namespace

TEST_CASE("same-line suppression: by code or name, any case, with a reason", "[suppress]") {
  auto r = lint(
      "M9999 ; rrflint: disable=RRF101\n"
      "M9998 ; rrflint: disable=unknown-command -- vendor code\n"
      "M9997 ; rrflint:disable = Unknown-Command;reason after a second semicolon\n"
      "M9996 ; a comment first ; rrflint: disable=rrf101\n"
      "M9995\n");
  CHECK(r->found() == V{"/sys/config.g:5 RRF101"});
}

TEST_CASE("disable-next-line covers the next line with code, past comments and blank lines", "[suppress]") {
  auto r = lint(
      "; rrflint: disable-next-line=unknown-command\n"
      "; a comment\n"
      "\n"
      "M9999\n"
      "M9998\n"
      "G1 X0 ; rrflint: disable-next-line=RRF101\n"
      "M9997\n");
  CHECK(r->found() == V{"/sys/config.g:5 RRF101"});
}

TEST_CASE("ranges inside ranges: a finding is covered by any that holds it, and only those are used", "[suppress]") {
  // The lookup sorts a code's entries by their first line and keeps the farthest last line so far: a short range
  // opened after a long one must neither hide the long one (line 7) nor count as used for a finding outside it.
  auto r = lint(
      "; rrflint: disable=unknown-command\n"            // 1: a range to the enable on line 6
      "; rrflint: disable=RRF1\n"                       // 2: a prefix range to the end of the file
      "; rrflint: disable-next-line=unknown-command\n"  // 3: covers line 4, which has no finding: unused
      "G1 X0\n"                                         // 4
      "M9999\n"                                         // 5: covered by 1 and 2
      "; rrflint: enable=unknown-command\n"             // 6
      "M9998\n"                                         // 7: covered by 2 only
      "M9997 ; rrflint: disable=RRF101\n");             // 8: covered by 2 and by itself
  CHECK(r->found() == V{"/sys/config.g:3 RRF900"});
}

TEST_CASE("ranges: own-line disable until enable, or to the end of the file", "[suppress]") {
  auto r = lint(
      "M9990\n"
      "; rrflint: disable=unknown-command\n"
      "M9991\n"
      "  M9992\n"
      "; rrflint: enable=unknown-command\n"
      "M9993\n"
      "; rrflint: disable=RRF1\n"
      "M9994\n");
  CHECK(r->found() == V{"/sys/config.g:1 RRF101", "/sys/config.g:6 RRF101"});
}

TEST_CASE("enable names the rule it closes, a bare enable closes every range", "[suppress]") {
  auto r = lint(
      "; rrflint: disable=unknown-command\n"
      "; rrflint: disable=syntax-error\n"
      "; rrflint: enable=syntax-error\n"
      "M9999\n"
      "; rrflint: enable\n"
      "M9998\n",
      LintOptions{.select = {"unknown-command", "syntax-error"}});
  CHECK(r->found() == V{"/sys/config.g:6 RRF101"});
}

TEST_CASE("disable-file anywhere covers the whole file, and only that file", "[suppress]") {
  auto r = lint(
      {{"/sys/config.g", "M9999\nM98 P\"/macros/m.g\"\n; rrflint: disable-file=all\n"}, {"/macros/m.g", "M9998\n"}});
  CHECK(r->found() == V{"/macros/m.g:1 RRF101"});
}

TEST_CASE("no-inline-suppressions: ignores every directive and reports nothing about them", "[suppress]") {
  LintOptions o;
  o.inline_suppressions = false;
  auto r = lint("M9999 ; rrflint: disable=unknown-command\nG1 X0 ; rrflint: disable=nothing-like-this\n", o);
  CHECK(r->found() == V{"/sys/config.g:1 RRF101"});
}

TEST_CASE("RRF900 reports a suppression that suppresses nothing, only for rules of this run", "[suppress]") {
  auto r = lint(
      "G1 X0 ; rrflint: disable=unknown-command\n"
      "G1 Y0 ; rrflint: disable=line-too-long\n"      // not enabled in this run: not counted
      "M9999 ; rrflint: disable=unknown-command\n");  // used
  CHECK(r->found() == V{"/sys/config.g:1 RRF900"});
  const Diagnostic& d = r->only("RRF900");
  CHECK(d.severity == Severity::Info);
  CHECK(d.message == "unused suppression 'unknown-command' in 'disable': no such finding on this line");
  REQUIRE(d.fix);
  CHECK(d.fix->applicability == Applicability::Safe);
  CHECK(r->fixed("/sys/config.g", "RRF900") ==
        "G1 X0\n"
        "G1 Y0 ; rrflint: disable=line-too-long\n"
        "M9999 ; rrflint: disable=unknown-command\n");
}

TEST_CASE("RRF900 fix: the whole line when the comment is alone, else the comment and blanks before it", "[suppress]") {
  auto r = lint(
      "G90\r\n"
      "  ; rrflint: disable-next-line=unknown-command -- old board\r\n"
      "G1 X0\r\n"
      "G1 Y0 ; keep this ; rrflint: disable=unknown-command\r\n"
      "; note ; rrflint: disable-next-line=unknown-command\r\n"
      "G1 Z0\r\n");
  CHECK(r->found() == V{"/sys/config.g:2 RRF900", "/sys/config.g:4 RRF900", "/sys/config.g:5 RRF900"});
  CHECK(r->fixed("/sys/config.g", "RRF900") ==
        "G90\r\n"
        "G1 X0\r\n"
        "G1 Y0 ; keep this\r\n"
        "; note\r\n"
        "G1 Z0\r\n");
}

TEST_CASE("RRF900 with several names: only the unused ones are reported and removed", "[suppress]") {
  auto r = lint("M9999 ; rrflint: disable=syntax-error,unknown-command,line-too-long -- why\n",
                LintOptions{.select = {"unknown-command", "syntax-error", "unused-suppression"}});
  const Diagnostic& d = r->only("RRF900");
  CHECK(d.message == "unused suppression 'syntax-error' in 'disable': no such finding on this line");
  CHECK(r->fixed("/sys/config.g", "RRF900") == "M9999 ; rrflint: disable=unknown-command,line-too-long -- why\n");
}

TEST_CASE("RRF900 for ranges, file-level directives and stray enables", "[suppress]") {
  auto r = lint(
      "; rrflint: disable=unknown-command\n"
      "G1 X0\n"
      "; rrflint: enable=unknown-command\n"
      "; rrflint: enable=unknown-command\n"
      "; rrflint: disable-file=RRF101\n");
  CHECK(r->found() == V{"/sys/config.g:1 RRF900", "/sys/config.g:4 RRF900", "/sys/config.g:5 RRF900"});
}

TEST_CASE("a suppression of unused-suppression silences the other RRF900 findings", "[suppress]") {
  auto r = lint(
      "; rrflint: disable-file=unused-suppression -- migration in progress\n"
      "G1 X0 ; rrflint: disable=unknown-command\n");
  CHECK(r->found().empty());
  // With nothing to silence it is itself unused.
  auto r2 = lint("; rrflint: disable-file=unused-suppression\nG1 X0\n");
  CHECK(r2->found() == V{"/sys/config.g:1 RRF900"});
}

TEST_CASE("RRF901: unknown names (with a suggestion), bad keywords, missing lists", "[suppress]") {
  auto r = lint(
      "M9999 ; rrflint: disable=unknown-comand\n"
      "G1 X0 ; rrflint: disabel=unknown-command\n"
      "; rrflint: disable unknown-command\n"
      "; rrflint: disable-file=\n"
      "G1 Y0 ; rrflint: disable=RRF999,unknown-command\n");
  CHECK(r->found() == V{"/sys/config.g:1 RRF101", "/sys/config.g:1 RRF901", "/sys/config.g:2 RRF901",
                        "/sys/config.g:3 RRF901", "/sys/config.g:4 RRF901", "/sys/config.g:5 RRF901",
                        "/sys/config.g:5 RRF900"});
  std::vector<std::string> messages;
  for (const Diagnostic& d : r->result.diagnostics)
    if (d.code == "RRF901") messages.push_back(d.message);
  CHECK(messages == V{"unknown rule 'unknown-comand' in suppression comment; did you mean 'unknown-command' (RRF101)?",
                      "unknown suppression directive 'disabel': use disable, disable-next-line, disable-file or enable",
                      "expected '=' and a rule list after 'disable'", "'disable-file=' names no rule",
                      "unknown rule 'RRF999' in suppression comment"});
  // The finding points at the name as written.
  const SourceFile& f = r->sm.get(r->result.diagnostics[1].loc.file);
  CHECK(f.slice(r->result.diagnostics[1].loc.span) == "unknown-comand");
}

TEST_CASE("RRF901: a long word is quoted short, and costs no more than its length", "[suppress]") {
  // A 50,000-byte "rule name" was compared with every rule's name letter by letter for a suggestion (20 of them
  // took 2.4 s) and quoted whole in the message. Names whose lengths differ too much are no longer compared.
  const std::string word(50000, 'a');
  auto r = lint("G1 X0 ; rrflint: disable=" + word + "\n; rrflint: " + word + "=all\n");
  std::vector<std::string> messages;
  for (const Diagnostic& d : r->result.diagnostics)
    if (d.code == "RRF901") messages.push_back(d.message);
  CHECK(messages == V{"unknown rule '" + std::string(40, 'a') + "…' in suppression comment",
                      "unknown suppression directive '" + std::string(40, 'a') +
                          "…': use disable, disable-next-line, disable-file or enable"});
  // A near miss of about the same length is still suggested, a longer or shorter one too when close enough.
  auto near = lint("M9999 ; rrflint: disable=unknown-commands\nM9998 ; rrflint: disable=unknown-comm\n");
  messages.clear();
  for (const Diagnostic& d : near->result.diagnostics)
    if (d.code == "RRF901") messages.push_back(d.message);
  CHECK(messages ==
        V{"unknown rule 'unknown-commands' in suppression comment; did you mean 'unknown-command' (RRF101)?",
          "unknown rule 'unknown-comm' in suppression comment; did you mean 'unknown-command' (RRF101)?"});
}

TEST_CASE("comments that merely mention rrflint are not directives", "[suppress]") {
  auto r = lint(
      "; rrflint-options: --firmware 3.5\n"
      "; rrflint checks this: disable=x\n"
      "; see https://example.com/rrflint: disable=all\n"
      "M550 P\"; rrflint: disable=all\"\n");
  CHECK(r->found().empty());
}

TEST_CASE("severity overrides apply to RRF900 and RRF901", "[suppress]") {
  LintOptions o;
  o.severity["RRF900"] = Severity::Error;
  auto r = lint("G1 X0 ; rrflint: disable=unknown-command\n", o);
  CHECK(r->only("RRF900").severity == Severity::Error);
}

TEST_CASE("per-file ignores drop findings and make suppressions of that rule not count", "[suppress]") {
  LintOptions o;
  o.ignored_in_file = [](const SourceFile& f, std::string_view code) {
    return f.sd_path().starts_with("/macros/") && code == "RRF101";
  };
  auto r = lint({{"/sys/config.g", "M9999\nM98 P\"/macros/m.g\"\n"},
                 {"/macros/m.g", "M9998\nG1 X0 ; rrflint: disable=unknown-command\n"}},
                o);
  CHECK(r->found() == V{"/sys/config.g:1 RRF101"});
}

TEST_CASE("parse_directives resolves scopes", "[suppress]") {
  SourceManager sm;
  const SourceFile& f = sm.add("x.g", "/sys/x.g",
                               "G1 ; rrflint: disable=RRF101\n"
                               "; rrflint: disable-next-line=all\n"
                               "\n"
                               "G1\n"
                               "; rrflint: disable=RRF3 -- range\n"
                               "G1\n");
  ParsedFile pf = parse(f);
  auto ds = parse_directives(pf, builtin_rules());
  REQUIRE(ds.size() == 3);
  CHECK(ds[0].kind == DirectiveKind::Line);
  CHECK(ds[0].entries[0].first_line == 0);
  CHECK(ds[1].kind == DirectiveKind::NextLine);
  CHECK(ds[1].entries[0].all);
  CHECK(ds[1].entries[0].first_line == 3);
  CHECK(ds[2].kind == DirectiveKind::RangeStart);
  CHECK(ds[2].entries[0].prefix == "rrf3");
  CHECK(ds[2].entries[0].first_line == 5);
  CHECK(ds[2].entries[0].last_line == 5);
  CHECK(f.slice(ds[2].reason) == "range");
}

TEST_CASE("suppression_edits: append, merge into an existing directive, file level for lines without code",
          "[suppress]") {
  SourceManager sm;
  const SourceFile& f = sm.add("x.g", "/sys/x.g",
                               "; header\r\n"
                               "M9999   \r\n"
                               "M9998 ; keep\r\n"
                               "M9997 ; rrflint: disable=line-too-long -- why\r\n");
  ParsedFile pf = parse(f);
  std::map<uint32_t, std::vector<std::string>> by_line{{0, {"unknown-command"}},
                                                       {1, {"unknown-command", "syntax-error"}},
                                                       {2, {"unknown-command"}},
                                                       {3, {"unknown-command", "line-too-long"}}};
  std::string text(f.text());
  apply_edits(text, suppression_edits(pf, builtin_rules(), by_line, "legacy"));
  CHECK(text ==
        "; rrflint: disable-file=unknown-command -- legacy\r\n"
        "; header\r\n"
        "M9999 ; rrflint: disable=unknown-command,syntax-error -- legacy   \r\n"
        "M9998 ; keep ; rrflint: disable=unknown-command -- legacy\r\n"
        "M9997 ; rrflint: disable=line-too-long,unknown-command -- why\r\n");
}

TEST_CASE("suppression_edits: a line with a parse error gets a disable-next-line line above it", "[suppress]") {
  auto r = lint("if true\n  M98 P\"/sys/x.g\n  M9999\n",
                LintOptions{.select = {"syntax-error", "unknown-command", "unused-suppression"}});
  const FileUnit& u = r->result.machine->unit(0);
  std::map<uint32_t, std::vector<std::string>> by_line{{1, {"syntax-error"}}, {2, {"unknown-command"}}};
  std::string text(u.source->text());
  apply_edits(text, suppression_edits(u.parsed, builtin_rules(), by_line, ""));
  CHECK(text ==
        "if true\n"
        "  ; rrflint: disable-next-line=syntax-error\n"
        "  M98 P\"/sys/x.g\n"
        "  M9999 ; rrflint: disable=unknown-command\n");
  auto again = lint(text, LintOptions{.select = {"syntax-error", "unknown-command", "unused-suppression"}});
  CHECK(again->found().empty());
}
