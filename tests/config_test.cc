// The config file (frontend/config.cc): keys, provenance, extend chains, errors with file:line, discovery, globs;
// and the CLI behaviour that depends on it (check, config, exit codes).
#include <catch2/catch.hpp>

#include "frontend/config.h"
#include "tests/cli_util.h"

using namespace rrflint;
using namespace rrflint::test;

TEST_CASE("config: every key, with the line it came from", "[config]") {
  TempTree t;
  t.write(".rrflint.toml",
          "# comment\n"
          "select = [\"RRF1\", \"g10-missing-z\"]\n"
          "extend-select = [\"RRF331\"]\n"
          "ignore = [\"line-too-long\"]\n"
          "firmware = \"3.4.6\"\n"
          "board = \"duet3-6hc\"\n"
          "fail-on = \"error\"\n"
          "exclude = [\"old/**\", \"*.bak.g\"]\n"
          "docs-url = \"https://example.org/rrflint/rules\"\n"
          "[severity]\n"
          "RRF306 = \"error\"\n"
          "unknown-command = \"info\"\n"
          "[machine]\n"
          "tool-changer = true\n"
          "[per-file-ignores]\n"
          "\"macros/**\" = [\"RRF101\", \"RRF3\"]\n");
  ConfigError err;
  auto cfg = load_config(t / ".rrflint.toml", &err);
  REQUIRE(cfg);
  REQUIRE(cfg->selection.size() == 1);
  CHECK(*cfg->selection[0].select.value == std::vector<std::string>{"RRF1", "g10-missing-z"});
  CHECK(cfg->selection[0].select.origin.line == 2);
  CHECK(cfg->selection[0].extend_select.origin.line == 3);
  CHECK(cfg->selection[0].ignore.origin.line == 4);
  CHECK(cfg->firmware.value->str() == Version(3, 4, 6).str());
  CHECK(cfg->firmware.origin.line == 5);
  CHECK(*cfg->board.value == Board::Duet3_6HC);
  CHECK(*cfg->fail_on.value == Severity::Error);
  CHECK(cfg->fail_on.origin.line == 7);
  REQUIRE(cfg->exclude.size() == 2);
  CHECK(cfg->exclude[1].glob == "*.bak.g");
  CHECK(*cfg->severity.at("RRF306").value == Severity::Error);
  CHECK(*cfg->severity.at("RRF101").value == Severity::Info);  // by name, stored by code
  CHECK(cfg->severity.at("RRF101").origin.line == 12);
  CHECK(*cfg->docs_url.value == "https://example.org/rrflint/rules/");  // a trailing '/' is added
  CHECK(cfg->docs_url.origin.line == 9);
  CHECK(*cfg->tool_changer.value);
  CHECK(cfg->tool_changer.origin.line == 14);
  REQUIRE(cfg->per_file_ignores.size() == 1);
  const auto& codes = cfg->per_file_ignores[0].codes;
  CHECK(std::find(codes.begin(), codes.end(), "RRF101") != codes.end());
  CHECK(std::find(codes.begin(), codes.end(), "RRF306") != codes.end());  // the RRF3 prefix
  CHECK(cfg->per_file_ignores[0].origin.line == 16);
}

TEST_CASE("config: extend inherits, this file's settings come after", "[config]") {
  TempTree t;
  t.write("base.toml", "firmware = \"3.3\"\nignore = [\"RRF101\"]\nfail-on = \"info\"\n");
  t.write("printer/.rrflint.toml", "extend = \"../base.toml\"\nfirmware = \"3.5\"\n");
  ConfigError err;
  auto cfg = load_config(t / "printer/.rrflint.toml", &err);
  REQUIRE(cfg);
  REQUIRE(cfg->files.size() == 2);
  CHECK(cfg->files[0].filename() == "base.toml");
  CHECK(cfg->firmware.value->str() == Version(3, 5, 0).str());
  CHECK(cfg->firmware.origin.file.filename() == ".rrflint.toml");
  CHECK(*cfg->fail_on.value == Severity::Info);
  CHECK(cfg->fail_on.origin.file.filename() == "base.toml");
  REQUIRE(cfg->selection.size() == 1);
  CHECK(cfg->selection[0].ignore.origin.line == 2);
}

TEST_CASE("config: errors name the file, line and column", "[config]") {
  TempTree t;
  auto error_of = [&](const std::string& text) {
    t.write("c.toml", text);
    ConfigError err;
    auto cfg = load_config(t / "c.toml", &err);
    CHECK_FALSE(cfg);
    return err;
  };
  ConfigError e = error_of("select = [\"RRF1\"\nfirmware = \"3.5\"\n");
  CHECK(e.line >= 1);
  CHECK(e.file.filename() == "c.toml");
  e = error_of("firmware = \"3.5\"\nselcet = [\"RRF1\"]\n");
  CHECK(e.line == 2);
  CHECK(e.column == 1);
  CHECK(contains(e.message, "unknown key 'selcet'"));
  CHECK(contains(e.str(), "c.toml:2:1: unknown key 'selcet'"));
  e = error_of("[machine]\ntoolchanger = true\n");
  CHECK(e.line == 2);
  CHECK(contains(e.message, "[machine]: unknown key 'toolchanger'"));
  e = error_of("ignore = [\"RRF101\", \"no-such-rule\"]\n");
  CHECK(e.line == 1);
  CHECK(contains(e.message, "unknown rule 'no-such-rule' in 'ignore' (see `rrflint rule --all`)"));
  e = error_of("extend-select = [\"unknown-comand\"]\n");
  CHECK(contains(e.message,
                 "unknown rule 'unknown-comand' in 'extend-select'; did you mean 'unknown-command' (RRF101)?"));
  e = error_of("[severity]\nunknown-comand = \"error\"\n");
  CHECK(contains(e.message, "[severity]: unknown rule 'unknown-comand'; did you mean 'unknown-command' (RRF101)?"));
  e = error_of("firmware = 3.10\n");
  CHECK(contains(e.message, "must be a string"));
  e = error_of("[severity]\nRRF306 = \"fatal\"\n");
  CHECK(e.line == 2);
  e = error_of("fail-on = \"never\"\n");
  CHECK(contains(e.message, "'never' is not error, warning or info"));
  e = error_of("extend = \"missing.toml\"\n");
  CHECK(contains(e.message, "no such file"));
  CHECK(e.line == 1);
  e = error_of("extend = \"c.toml\"\n");
  CHECK(contains(e.message, "cycle"));
  // docs-url: a web or file URL of a folder, nothing rrflint cannot append "<name>.md" to.
  for (const char* bad :
       {"docs-url = \"docs/rules/\"\n", "docs-url = \"ftp://example.org/\"\n", "docs-url = \"https:///rules/\"\n",
        "docs-url = \"file://relative/rules\"\n", "docs-url = \"https://example.org/a b/\"\n",
        "docs-url = \"https://example.org/?page=\"\n", "docs-url = \"\"\n", "docs-url = 3\n"}) {
    INFO(bad);
    e = error_of(bad);
    CHECK(e.line == 1);
    CHECK(contains(e.message, "docs-url"));
  }
  std::string why;
  CHECK(parse_docs_url("file:///usr/share/doc/rrflint/rules", &why) == "file:///usr/share/doc/rrflint/rules/");
  CHECK(parse_docs_url("HTTPS://example.org/r/", &why) == "HTTPS://example.org/r/");
}

TEST_CASE("config: discovery walks up and stops at the repository root", "[config]") {
  TempTree t;
  t.write(".rrflint.toml", "fail-on = \"info\"\n");
  fs::create_directories(t / "repo/.git");
  t.write("repo/printer/sys/config.g", "M584 X0\n");
  CHECK_FALSE(find_config(t / "repo/printer/sys"));  // the file above the repository is not used
  t.write("repo/.rrflint.toml", "\n");
  CHECK(find_config(t / "repo/printer/sys") == t / "repo/.rrflint.toml");
  t.write("repo/printer/.rrflint.toml", "\n");
  CHECK(find_config(t / "repo/printer/sys") == t / "repo/printer/.rrflint.toml");
}

TEST_CASE("globs and path patterns", "[config]") {
  CHECK(glob_match("sys/*.g", "sys/config.g"));
  CHECK_FALSE(glob_match("sys/*.g", "sys/sub/config.g"));
  CHECK(glob_match("macros/**", "macros/a/b/c"));
  CHECK(glob_match("**/tpost?.g", "printer/sys/tpost1.g"));
  CHECK(glob_match("sys/[tT]free*.g", "sys/Tfree0.g"));
  CHECK_FALSE(glob_match("sys/[!t]*.g", "sys/tfree0.g"));
  CHECK(pattern_applies("old", "printers/old/sys/config.g"));  // a name at any depth
  CHECK(pattern_applies("*.bak.g", "sys/config.bak.g"));
  CHECK_FALSE(pattern_applies("*.bak.g", "sys/config.g"));
  CHECK(pattern_applies("printers/old", "printers/old/sys/config.g"));  // anchored; a folder covers its files
  CHECK_FALSE(pattern_applies("printers/old", "x/printers/old/sys/config.g"));
  CHECK(pattern_applies("/macros/", "macros/park.g"));
  CHECK(pattern_applies("macros/**", "macros/park.g"));
}

// ---- the CLI with config files ----

namespace {
const std::string kBad = "M584 X0 Y1 Z2\nM9999\n";  // RRF101 (warning) on line 2
}

TEST_CASE("cli config: discovered file changes the run, --isolated and --config override", "[config][cli]") {
  TempTree t;
  fs::create_directories(t / ".git");
  t.write("printer/sys/config.g", kBad);
  t.write(".rrflint.toml", "ignore = [\"unknown-command\"]\n");
  auto o = run_rrflint(t.root(), "check printer --format concise");
  CHECK(o.code == 0);
  CHECK(o.out.empty());
  o = run_rrflint(t.root(), "check printer --format concise --isolated");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "printer/sys/config.g:2:1: warning:"));
  t.write("other.toml", "fail-on = \"error\"\n");
  o = run_rrflint(t.root(), "check printer --format concise --config other.toml");
  CHECK(o.code == 0);  // the finding is a warning, and fail-on is error
  CHECK(contains(o.out, "RRF101"));
  // The command line wins over the file.
  o = run_rrflint(t.root(), "check printer --format concise --config other.toml --fail-on warning");
  CHECK(o.code == 1);
}

TEST_CASE("cli config: a bad config file is exit 2 with file:line", "[config][cli]") {
  TempTree t;
  fs::create_directories(t / ".git");
  t.write("printer/sys/config.g", kBad);
  t.write(".rrflint.toml", "firmware = \"3.5\"\nignroe = [\"RRF101\"]\n");
  auto o = run_rrflint(t.root(), "check printer");
  CHECK(o.code == 2);
  CHECK(contains(o.err, ".rrflint.toml:2:1: unknown key 'ignroe'"));
  t.write(".rrflint.toml", "select = [\n");
  o = run_rrflint(t.root(), "check printer");
  CHECK(o.code == 2);
  CHECK(contains(o.err, ".rrflint.toml:"));
  o = run_rrflint(t.root(), "config printer");
  CHECK(o.code == 2);
}

TEST_CASE("cli config: severity, per-file-ignores, exclude, tool-changer", "[config][cli]") {
  TempTree t;
  fs::create_directories(t / ".git");
  t.write("p/sys/config.g", "M584 X0 Y1 Z2\nM9999\nM98 P\"/macros/m.g\"\n");
  t.write("p/macros/m.g", "M9998\n");
  t.write("p/macros/old/x.g", "M9997\n");
  t.write(".rrflint.toml",
          "exclude = [\"old\"]\n"
          "[severity]\nunknown-command = \"error\"\n"
          "[per-file-ignores]\n\"p/macros/*.g\" = [\"RRF101\"]\n");
  auto o = run_rrflint(t.root(), "check . --format concise");
  CHECK(o.code == 1);
  CHECK(contains(o.out, "p/sys/config.g:2:1: error:"));
  CHECK_FALSE(contains(o.out, "m.g"));
  CHECK_FALSE(contains(o.out, "x.g"));
  // An SD path works in per-file-ignores too.
  t.write(".rrflint.toml", "[per-file-ignores]\n\"sys/config.g\" = [\"unknown-command\"]\n");
  o = run_rrflint(t.root(), "check . --format concise");
  CHECK_FALSE(contains(o.out, "config.g"));
  CHECK(contains(o.out, "p/macros/m.g:1:1"));
  CHECK(contains(o.out, "p/macros/old/x.g:1:1"));
}

TEST_CASE("cli config: `rrflint config` prints settings and where each came from", "[config][cli]") {
  TempTree t;
  fs::create_directories(t / ".git");
  t.write("p/sys/config.g", kBad);
  t.write("base.toml", "fail-on = \"info\"\n");
  t.write(".rrflint.toml",
          "extend = \"base.toml\"\nfirmware = \"3.5\"\nignore = [\"RRF101\"]\n[per-file-ignores]\n\"p/macros/**\" = "
          "[\"RRF1\"]\n");
  auto o = run_rrflint(t.root(), "config p --board duet2");
  CHECK(o.code == 0);
  CHECK(contains(o.out, "# config file: .rrflint.toml"));
  CHECK(contains(o.out, "#   extends: base.toml"));
  CHECK(contains(o.out, "\"3.5\""));
  CHECK(contains(o.out, "# .rrflint.toml:2"));
  CHECK(contains(o.out, "# base.toml:1"));                     // fail-on
  CHECK(contains(o.out, "# command line"));                    // board
  CHECK(contains(o.out, "# default"));                         // tool-changer
  CHECK(contains(o.out, "docs-url             = \"file://"));  // the build's default
  t.write("base.toml", "fail-on = \"info\"\ndocs-url = \"https://example.org/r/\"\n");
  o = run_rrflint(t.root(), "config p");
  CHECK(contains(o.out, "docs-url             = \"https://example.org/r/\"     # base.toml:2\n"));
  t.write("base.toml", "fail-on = \"info\"\n");
  CHECK(contains(o.out, "RRF101  unknown-command"));
  CHECK(contains(o.out, "off  warning  # ignore at .rrflint.toml:3"));
  t.write("p/macros/x.g", "G1 X0\n");
  o = run_rrflint(t.root(), "config p/macros/x.g");
  CHECK(contains(o.out, "per-file-ignores \"p/macros/**\" (.rrflint.toml:5) applies to this file"));
}
