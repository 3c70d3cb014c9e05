// The rrflint binary end to end: formats, colours, text output, fixes (--fix, --diff, --unsafe-fixes),
// suppressions on the command line, repository walks (.gitignore, exclude, --force-exclude), stdin, the `rule`
// command and the generated docs (which must not be stale).
#include <sys/stat.h>
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "cli/cli.h"
#include "lint/render/render.h"
#include "lint/render/rule_docs.h"
#include "rules/registry.h"
#include "tests/cli_util.h"

using namespace rrflint;
using namespace rrflint::test;
using nlohmann::json;

namespace {

const std::string kConfig =
    "; a small machine\n"
    "M584 X0 Y1 Z2\n"
    "M9999 ; vendor code\n"                       // RRF101 warning
    "G1 X0 ; rrflint: disable=unknown-command\n"  // RRF900 info, safe fix
    "M98 P\"/macros/park.g\"\n";

bool git_available() { return std::system("git --version >/dev/null 2>&1") == 0; }

// The page a link points at by default. The tests run from the build tree, so that is the source tree's
// docs/rules/ (cli/docs_url.cc), whatever is installed.
std::string docs_link(const std::string& name) {
  const std::string base = rrflint::cli::default_docs_base();
  CHECK(base == rrflint::cli::file_url(fs::path(RRFLINT_SOURCE_DIR) / "docs/rules"));
  return base + name + ".md";
}

// The file behind a file:// URL (percent-decoded).
fs::path file_of_url(const std::string& url) {
  REQUIRE(url.starts_with("file:///"));
  std::string path;
  for (size_t i = 7; i < url.size(); ++i) {
    if (url[i] == '%' && i + 2 < url.size()) {
      path += static_cast<char>(std::stoi(url.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      path += url[i];
    }
  }
  return path;
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace

TEST_CASE("cli: text output: carets, notes with their own snippet, fix preview, summary, rule links", "[cli]") {
  TempTree t;
  t.write("p/sys/config.g", kConfig);
  t.write("p/macros/park.g", "G1 X0 Y200\n");
  auto o = run_rrflint(t.root(), "check p");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "p/sys/config.g:3:1: warning RRF101 unknown-command: 'M9999'"));
  CHECK(contains(o.out, " 3 | M9999 ; vendor code\n   | ^^^^^\n"));
  CHECK(contains(o.out, "p/sys/config.g:4:7: info RRF900 unused-suppression:"));
  CHECK(contains(o.out, "  help: remove the suppression comment (--fix)\n 4 + G1 X0\n"));
  CHECK(contains(o.out, "0 errors, 1 warning, 1 info in 1 file (1 fixable with --fix)"));
  CHECK(contains(o.out, "  RRF101 unknown-command: " + docs_link("unknown-command") + "\n"));
}

TEST_CASE("text: a note in another file has that file's name and snippet, carets cover the exact range", "[cli]") {
  SourceManager sm;
  const SourceFile& cfg = sm.add("p/sys/config.g", "/sys/config.g", "M584 X0 Y1 Z2\nT0\tP1 ; select\n");
  const SourceFile& post = sm.add("p/sys/tpost0.g", "/sys/tpost0.g", "; wipe\nG1 X-30 F9000\n");
  Diagnostic d;
  d.code = "RRF326";
  d.name = "tool-select-runs-macros-at-boot";
  d.severity = Severity::Warning;
  d.loc = Location{cfg.id(), Span{14, 16}};
  d.message = "'T0' runs tpost0.g at boot";
  d.notes.push_back(Note{Location{post.id(), Span{10, 16}}, "tpost0.g moves the machine here"});
  Fix f;
  f.title = "add 'P0'";
  f.applicability = Applicability::Unsafe;
  f.edits.push_back(Edit{Location{cfg.id(), Span{16, 16}}, " P0"});
  d.fix = f;
  RenderOptions o;
  o.files_checked = 2;
  o.docs_base = "https://example.org/rrflint/rules";  // a '/' is added between the base and the name
  std::ostringstream os;
  render_text(os, sm, {d}, o);
  CHECK(os.str() ==
        "p/sys/config.g:2:1: warning RRF326 tool-select-runs-macros-at-boot: 'T0' runs tpost0.g at boot\n"
        " 2 | T0 P1 ; select\n"
        "   | ^^\n"
        "  note: p/sys/tpost0.g:2:4: tpost0.g moves the machine here\n"
        " 2 | G1 X-30 F9000\n"
        "   |    ------\n"
        "  help: add 'P0' (unsafe fix: --unsafe-fixes)\n"
        " 2 + T0 P0 P1 ; select\n"
        "\n"
        "0 errors, 1 warning, 0 infos in 1 file (1 fixable with --fix --unsafe-fixes)\n"
        "  RRF326 tool-select-runs-macros-at-boot: "
        "https://example.org/rrflint/rules/tool-select-runs-macros-at-boot.md\n");
}

TEST_CASE("text: the fix preview shows every line the fixed line becomes, and a removed line", "[cli]") {
  SourceManager sm;
  const SourceFile& cfg = sm.add("p/sys/config.g", "/sys/config.g", "M569 P0:1 S1\r\n; a\r\n; b\r\nG28\r\n");
  auto preview = [&](std::vector<Edit> edits) {
    Diagnostic d;
    d.code = "RRF220";
    d.name = "m569-driver-list";
    d.loc = Location{cfg.id(), Span{0, 4}};
    d.message = "m";
    Fix f;
    f.title = "t";
    f.edits = std::move(edits);
    d.fix = f;
    std::ostringstream os;
    render_text(os, sm, {d}, RenderOptions{});
    const std::string out = os.str();
    const size_t from = out.find("(--fix)\n") + 8;
    return out.substr(from, out.find("\n\n", from) - from);
  };
  auto at = [&](uint32_t b, uint32_t e) { return Location{cfg.id(), Span{b, e}}; };
  // One line split into two (CRLF kept in the file, not shown).
  CHECK(preview({Edit{at(0, 12), "M569 P0 S1\r\nM569 P1 S1"}}) == " 1 + M569 P0 S1\n 2 + M569 P1 S1");
  // A removed line (with its terminator) is shown as it was.
  CHECK(preview({Edit{at(0, 14), ""}}) == " 1 - M569 P0:1 S1");
  // An edit that inserts at the start of the next line takes that whole line in.
  CHECK(preview({Edit{at(14, 14), "  "}, Edit{at(19, 19), "  "}}) == " 2 +   ; a\n 3 +   ; b");
  // Many lines: the first three, then how many more.
  CHECK(preview({Edit{at(0, 12), "A\nB\nC\nD\nE\nF"}}) == " 1 + A\n 2 + B\n 3 + C\n 4 + … (3 more lines)");
}

TEST_CASE("text: a span that starts or ends inside a character marks the whole character", "[cli]") {
  // RRF102 marks a long line from its 256th byte, which can fall inside a character: here 2 bytes into the
  // 4-byte emoji. The snippet once showed the emoji as four U+FFFD, and its columns came out backwards.
  SourceManager sm;
  const SourceFile& f = sm.add("m.g", "/macros/m.g", "M117 \"ab\xF0\x9F\x98\x80 x\"\n");
  Diagnostic d;
  d.code = "RRF102";
  d.name = "line-too-long";
  d.severity = Severity::Error;
  d.loc = Location{f.id(), Span{10, 11}};  // both ends inside the emoji
  d.message = "long";
  RenderOptions o;
  o.files_checked = 1;
  std::ostringstream os;
  render_text(os, sm, {d}, o);
  CHECK(contains(os.str(),
                 "m.g:1:9: error RRF102 line-too-long: long\n"
                 " 1 | M117 \"ab\xF0\x9F\x98\x80 x\"\n"
                 "   |         ^\n"));
  const Range r = range_of(sm, d.loc);
  CHECK(r.start.column == 9);
  CHECK(r.end.column == 10);
}

TEST_CASE("cli: colours follow --color, FORCE_COLOR, NO_COLOR and TERM=dumb", "[cli]") {
  TempTree t;
  t.write("p/sys/config.g", kConfig);
  t.write("p/macros/park.g", "G1 X0\n");
  const std::string esc = "\x1b[";
  CHECK_FALSE(contains(run_rrflint(t.root(), "check p").out, esc));  // not a terminal
  CHECK(contains(run_rrflint(t.root(), "check p", "FORCE_COLOR=1").out, esc));
  CHECK_FALSE(contains(run_rrflint(t.root(), "check p", "FORCE_COLOR=0").out, esc));
  CHECK(contains(run_rrflint(t.root(), "check p --color always").out, esc));
  CHECK_FALSE(contains(run_rrflint(t.root(), "check p --color never", "FORCE_COLOR=1").out, esc));
  // On a terminal: `script` gives rrflint a pseudo-terminal when it is installed.
  if (std::system("command -v script >/dev/null 2>&1") == 0) {
    const std::string base = "cd " + shell_quote(t.root().string()) + " && env -u FORCE_COLOR -u NO_COLOR ";
    auto run_tty = [&](const std::string& env) {
      const std::string out = (t / "tty.out").string();
      const std::string cmd = base + env + " script -qec " + shell_quote(shell_quote(RRFLINT_BINARY) + " check p") +
                              " /dev/null > " + shell_quote(out) + " 2>&1";
      (void)std::system(cmd.c_str());
      return t.read("tty.out");
    };
    CHECK(contains(run_tty("TERM=xterm"), esc));
    CHECK_FALSE(contains(run_tty("TERM=xterm NO_COLOR=1"), esc));
    CHECK_FALSE(contains(run_tty("TERM=dumb"), esc));
  } else {
    RRFLINT_SKIPPED("the terminal part of the colour test needs `script` (bsdutils)");
  }
}

TEST_CASE("cli: concise, json, json-lines and -o", "[cli]") {
  TempTree t;
  t.write("p/sys/config.g", kConfig);
  t.write("p/macros/park.g", "G1 X0\n");
  auto o = run_rrflint(t.root(), "check p --format concise");
  auto cl = lines_of(o.out);
  REQUIRE(cl.size() == 2);
  CHECK(cl[0].starts_with("p/sys/config.g:3:1: warning: 'M9999' "));
  CHECK(cl[0].ends_with(" [RRF101 unknown-command]"));
  CHECK(cl[1] ==
        "p/sys/config.g:4:7: warning: unused suppression 'unknown-command' in 'disable': no such finding on this "
        "line [RRF900 unused-suppression, info]");
  o = run_rrflint(t.root(), "check p --format json");
  json doc = json::parse(o.out);
  CHECK(doc["version"] == 1);
  CHECK(doc["diagnostics"].size() == 2);
  CHECK(doc["diagnostics"][0]["url"] == docs_link("unknown-command"));
  CHECK(fs::is_regular_file(file_of_url(doc["diagnostics"][0]["url"])));
  CHECK(doc["summary"]["files_checked"] == 2);
  o = run_rrflint(t.root(), "check p --format json-lines");
  auto ls = lines_of(o.out);
  REQUIRE(ls.size() == 2);
  CHECK(json::parse(ls[1]) == doc["diagnostics"][1]);
  o = run_rrflint(t.root(), "check p --format sarif -o out.sarif");
  CHECK(o.out.empty());
  CHECK(json::parse(t.read("out.sarif"))["version"] == "2.1.0");
}

TEST_CASE("cli: --statistics counts the findings per rule, most first, as text or json", "[cli]") {
  TempTree t;
  // Two RRF307 findings (each with a safe fix to M568), one RRF101 (no fix), and one file with none.
  t.write("p/sys/config.g",
          "M584 X0 Y1 Z2 E3\nM950 H1 C\"out1\" T1\nM563 P0 D0 H1\nG10 P0 R0 S0\nG10 P0 R10 S20\nM9999\n");
  t.write("p/macros/park.g", "G1 X0\n");
  auto o = run_rrflint(t.root(), "check p --firmware 3.5 --select RRF307,RRF101 --statistics");
  CHECK(o.code == 1);  // the exit code of the findings, as without --statistics
  CHECK(o.out ==
        "2  RRF307  info     g10-temperature-form  2 fixable with --fix\n"
        "1  RRF101  warning  unknown-command\n"
        "0 errors, 1 warning, 2 infos in 1 file\n");
  o = run_rrflint(t.root(), "check p --firmware 3.5 --select RRF307,RRF101 --statistics --format json");
  const json doc = json::parse(o.out);
  CHECK(doc["version"] == 1);
  REQUIRE(doc["statistics"].size() == 2);
  CHECK(doc["statistics"][0] == json{{"code", "RRF307"},
                                     {"count", 2},
                                     {"fixable", 2},
                                     {"name", "g10-temperature-form"},
                                     {"severity", "info"},
                                     {"unsafe_fixable", 0},
                                     {"url", docs_link("g10-temperature-form")}});
  CHECK(doc["statistics"][1]["code"] == "RRF101");
  CHECK(doc["summary"]["files_checked"] == 2);
  CHECK(doc["summary"]["warnings"] == 1);
  // Nothing found: the text says so; the exit code is 0.
  o = run_rrflint(t.root(), "check p --select RRF116 --statistics");
  CHECK(o.code == 0);
  CHECK(o.out == "No problems found in 2 files.\n");
  // Options it cannot go with are usage errors, not a silently different report.
  for (const char* bad : {"--statistics --format sarif", "--statistics --format github", "--statistics --diff",
                          "--statistics --add-suppressions"}) {
    o = run_rrflint(t.root(), std::string("check p ") + bad);
    CHECK(o.code == 2);
    CHECK(contains(o.err, "--statistics"));
  }
}

TEST_CASE("cli: sarif URIs are relative to the git top-level, from any folder", "[cli][sarif]") {
  TempTree t;
  fs::create_directories(t / ".git");
  t.write("printers/p/sys/config.g", kConfig);
  t.write("printers/p/macros/park.g", "G1 X0\n");
  auto o = run_rrflint(t / "printers", "check p --format sarif");
  json doc = json::parse(o.out);
  CHECK(doc["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] ==
        "printers/p/sys/config.g");
  fs::remove_all(t / ".git");
  o = run_rrflint(t / "printers", "check p --format sarif");
  doc = json::parse(o.out);
  CHECK(doc["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] ==
        "p/sys/config.g");
}

TEST_CASE("cli: gitlab Code Quality: one entry per finding, paths from the git top-level, stable fingerprints",
          "[cli][gitlab]") {
  TempTree t;
  fs::create_directories(t / ".git");
  // Two identical lines with the same finding: their fingerprints differ (the occurrence counts).
  t.write("printers/p/sys/config.g", kConfig + "M9999\nM9999\n");
  t.write("printers/p/macros/park.g", "G1 X0\n");
  auto o = run_rrflint(t / "printers", "check p --format gitlab");
  CHECK(o.code == 1);
  const json doc = json::parse(o.out);
  REQUIRE(doc.is_array());
  REQUIRE(doc.size() == 4);  // RRF101 three times, RRF900 once
  std::set<std::string> fingerprints;
  for (const json& e : doc) {
    for (const char* k : {"check_name", "description", "fingerprint", "severity"}) CHECK(e[k].is_string());
    CHECK(e["location"]["path"] == "printers/p/sys/config.g");
    CHECK(e["location"]["positions"]["begin"]["line"].is_number_unsigned());
    fingerprints.insert(e["fingerprint"].get<std::string>());
  }
  CHECK(fingerprints.size() == doc.size());
  CHECK(doc[0]["check_name"] == "RRF101");
  CHECK(doc[0]["severity"] == "minor");  // a warning; an error is major, an info info
  CHECK(doc[0]["location"]["positions"]["begin"] == json{{"column", 1}, {"line", 3}});
  CHECK(contains(doc[0]["description"].get<std::string>(), "[RRF101 unknown-command]"));
  CHECK(doc[1]["check_name"] == "RRF900");
  CHECK(doc[1]["severity"] == "info");
  // A line inserted above moves the findings but keeps their fingerprints: GitLab reports nothing new.
  t.write("printers/p/sys/config.g", "; a new first line\n" + kConfig + "M9999\nM9999\n");
  const json moved = json::parse(run_rrflint(t / "printers", "check p --format gitlab").out);
  REQUIRE(moved.size() == doc.size());
  for (size_t i = 0; i < doc.size(); ++i) {
    CHECK(moved[i]["fingerprint"] == doc[i]["fingerprint"]);
    CHECK(moved[i]["location"]["positions"]["begin"]["line"] ==
          doc[i]["location"]["positions"]["begin"]["line"].get<int>() + 1);
  }
  // Nothing found: an empty array, which GitLab reads as "no issues".
  t.write("printers/q/sys/config.g", "M584 X0 Y1 Z2\n");
  o = run_rrflint(t / "printers", "check q --format gitlab");
  CHECK(o.code == 0);
  CHECK(json::parse(o.out) == json::array());
}

TEST_CASE("cli: github format is chosen under GITHUB_ACTIONS unless --format says otherwise", "[cli][github]") {
  TempTree t;
  t.write("p/sys/config.g", kConfig);
  t.write("p/macros/park.g", "G1 X0\n");
  auto o = run_rrflint(t.root(), "check p", "GITHUB_ACTIONS=true");
  CHECK(o.code == 1);
  auto ls = lines_of(o.out);
  REQUIRE(ls.size() == 2);
  CHECK(ls[0].starts_with(
      "::warning file=p/sys/config.g,line=3,endLine=3,col=1,endColumn=6,title=rrflint RRF101 unknown-command::"));
  CHECK(ls[1].starts_with("::notice file=p/sys/config.g,line=4,"));
  o = run_rrflint(t.root(), "check p --format concise", "GITHUB_ACTIONS=true");
  CHECK(lines_of(o.out)[0].starts_with("p/sys/config.g:3:1: warning:"));
}

TEST_CASE("cli: exit codes and --exit-zero, --fail-on", "[cli]") {
  TempTree t;
  t.write("p/sys/config.g", kConfig);
  t.write("p/macros/park.g", "G1 X0\n");
  CHECK(run_rrflint(t.root(), "check p").code == 1);
  CHECK(run_rrflint(t.root(), "check p --exit-zero").code == 0);
  CHECK(run_rrflint(t.root(), "check p --fail-on error").code == 0);
  t.write("i/sys/config.g", "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\n");  // one info finding
  CHECK(run_rrflint(t.root(), "check i").code == 0);
  CHECK(run_rrflint(t.root(), "check i --fail-on info").code == 1);
  CHECK(run_rrflint(t.root(), "check missing-folder").code == 2);
  auto bad = run_rrflint(t.root(), "check p --select no-such-rule");
  CHECK(bad.code == 2);
  CHECK(contains(bad.err, "unknown rule 'no-such-rule' (see `rrflint rule --all`)"));
  // A misspelt name gets the nearest one (on the command line, in rrflint rule and in a config file).
  bad = run_rrflint(t.root(), "check p --ignore g10-tool-befor-definition");
  CHECK(bad.code == 2);
  CHECK(contains(bad.err,
                 "unknown rule 'g10-tool-befor-definition'; did you mean 'g10-tool-before-definition' (RRF301)?"));
  CHECK(run_rrflint(t.root(), "check p --format yaml").code == 2);
  // A rule list before the paths takes one value (comma-separated), so the path stays a path.
  auto o = run_rrflint(t.root(), "check --select RRF101,RRF900 --ignore RRF900 p --format concise");
  CHECK(o.code == 1);
  CHECK(lines_of(o.out).size() == 1);
  CHECK(contains(o.out, "[RRF101 unknown-command]"));
}

TEST_CASE("cli: --fix applies safe fixes until stable, keeps line endings and permissions", "[cli][fix]") {
  TempTree t;
  t.write("p/sys/config.g",
          "M584 X0 Y1 Z2\r\n"
          "; rrflint: disable=unknown-command -- nothing below\r\n"
          "G1 X0\r\n"
          "; rrflint: enable=unknown-command\r\n"
          "M9999\r\n");
  t.write("q/sys/config.g", "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\n");
  ::chmod((t / "p/sys/config.g").c_str(), 0640);
  auto o = run_rrflint(t.root(), "check p q --fix");
  CHECK(o.code == 1);                                                        // the RRF101 on M9999 remains
  CHECK(t.read("p/sys/config.g") == "M584 X0 Y1 Z2\r\nG1 X0\r\nM9999\r\n");  // two rounds: disable, then enable
  CHECK(t.read("q/sys/config.g") == "M584 X0 Y1 Z2\nG1 X0\n");
  CHECK(contains(o.out, "Fixed 3 findings."));
  CHECK(contains(o.out, "RRF101"));
  CHECK_FALSE(contains(o.out, "RRF900"));
  struct stat st {};
  ::stat((t / "p/sys/config.g").c_str(), &st);
  CHECK((st.st_mode & 0777) == 0640);
  // No temporary files are left behind.
  for (const auto& e : fs::directory_iterator(t / "p/sys"))
    CHECK_FALSE(contains(e.path().filename().string(), ".rrflint-"));
  // Nothing left to fix: the files stay as they are.
  o = run_rrflint(t.root(), "check q --fix");
  CHECK(o.code == 0);
}

TEST_CASE("cli: --fix writes through symbolic links inside the linted folder", "[cli][fix]") {
  // A link out of the folder is refused: tests/robustness_test.cc.
  TempTree t;
  t.write("p/shared/config.g", "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\n");
  fs::create_directories(t / "p/sys");
  fs::create_symlink(t / "p/shared/config.g", t / "p/sys/config.g");
  CHECK(run_rrflint(t.root(), "check p --fix").code == 0);
  CHECK(fs::is_symlink(t / "p/sys/config.g"));
  CHECK(t.read("p/shared/config.g") == "M584 X0 Y1 Z2\nG1 X0\n");
}

TEST_CASE("cli: a symbolic link in sys/ to another card's file is a file of its own card, linted once", "[cli][walk]") {
  TempTree t;
  t.write("a/sys/config.g", "M98 P\"common.g\"\n");
  t.write("b/sys/config.g", "M98 P\"common.g\"\n");
  t.write("a/sys/common.g", "M584 X0 Y1 Z2E3\n");
  fs::create_symlink("../../a/sys/common.g", t / "b/sys/common.g");
  auto o = run_rrflint(t.root(), "check --format concise .");
  CHECK(o.code == 1);
  const auto lines = lines_of(o.out);
  REQUIRE(lines.size() == 2);
  CHECK(lines[0].starts_with("a/sys/common.g:1:14: warning:"));
  CHECK(lines[1].starts_with("b/sys/common.g:1:14: warning:"));
  // Named on its own, it is linted as b's /sys/common.g, not as a lone file: no note about a file with no card.
  o = run_rrflint(t.root(), "check --format concise b/sys/common.g");
  CHECK(o.out.starts_with("b/sys/common.g:1:14: warning:"));
  CHECK(lines_of(o.out).size() == 1);
  CHECK_FALSE(contains(o.err, "no SD card around it"));
}

TEST_CASE("cli: a file two cards share through a symbolic link is fixed once, and --diff names the real file",
          "[cli][fix]") {
  // b is named first, so its link is the first way to the file that the run fixes (before this was mended it was
  // refused as "outside the linted folder", b's card, and --diff gave the file twice, once under the link's name).
  TempTree t;
  const std::string card = "M584 X0 Y1 Z2 E3\nM563 P0 D0\nM98 P\"common.g\"\n";
  t.write("a/sys/config.g", card);
  t.write("b/sys/config.g", card);
  t.write("a/sys/common.g", "G10 P0 X1 Y2\n");
  fs::create_symlink("../../a/sys/common.g", t / "b/sys/common.g");
  // --diff: one part for the one file, under the name git apply can patch (it will not patch through a link).
  auto o = run_rrflint(t.root(), "check --select g10-implicit-z --diff b a");
  CHECK(o.code == 1);
  CHECK(o.out ==
        "--- a/a/sys/common.g\n"
        "+++ b/a/sys/common.g\n"
        "@@ -1 +1 @@\n"
        "-G10 P0 X1 Y2\n"
        "+G10 P0 X1 Y2 Z0\n");
  CHECK(contains(o.err, "would fix 1 finding in 1 file"));
  t.write("fix.diff", o.out);
  REQUIRE(std::system(("cd " + shell_quote(t.root().string()) + " && git apply -p1 --check fix.diff").c_str()) == 0);
  // --fix: the link leads into a folder named on the command line, so it is written through (the link stays).
  o = run_rrflint(t.root(), "check --select g10-implicit-z --fix b a");
  CHECK(o.code == 0);
  CHECK(t.read("a/sys/common.g") == "G10 P0 X1 Y2 Z0\n");
  CHECK(fs::is_symlink(t / "b/sys/common.g"));
  // Named alone, b's link leads out of what was named: refused, and the finding stays reported.
  t.write("a/sys/common.g", "G10 P0 X1 Y2\n");
  o = run_rrflint(t.root(), "check --select g10-implicit-z --fix b");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "b/sys/common.g: a symbolic link to "));
  CHECK(contains(o.err, "outside the linted folders: not written"));
  CHECK(t.read("a/sys/common.g") == "G10 P0 X1 Y2\n");
}

TEST_CASE("cli: --fix and --diff never write through a linked folder to outside what was named", "[cli][fix]") {
  // A linked folder on the way (here sys/lib) was not checked: only a link as the file itself was, so `--fix b`
  // rewrote a file outside b, and --diff showed it.
  TempTree t;
  const std::string unused = "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\n";
  t.write("outside/lib/x.g", unused);
  t.write("b/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"lib/x.g\"\n");
  fs::create_directory_symlink("../../outside/lib", t / "b/sys/lib");
  auto o = run_rrflint(t.root(), "check --fix b");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "b/sys/lib/x.g: reached through a linked folder"));
  CHECK(t.read("outside/lib/x.g") == unused);
  o = run_rrflint(t.root(), "check --diff b");
  CHECK(o.code == 2);
  CHECK(o.out.empty());
  CHECK(contains(o.err, "--fix would not write it"));
  // Named, the folder the link leads into may be written; the diff names the file where it is.
  o = run_rrflint(t.root(), "check --diff b outside");
  CHECK(o.code == 1);
  CHECK(o.out.starts_with("--- a/outside/lib/x.g\n+++ b/outside/lib/x.g\n"));
  CHECK(contains(o.err, "would fix 1 finding in 1 file"));
  CHECK(run_rrflint(t.root(), "check --fix b outside").code == 0);
  CHECK(t.read("outside/lib/x.g") == "M584 X0 Y1 Z2\nG1 X0\n");
}

TEST_CASE("cli: --diff over a linked card folder gives each file once, by the name git apply can patch", "[cli][fix]") {
  TempTree t;
  t.write("t1/a/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"common.g\"\n");
  t.write("t1/b/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"common.g\"\n");
  t.write("t1/a/sys/common.g", "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\n");
  fs::create_symlink("../../a/sys/common.g", t / "t1/b/sys/common.g");
  fs::create_directory_symlink("t1", t / "L");
  const auto o = run_rrflint(t.root(), "check --diff L");
  CHECK(o.code == 1);
  CHECK(o.out ==
        "--- a/t1/a/sys/common.g\n+++ b/t1/a/sys/common.g\n@@ -1,2 +1,2 @@\n M584 X0 Y1 Z2\n"
        "-G1 X0 ; rrflint: disable=unknown-command\n+G1 X0\n");
  CHECK(contains(o.err, "would fix 1 finding in 1 file"));
  t.write("fix.diff", o.out);
  CHECK(std::system(("cd " + shell_quote(t.root().string()) + " && git apply -p1 --check fix.diff").c_str()) == 0);
}

TEST_CASE("cli: RRF111 moves no text that holds a syntax error to a line of its own", "[cli][fix]") {
  // Found by fuzz_fix: the text after an M98 was moved out of the reach of the disable-next-line above it, and its
  // syntax error (which would abort config.g once RRF reads the line) appeared. Unreadable text stays where RRF
  // drops it; the finding is still reported, without a fix.
  TempTree t;
  const std::string before =
      "M584 X0 Y1 Z2\n; rrflint: disable-next-line = unknown-command, syntax-error\nM98 P\"m.g\" M9command\n"
      "M98 P\"m.g\" M106 P0 S{1+\nM98 P\"m.g\" M400\n";
  t.write("p/sys/config.g", before);
  t.write("p/sys/m.g", "G4 S0\n");
  auto syntax_errors = [&] {
    const auto lines = lines_of(run_rrflint(t.root(), "check --select ALL --format concise p").out);
    return std::count_if(lines.begin(), lines.end(), [](const std::string& l) { return contains(l, "RRF100"); });
  };
  const auto was = syntax_errors();
  auto o = run_rrflint(t.root(), "check --select ALL --format concise --unsafe-fixes --fix p");
  CHECK(t.read("p/sys/config.g") ==
        "M584 X0 Y1 Z2\n; rrflint: disable-next-line = unknown-command, syntax-error\nM98 P\"m.g\" M9command\n"
        "M98 P\"m.g\" M106 P0 S{1+\nM98 P\"m.g\"\nM400\n");
  CHECK(syntax_errors() == was);
  CHECK(contains(o.out, "p/sys/config.g:4:12: warning: 'M106 P0 S{1+' after 'M98'"));
}

TEST_CASE("cli: --diff prints a unified diff, writes nothing, exits 1 when there is something to fix", "[cli][fix]") {
  TempTree t;
  const std::string before = "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\nG1 Y0\n";
  t.write("p/sys/config.g", before);
  auto o = run_rrflint(t.root(), "check p --diff");
  CHECK(o.code == 1);
  CHECK(o.out ==
        "--- a/p/sys/config.g\n"
        "+++ b/p/sys/config.g\n"
        "@@ -1,3 +1,3 @@\n"
        " M584 X0 Y1 Z2\n"
        "-G1 X0 ; rrflint: disable=unknown-command\n"
        "+G1 X0\n"
        " G1 Y0\n");
  CHECK(contains(o.err, "would fix 1 finding in 1 file"));
  CHECK(t.read("p/sys/config.g") == before);
  // The diff applies with git apply (git is a test dependency, installed by scripts/setup.sh --test; patch(1)
  // is not, and a test must not depend on what happens to be installed). git apply works outside a repository.
  t.write("fix.diff", o.out);
  REQUIRE(std::system(("cd " + shell_quote(t.root().string()) + " && git apply -p1 fix.diff").c_str()) == 0);
  CHECK(t.read("p/sys/config.g") == "M584 X0 Y1 Z2\nG1 X0\nG1 Y0\n");
  o = run_rrflint(t.root(), "check p --diff");
  CHECK(o.code == 0);
  CHECK(o.out.empty());
}

TEST_CASE("cli: --diff applies to files with CR line endings and to names with spaces", "[cli][fix]") {
  TempTree t;
  // CR-only (RRF107 rewrites the endings), a lone CR inside an LF file, and a card folder with a space in its name.
  t.write("a/sys/config.g", "M550 P\"Bob's\"\rM584 X0 Y1 Z2E3\r");
  t.write("b/sys/config.g", "M584 X0 Y1 Z2\nG1 X0 ; rrflint: disable=unknown-command\r; note\n");
  t.write("my card/sys/config.g", "M584 X0 Y1 Z2E3\n");
  auto o = run_rrflint(t.root(), "check --diff .");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "--- a/my card/sys/config.g\t\n+++ b/my card/sys/config.g\t\n"));
  t.write("fix.diff", o.out);
  TempTree fixed;  // what --fix writes, for comparison
  for (const char* f : {"a/sys/config.g", "b/sys/config.g", "my card/sys/config.g"}) fixed.write(f, t.read(f));
  run_rrflint(fixed.root(), "check --fix .");
  REQUIRE(std::system(("cd " + shell_quote(t.root().string()) + " && git apply -p1 fix.diff").c_str()) == 0);
  for (const char* f : {"a/sys/config.g", "b/sys/config.g", "my card/sys/config.g"}) {
    INFO(f);
    CHECK(t.read(f) == fixed.read(f));
  }
  CHECK(t.read("a/sys/config.g") != "M550 P\"Bob's\"\rM584 X0 Y1 Z2E3\r");
}

TEST_CASE("cli: unsafe fixes only with --unsafe-fixes", "[cli][fix]") {
  TempTree t;
  const std::string before = "M584 X0 Y1 Z2 E3\nG10 P0 X0 Y0 Z0\nM563 P0 D0\n";
  t.write("p/sys/config.g", before);
  auto o = run_rrflint(t.root(), "check p --select g10-tool-before-definition --fix");
  CHECK(t.read("p/sys/config.g") == before);
  // The rule's fix moves the G10 below the M563: unsafe (it changes the order config.g runs in).
  REQUIRE(contains(o.out, "unsafe fix"));
  CHECK(contains(o.out, "fixable with --fix --unsafe-fixes"));
  // --diff shows only safe fixes, and says that an unsafe one is left out rather than "nothing to fix" alone.
  o = run_rrflint(t.root(), "check p --select g10-tool-before-definition --diff");
  CHECK(o.code == 0);
  CHECK(o.out.empty());
  CHECK(contains(o.err, "no fixes to apply (1 unsafe fix hidden: add --unsafe-fixes to see it)"));
  o = run_rrflint(t.root(), "check p --select g10-tool-before-definition --diff --unsafe-fixes");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "+G10 P0 X0 Y0 Z0"));
  CHECK(contains(o.err, "would fix 1 finding in 1 file\n"));
  CHECK(t.read("p/sys/config.g") == before);
  o = run_rrflint(t.root(), "check p --select g10-tool-before-definition --fix --unsafe-fixes");
  CHECK(t.read("p/sys/config.g") != before);
  CHECK(o.code == 0);
}

TEST_CASE("cli: stdin with --stdin-filename: placed in its card, config found from its folder, --fix to stdout",
          "[cli]") {
  TempTree t;
  t.write("p/sys/config.g", "M584 X0 Y1 Z2\nM98 P\"tool.g\"\n");
  t.write("p/sys/tool.g", "G1 X0\n");
  t.write("p/.rrflint.toml", "fail-on = \"info\"\n");
  const std::string text = "M9999\nG1 X0 ; rrflint: disable=unknown-command\n";
  auto o = run_rrflint(t.root(), "check --format concise --stdin-filename p/sys/tool.g -", "", text);
  CHECK(o.code == 1);
  CHECK(contains(o.out, "p/sys/tool.g:1:1: warning:"));
  CHECK(contains(o.out, "p/sys/tool.g:2:7: warning:"));
  CHECK_FALSE(contains(o.out, "config.g"));
  o = run_rrflint(t.root(), "check --fix --stdin-filename p/sys/tool.g -", "", text);
  CHECK(o.out == "M9999\nG1 X0\n");
  CHECK(contains(o.err, "RRF101"));
  CHECK(t.read("p/sys/tool.g") == "G1 X0\n");
}

TEST_CASE(
    "cli: stdin named as a file not on disk yet is shown where it will be, with its case, a name that is not "
    "G-code says why",
    "[cli]") {
  TempTree t;
  t.write("p/sys/config.g", "M584 X0 Y1 Z2\n");
  t.write("p/macros/Old.g", "G28\n");
  const std::string text = "M9999\n";
  // New files in sys/, macros/ (with and without an extension) and filaments/: each at its own path, as named.
  for (const std::string name : {"p/sys/New.g", "p/macros/Park.g", "p/macros/Wipe Nozzle", "p/filaments/PLA/load.g"}) {
    INFO(name);
    const auto o =
        run_rrflint(t.root(), "check --format concise --stdin-filename " + shell_quote(name) + " -", "", text);
    CHECK(o.code == 1);
    CHECK(o.out.starts_with(name + ":1:1: warning:"));
    CHECK(lines_of(o.out).size() == 1);
  }
  // A file on disk named in another case: linted once, as the disk spells it.
  auto o = run_rrflint(t.root(), "check --format concise --stdin-filename p/macros/old.g -", "", text);
  CHECK(o.out.starts_with("p/macros/Old.g:1:1: warning:"));
  CHECK(lines_of(o.out).size() == 1);
  // Not G-code (an extensionless file in sys/, a folder): an error that says so, not only "no file was linted".
  for (const std::string name : {"p/sys/notes", "p/sys"}) {
    INFO(name);
    o = run_rrflint(t.root(), "check --stdin-filename " + name + " -", "", text);
    CHECK(o.code == 2);
    CHECK(contains(o.err, "error: " + name + ": not linted: not a G-code file"));
  }
  // A name that ends at a folder (`/`, `p/sys/`): not linted as a file of that name.
  for (const std::string name : {"/", "p/sys/"}) {
    INFO(name);
    o = run_rrflint(t.root(), "check --stdin-filename " + name + " -", "", text);
    CHECK(o.code == 2);
    CHECK(contains(o.err, "error: --stdin-filename " + name + ": that names a folder"));
    CHECK(o.out.empty());
  }
}

TEST_CASE("cli: --no-inline-suppressions and --add-suppressions", "[cli][suppress]") {
  TempTree t;
  t.write("p/sys/config.g",
          "M584 X0 Y1 Z2\nM9999 ; rrflint: disable=RRF101\nM9998 ; note\nM9997 ; rrflint: disable=line-too-long\n");
  auto o = run_rrflint(t.root(), "check p --format concise --no-inline-suppressions");
  CHECK(lines_of(o.out).size() == 3);
  CHECK_FALSE(contains(o.out, "RRF900"));
  // The flag takes its reason only after '=', so a path after it stays a path.
  o = run_rrflint(t.root(), "check --add-suppressions p");
  CHECK(o.code == 0);
  CHECK(contains(o.err, "added 2 suppressions to 1 file"));
  CHECK(t.read("p/sys/config.g") ==
        "M584 X0 Y1 Z2\nM9999 ; rrflint: disable=RRF101\nM9998 ; note ; rrflint: disable=unknown-command\n"
        "M9997 ; rrflint: disable=line-too-long,unknown-command\n");
  CHECK(run_rrflint(t.root(), "check p").code == 0);
  t.write("q/sys/config.g", "M9999\n");
  o = run_rrflint(t.root(), "check q --add-suppressions='old board, kept on purpose'");
  CHECK(t.read("q/sys/config.g") == "M9999 ; rrflint: disable=unknown-command -- old board, kept on purpose\n");
  CHECK(run_rrflint(t.root(), "check q --add-suppressions --fix").code == 2);
}

TEST_CASE("cli: --add-suppressions refuses a reason that would end the comment, the reason keeps a tab",
          "[cli][suppress]") {
  TempTree t;
  const std::string config = "M584 X0 Y1 Z2\nM9999\n";
  t.write("p/sys/config.g", config);
  // A line break would make the rest of the reason a command (here a board reset); NUL ends the line in RRF too,
  // and DEL makes RRF drop the whole line.
  for (const std::string reason : {"why\\nM999 ; reset", "why\\rM999", "a\\001b", "a\\177b"}) {
    INFO(reason);
    const auto o = run_rrflint(t.root(), "check p --add-suppressions=\"$(printf '" + reason + "')\"");
    CHECK(o.code == 2);
    CHECK(contains(o.err, "the reason must be one line of text"));
    CHECK(t.read("p/sys/config.g") == config);
  }
  CHECK(run_rrflint(t.root(), "check p --add-suppressions=\"$(printf 'old\\tboard')\"").code == 0);
  CHECK(t.read("p/sys/config.g") == "M584 X0 Y1 Z2\nM9999 ; rrflint: disable=unknown-command -- old\tboard\n");
}

TEST_CASE("cli: --fix on stdin with -o FILE still hands the fixed text back on stdout", "[cli]") {
  TempTree t;
  const auto o = run_rrflint(t.root(), "check --fix -o report.txt -", "", "M584 X0 Y1 Z2E3\nG1 X0\n");
  CHECK(o.code == 0);
  CHECK(o.out == "M584 X0 Y1 Z2 E3\nG1 X0\n");
  CHECK(contains(t.read("report.txt"), "Fixed 1 finding."));
}

TEST_CASE("cli: --diff honours --exit-zero, an empty --select, --firmware or --board is a usage error", "[cli]") {
  TempTree t;
  t.write("p/sys/config.g", "M584 X0 Y1 Z2E3\n");
  CHECK(run_rrflint(t.root(), "check --diff p").code == 1);
  auto o = run_rrflint(t.root(), "check --diff --exit-zero p");
  CHECK(o.code == 0);
  CHECK(contains(o.out, "+M584 X0 Y1 Z2 E3"));
  // `--select "$RULES"` with the variable unset would turn every rule off and pass.
  for (const std::string args : {"--select ''", "--select ' , '", "--firmware ''", "--board ''"}) {
    INFO(args);
    o = run_rrflint(t.root(), "check p " + args);
    CHECK(o.code == 2);
    CHECK(contains(o.err, ": empty value"));
  }
  CHECK(run_rrflint(t.root(), "check p --ignore ''").code == 1);  // ignores nothing: the findings stay
}

TEST_CASE("cli: a lone file is shown by its path from here when walked, and linted once however often it is named",
          "[cli][walk]") {
  TempTree t;
  t.write("w/x.g", "M584 X0 Y1 Z2E3\n");
  auto o = run_rrflint(t.root(), "check --format concise w");
  CHECK(o.out.starts_with("w/x.g:1:14: warning:"));
  o = run_rrflint(t.root(), "check --diff w");
  CHECK(o.out.starts_with("--- a/w/x.g\n+++ b/w/x.g\n"));
  o = run_rrflint(t.root(), "check --format concise w/x.g ./w/x.g w/../w/x.g w");
  CHECK(o.code == 1);
  CHECK(lines_of(o.out).size() == 1);
  o = run_rrflint(t.root() / "w", "check --fix x.g x.g");
  CHECK(o.code == 0);
  CHECK(contains(o.out, "No problems found in 1 file."));
  CHECK(t.read("w/x.g") == "M584 X0 Y1 Z2 E3\n");
}

TEST_CASE("cli: model of a folder with no machine, or with several, says so", "[cli][model]") {
  TempTree t;
  fs::create_directories(t / "empty");
  t.write("s/a/sys/config.g", "M584 X0 Y1 Z2\n");
  t.write("s/b/sys/config.g", "M584 X0 Y1 Z2\n");
  auto o = run_rrflint(t.root(), "model empty");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "error: empty: no G-code here"));
  o = run_rrflint(t.root(), "model s");
  CHECK(o.code == 2);
  CHECK(o.out.empty());
  CHECK(contains(o.err, "error: s holds 2 machines (s/a, s/b): name one of them"));
  o = run_rrflint(t.root(), "model s/b");
  CHECK(o.code == 0);
  CHECK(o.out.starts_with("Machine: s/b\n"));
}

TEST_CASE("cli: --config names what is wrong with the file, --isolated with --config is a usage error",
          "[cli][config]") {
  TempTree t;
  t.write("p/sys/config.g", "M584 X0 Y1 Z2\n");
  auto o = run_rrflint(t.root(), "check --config . p");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "error: .: is a folder, not a config file"));
  o = run_rrflint(t.root(), "check --config /dev/null p");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "error: /dev/null: is not a regular file"));
  o = run_rrflint(t.root(), "check --config nope.toml p");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "error: nope.toml: no such file"));
  o = run_rrflint(t.root(), "check --isolated --config nope.toml p");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "--config excludes --isolated"));
}

TEST_CASE("cli: a card whose every file is excluded says so, named, its file is linted", "[cli][walk]") {
  TempTree t;
  t.write("c/sys/config.g", "M584 X0 Y1 Z2E3\n");
  t.write("c/.rrflint.toml", "exclude = [\"sys/config.g\"]\n");
  auto o = run_rrflint(t.root(), "check c");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "error: every file of the cards given is left out by `exclude` or .gitignore"));
  CHECK(run_rrflint(t.root(), "check c/sys/config.g").code == 1);
  // A named file that is not G-code is not "left out": the card's other files are simply not reported.
  t.write("c/sys/notes", "x\n");
  o = run_rrflint(t.root(), "check c/sys/notes");
  CHECK(o.code == 2);
  CHECK(contains(o.err, "c/sys/notes: not linted: not a G-code file"));
  CHECK_FALSE(contains(o.err, "left out"));
}

TEST_CASE("cli: a repository walk finds every card, lone files and extensionless macros", "[cli][walk]") {
  TempTree t;
  t.write("a/sys/config.g", "M584 X0 Y1 Z2\nM9991\n");
  t.write("a/macros/Park Head", "M9992\n");             // extensionless macro with a space, inside card a
  t.write("b/SYS/config.g", "M584 X0 Y1 Z2\nM9993\n");  // any case
  t.write("c/sys/homeall.g", "M9994\n");                // a sys folder without config.g
  t.write("d/macros/wipe", "M9995\n");                  // a macros folder on its own
  t.write("misc/test.g", "M9996\n");                    // a lone file
  t.write("misc/readme.txt", "M9997\n");                // not G-code
  t.write("misc/notes", "M9998\n");                     // no extension, not under macros/
  auto o = run_rrflint(t.root(), "check . --format concise");
  CHECK(o.code == 1);
  for (const char* want : {"a/sys/config.g:2:1", "a/macros/Park Head:1:1", "b/SYS/config.g:2:1", "c/sys/homeall.g:1:1",
                           "d/macros/wipe:1:1", "misc/test.g:1:1"})
    CHECK(contains(o.out, want));
  CHECK_FALSE(contains(o.out, "readme.txt"));
  CHECK_FALSE(contains(o.out, "misc/notes"));
  // A folder inside a card reports only what is below it, with the card as context.
  o = run_rrflint(t.root(), "check a/macros --format concise");
  CHECK(contains(o.out, "a/macros/Park Head:1:1"));
  CHECK_FALSE(contains(o.out, "config.g"));
}

TEST_CASE("cli: a module folder inside sys/ is walked as part of its card, however it is spelled", "[cli][walk]") {
  TempTree t;
  t.write("a/sys/config.g", "M584 X0 Y1 Z2\nM9991\n");
  t.write("a/sys/mod/config.g", "M9992\n");
  t.write("a/sys/mod/x.g", "M9993\n");  // reached by nothing: linted as an entry of card a
  const auto plain = run_rrflint(t.root(), "check a/sys/mod --format concise");
  CHECK(contains(plain.out, "a/sys/mod/config.g:1:1"));
  CHECK(contains(plain.out, "a/sys/mod/x.g:1:1"));
  CHECK_FALSE(contains(plain.out, "a/sys/config.g"));
  for (const char* spelled : {"a/sys/mod/", "./a/sys/mod", "a/sys/../sys/mod"}) {
    INFO(spelled);
    CHECK(run_rrflint(t.root(), std::string("check ") + spelled + " --format concise").out == plain.out);
  }
}

TEST_CASE("cli: .gitignore and exclude are honoured in walks, explicit files only with --force-exclude",
          "[cli][walk]") {
  TempTree t;
  t.write("a/sys/config.g", "M584 X0 Y1 Z2\nM9991\n");
  t.write("a/sys/scratch.g", "M9992\n");
  t.write("old/sys/config.g", "M9993\n");
  t.write("gen/out.g", "M9994\n");
  t.write(".gitignore", "# generated\n/gen/\n*scratch*\n");
  t.write(".rrflint.toml", "exclude = [\"old\"]\n");
  auto check_walk = [&](const std::string& label) {
    INFO(label);
    auto o = run_rrflint(t.root(), "check . --format concise");
    CHECK(contains(o.out, "a/sys/config.g:2:1"));
    CHECK_FALSE(contains(o.out, "scratch.g"));
    CHECK_FALSE(contains(o.out, "old/"));
    CHECK_FALSE(contains(o.out, "gen/"));
  };
  check_walk("no repository: the built-in .gitignore matcher");
  if (git_available()) {
    REQUIRE(std::system(("git -C " + shell_quote(t.root().string()) + " init -q").c_str()) == 0);
    check_walk("inside a git repository: git check-ignore");
    // Only git reads .git/info/exclude: a file left out by it shows that git answered (a git that failed would
    // leave the built-in matcher to answer, and the walk above would pass all the same).
    t.write(".git/info/exclude", "gitonly.g\n");
    t.write("a/sys/gitonly.g", "M9995\n");
    CHECK_FALSE(contains(run_rrflint(t.root(), "check . --format concise").out, "gitonly.g"));
    fs::remove(t / "a/sys/gitonly.g");
  } else {
    RRFLINT_SKIPPED("git is not installed; only the built-in .gitignore matcher was tested");
  }
  auto o = run_rrflint(t.root(), "check old/sys/config.g --format concise");
  CHECK(contains(o.out, "old/sys/config.g:1:1"));  // named explicitly: linted
  o = run_rrflint(t.root(), "check old/sys/config.g a/sys/scratch.g --format concise --force-exclude");
  CHECK(o.out.empty());
  CHECK(o.code == 0);
  o = run_rrflint(t.root(), "check . --format concise --no-respect-gitignore");
  CHECK(contains(o.out, "gen/out.g"));
  // A gitignored folder or file named on the command line is linted; --force-exclude leaves it out.
  o = run_rrflint(t.root(), "check gen --format concise");
  CHECK(contains(o.out, "gen/out.g"));
  o = run_rrflint(t.root(), "check a/sys/scratch.g --format concise");
  CHECK(contains(o.out, "a/sys/scratch.g:1:1"));
  o = run_rrflint(t.root(), "check gen --format concise --force-exclude");
  CHECK_FALSE(contains(o.out, "gen/out.g"));
  CHECK(o.code == 0);
}

TEST_CASE(
    "cli: .gitignore in a sub-folder: negation, anchoring, folder-only patterns, git and the built-in matcher agree",
    "[cli][walk]") {
  TempTree t;
  t.write("sub/.gitignore", "# comment\nkeep/*\n!keep/this.g\n/anch.g\ndironly/\n");
  t.write("sub/keep/this.g", "M9991\n");  // ignored by keep/*, then un-ignored
  t.write("sub/keep/that.g", "M9992\n");  // ignored
  t.write("sub/anch.g", "M9993\n");       // ignored: anchored to sub/
  t.write("sub/x/anch.g", "M9994\n");     // not: the pattern is anchored
  t.write("sub/dironly/f.g", "M9995\n");  // ignored with its folder
  t.write("sub/dironly.g", "M9996\n");    // not: dironly/ matches folders only
  auto check_walk = [&](const std::string& label) {
    INFO(label);
    const std::string out = run_rrflint(t.root(), "check sub --format concise").out;
    for (const char* code : {"M9991", "M9994", "M9996"}) CHECK(contains(out, code));
    for (const char* code : {"M9992", "M9993", "M9995"}) CHECK_FALSE(contains(out, code));
  };
  check_walk("no repository: the built-in .gitignore matcher");
  if (git_available()) {
    REQUIRE(std::system(("git -C " + shell_quote(t.root().string()) + " init -q").c_str()) == 0);
    check_walk("inside a git repository: git check-ignore");
  }
}

TEST_CASE("cli: `rrflint rule` prints the page, --all --format json carries url and fix", "[cli][docs]") {
  TempTree t;
  auto o = run_rrflint(t.root(), "rule RRF900");
  CHECK(o.code == 0);
  CHECK(o.out.starts_with("# unused-suppression (RRF900)\n"));
  CHECK(contains(o.out, "## What it does"));
  o = run_rrflint(t.root(), "rule unknown-command --format json");
  json j = json::parse(o.out);
  CHECK(j["code"] == "RRF101");
  CHECK(j["url"] == docs_link("unknown-command"));
  o = run_rrflint(t.root(), "rule --all --format json");
  j = json::parse(o.out);
  for (const json& r : j) {
    CHECK(r.contains("url"));
    CHECK(r["url"] == docs_link(r["name"]));
    CHECK(std::set<std::string>{"none", "sometimes", "always"}.count(r["fix"]));
  }
  CHECK(run_rrflint(t.root(), "rule no-such-rule").code == 2);
  const auto miss = run_rrflint(t.root(), "rule unknown-comand");
  CHECK(miss.code == 2);
  CHECK(contains(miss.err, "unknown rule 'unknown-comand'; did you mean 'unknown-command' (RRF101)?"));
}

TEST_CASE("docs: docs/rules and the README rule list are up to date with the rule registry", "[docs]") {
  const fs::path dir = fs::path(RRFLINT_SOURCE_DIR) / "docs/rules";
  const std::string fix =
      "regenerate with: rrflint rule --generate-docs docs/rules --readme README.md "
      "(or cmake --build <dir> --target rrflint_docs)";
  // The first line that differs, so a failure says where without dumping both pages.
  auto first_difference = [](const std::string& have, const std::string& want) {
    auto a = lines_of(have), b = lines_of(want);
    for (size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
      std::string x = i < a.size() ? a[i] : "(end of file)", y = i < b.size() ? b[i] : "(end of file)";
      if (x != y) return "line " + std::to_string(i + 1) + ": has \"" + x + "\", should be \"" + y + "\"";
    }
    return std::string("(line endings differ)");
  };
  for (const auto& [name, text] : generated_rule_docs(builtin_rules())) {
    std::ifstream in(dir / name, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const bool fresh = ss.str() == text;
    if (fresh) continue;
    INFO("docs/rules/" << name << " is stale (" << (in ? first_difference(ss.str(), text) : "missing") << "); " << fix);
    CHECK(fresh);
  }
  const auto want = generated_rule_docs(builtin_rules());
  for (const auto& e : fs::directory_iterator(dir)) {
    INFO("docs/rules/" << e.path().filename().string() << " belongs to no rule; " << fix);
    CHECK(want.count(e.path().filename().string()) == 1);
  }
  std::ifstream in(fs::path(RRFLINT_SOURCE_DIR) / "README.md", std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  auto updated = replace_rule_list(ss.str(), readme_rule_list(builtin_rules()));
  INFO("README.md has no '" << kRulesBegin << "' ... '" << kRulesEnd << "' markers");
  REQUIRE(updated);
  const bool fresh = *updated == ss.str();
  if (!fresh) {
    INFO("README.md's rule list is stale (" << first_difference(ss.str(), *updated) << "); " << fix);
    CHECK(fresh);
  }
}

TEST_CASE("ci: the problem matcher in .github reads every concise line", "[cli][github]") {
  std::ifstream in(fs::path(RRFLINT_SOURCE_DIR) / ".github/rrflint-matcher.json");
  REQUIRE(in);
  const json m = json::parse(in);
  const json& p = m["problemMatcher"][0]["pattern"][0];
  const std::regex re(p["regexp"].get<std::string>());
  TempTree t;
  t.write("p/sys/all standby.g", "M9999\nG1 X0 ; rrflint: disable=unknown-command\n");
  auto o = run_rrflint(t.root(), "check p --format concise");
  auto ls = lines_of(o.out);
  REQUIRE(ls.size() == 2);
  std::smatch sm;
  REQUIRE(std::regex_match(ls[0], sm, re));
  CHECK(sm[p["file"].get<int>()] == "p/sys/all standby.g");
  CHECK(sm[p["line"].get<int>()] == "1");
  CHECK(sm[p["column"].get<int>()] == "1");
  CHECK(sm[p["severity"].get<int>()] == "warning");
  CHECK(sm[p["code"].get<int>()] == "RRF101");
  REQUIRE(std::regex_match(ls[1], sm, re));  // an info finding
  CHECK(sm[p["code"].get<int>()] == "RRF900");
  CHECK(sm[p["message"].get<int>()] ==
        "unused suppression 'unknown-command' in 'disable': no such finding on this line");
}

TEST_CASE("cli: machines linted in parallel report exactly what a serial run reports", "[cli]") {
  TempTree t;
  // Several cards with findings in several files, notes across files, a lone file and a config with per-file
  // ignores: the parallel run must give the same bytes, in the same order.
  for (int i = 0; i < 6; ++i) {
    const std::string card = "c" + std::to_string(i);
    t.write(card + "/sys/config.g", "M9999\nM563 P0 D0 H1\nG10 P0 X1\nM98 P\"a.g\"\nT0\n");
    t.write(card + "/sys/a.g", "M9998\nG10 P" + std::to_string(i) + " Z1\n");
    t.write(card + "/sys/tpost0.g", "G1 X1 F600 G1 Y2\n");
  }
  t.write("lone.g", "M9997\n");
  t.write(".rrflint.toml", "[per-file-ignores]\n\"c3/**\" = [\"RRF101\"]\n");
  for (const std::string fmt : {"text", "json", "sarif"}) {
    auto serial = run_rrflint(t.root(), "check . lone.g --format " + fmt + " -j 1");
    auto parallel = run_rrflint(t.root(), "check . lone.g --format " + fmt + " -j 4");
    INFO(fmt);
    CHECK(serial.code == 1);
    CHECK(parallel.code == serial.code);
    CHECK(parallel.out == serial.out);
    CHECK(parallel.err == serial.err);
    CHECK(contains(serial.out, "M9998"));
  }
  CHECK(run_rrflint(t.root(), "check . -j 0").code == 2);  // a usage error
}

TEST_CASE("cli: a macro in a sys folder under another name is linted with its card", "[cli]") {
  TempTree t;
  t.write("printer/config.g", "M98 P\"homeall.g\"\n");
  t.write("printer/homeall.g", "M9998\n");
  t.write("printer/park.g", "M9997\n");
  // Named on its own, the macro is linted as part of the card (config.g's folder plays /sys) and reported.
  auto o = run_rrflint(t.root() / "printer", "check park.g --format concise");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "park.g:1:1: warning: 'M9997'"));
  CHECK_FALSE(contains(o.out, "M9998"));  // only the file asked for
  o = run_rrflint(t.root(), "check printer --format concise");
  CHECK(contains(o.out, "printer/homeall.g:1:1"));
  CHECK(contains(o.out, "printer/park.g:1:1"));
}

TEST_CASE("cli: a large file, mapped rather than read, reports what the same bytes from stdin report", "[cli]") {
  TempTree t;
  // 4 MB and more is mapped. Findings at the start and at the very end, and a size that is a whole number of
  // pages, so that every scan runs up to the end of the mapping.
  std::string big = "M584 X0 Y1 Z2\nM9999\n";
  while (big.size() < (size_t{5} << 20)) big += "G1 X10.5 Y20 F3000 ; a move\nM950 H1 C\"out1\" T1\n";
  const std::string last = "\nM950 H2 Cout2 T1";
  big.resize((size_t{5} << 20) - last.size());
  big += last;
  REQUIRE(big.size() % 4096 == 0);
  t.write("big.g", big);
  const auto mapped = run_rrflint(t.root(), "check --format concise big.g");
  const auto piped = run_rrflint(t.root(), "check --format concise --stdin-filename big.g -", "", big);
  CHECK(mapped.code == 1);
  CHECK(mapped.err == piped.err);
  CHECK(mapped.out == piped.out);
  CHECK(contains(mapped.out, "big.g:2:1: warning:"));       // M9999
  CHECK(contains(mapped.out, "unquoted pin name 'out2'"));  // the last line
}

TEST_CASE("docs links: the default from a build opens an existing page for every rule", "[cli][docs]") {
  TempTree t;  // no config file: the build's default
  auto o = run_rrflint(t.root(), "rule --all --format json");
  REQUIRE(o.code == 0);
  const json rules = json::parse(o.out);
  REQUIRE(rules.size() == builtin_rules().all().size());
  for (const json& r : rules) {
    INFO(r["url"]);
    const fs::path page = file_of_url(r["url"]);
    CHECK(fs::is_regular_file(page));
    CHECK(page.filename() == r["name"].get<std::string>() + ".md");
  }
  // The explanation the pages link to ships with them.
  CHECK(fs::is_regular_file(fs::path(RRFLINT_SOURCE_DIR) / "docs/firmware-behaviour.md"));
}

TEST_CASE("docs links: docs-url moves every link, and only a web base gets SARIF helpUri", "[cli][docs][sarif]") {
  TempTree t;
  fs::create_directories(t / ".git");
  t.write("p/sys/config.g", kConfig);
  t.write("p/macros/park.g", "G1 X0\n");
  // Default (file://): JSON url is the local page, SARIF has no helpUri and no informationUri.
  json sarif = json::parse(run_rrflint(t.root(), "check p --format sarif").out);
  const json& driver = sarif["runs"][0]["tool"]["driver"];
  CHECK_FALSE(driver.contains("informationUri"));
  for (const json& r : driver["rules"]) CHECK_FALSE(r.contains("helpUri"));
  auto gh = run_rrflint(t.root(), "check p --format github");
  CHECK(contains(gh.out, "%0Arrflint rule RRF101\n"));
  CHECK_FALSE(contains(gh.out, "file://"));

  t.write(".rrflint.toml", "docs-url = \"https://docs.example.org/rrflint/rules/\"\n");
  json doc = json::parse(run_rrflint(t.root(), "check p --format json").out);
  CHECK(doc["diagnostics"][0]["url"] == "https://docs.example.org/rrflint/rules/unknown-command.md");
  sarif = json::parse(run_rrflint(t.root(), "check p --format sarif").out);
  for (const json& r : sarif["runs"][0]["tool"]["driver"]["rules"])
    CHECK(r["helpUri"] == "https://docs.example.org/rrflint/rules/" + r["name"].get<std::string>() + ".md");
  CHECK(contains(run_rrflint(t.root(), "check p").out,
                 "  RRF101 unknown-command: https://docs.example.org/rrflint/rules/unknown-command.md\n"));
  gh = run_rrflint(t.root(), "check p --format github");
  CHECK(contains(gh.out, "%0Ahttps://docs.example.org/rrflint/rules/unknown-command.md\n"));
  CHECK(json::parse(run_rrflint(t.root(), "rule RRF101 --format json").out)["url"] ==
        "https://docs.example.org/rrflint/rules/unknown-command.md");
  CHECK(json::parse(run_rrflint(t.root(), "rule RRF101 --format json --isolated").out)["url"] ==
        docs_link("unknown-command"));

  // A file:// docs-url (a local mirror): the links follow it, SARIF still leaves helpUri out.
  t.write(".rrflint.toml", "docs-url = \"file:///opt/rrflint%20docs/rules\"\n");
  doc = json::parse(run_rrflint(t.root(), "check p --format json").out);
  CHECK(doc["diagnostics"][0]["url"] == "file:///opt/rrflint%20docs/rules/unknown-command.md");
  sarif = json::parse(run_rrflint(t.root(), "check p --format sarif").out);
  for (const json& r : sarif["runs"][0]["tool"]["driver"]["rules"]) CHECK_FALSE(r.contains("helpUri"));

  // A bad docs-url is a config error like any other.
  t.write(".rrflint.toml", "docs-url = \"docs/rules\"\n");
  auto bad = run_rrflint(t.root(), "check p");
  CHECK(bad.code == 2);
  CHECK(contains(bad.err, ".rrflint.toml:1:12: 'docs-url': "));
}
