// Machine formats: SARIF 2.1.0 (validated against the official schema when it is available, and checked field
// by field against GitHub code scanning's requirements), GitHub workflow commands, json and json-lines.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "lint/engine/rule.h"
#include "lint/render/json_writer.h"
#include "lint/render/render.h"
#include "rules/registry.h"
#include "tests/cli_util.h"

using namespace rrflint;
using namespace rrflint::test;
using nlohmann::json;

namespace {

// A fixed set of findings: one with a note in another file and a fix, one multi-line, one info, in a file
// whose name has a space.
struct Sample {
  SourceManager sm;
  std::vector<Diagnostic> diags;
  Sample() {
    const SourceFile& cfg =
        sm.add("printer/sys/config.g", "/sys/config.g", "M584 X0 Y1 Z2\nG10 P1 X0 Y0\nM563 P1 D0 H1\nM9999 ; odd\n");
    const SourceFile& standby = sm.add("printer/sys/all standby.g", "/sys/all standby.g", "M9998\nM9997\n");
    Diagnostic a;
    a.code = "RRF301";
    a.name = "g10-tool-before-definition";
    a.severity = Severity::Error;
    a.loc = Location{cfg.id(), Span{14, 26}};  // G10 P1 X0 Y0
    a.message = "'G10 P1' names tool 1, which does not exist yet";
    a.notes.push_back(Note{Location{standby.id(), Span{0, 5}}, "tool 1 is created here"});
    Fix f;
    f.title = "append 'Z0'";
    f.edits.push_back(Edit{Location{cfg.id(), Span{26, 26}}, " Z0"});
    a.fix = f;
    diags.push_back(a);
    Diagnostic b;
    b.code = "RRF101";
    b.name = "unknown-command";
    b.severity = Severity::Warning;
    b.loc = Location{standby.id(), Span{0, 11}};  // spans two lines
    b.message = "'M9998' is not a command: 50% of 'odd', really";
    diags.push_back(b);
    Diagnostic c;
    c.code = "RRF900";
    c.name = "unused-suppression";
    c.severity = Severity::Info;
    c.loc = Location{cfg.id(), Span{41, 46}};
    c.message = "unused suppression";
    diags.push_back(c);
  }
};

constexpr const char* kWebDocs = "https://docs.example.org/rrflint/rules/";

json sarif_of(const Sample& s, const fs::path& base = "/repo", const fs::path& cwd = "/repo",
              const std::string& docs_base = kWebDocs) {
  RenderOptions o;
  o.rules = &builtin_rules();
  o.uri_base = base;
  o.cwd = cwd;
  o.docs_base = docs_base;
  std::ostringstream os;
  render_sarif(os, s.sm, s.diags, o);
  return json::parse(os.str());
}

}  // namespace

TEST_CASE("sarif: GitHub code scanning's required fields", "[sarif]") {
  Sample s;
  json doc = sarif_of(s);
  CHECK(doc["$schema"] == "https://json.schemastore.org/sarif-2.1.0.json");
  CHECK(doc["version"] == "2.1.0");
  REQUIRE(doc["runs"].size() == 1);
  const json& run = doc["runs"][0];
  CHECK(run["tool"]["driver"]["name"] == "rrflint");
  CHECK(run["tool"]["driver"]["version"] == RRFLINT_VERSION);
  const json& rules = run["tool"]["driver"]["rules"];
  REQUIRE(rules.size() == builtin_rules().all().size());
  std::set<std::string> ids;
  for (const json& r : rules) {
    INFO(r["id"]);
    ids.insert(r["id"].get<std::string>());
    CHECK_FALSE(r["id"].get<std::string>().empty());
    CHECK_FALSE(r["name"].get<std::string>().empty());
    CHECK(r["name"].get<std::string>().size() <= 255);
    CHECK_FALSE(r["shortDescription"]["text"].get<std::string>().empty());
    CHECK_FALSE(r["fullDescription"]["text"].get<std::string>().empty());
    CHECK_FALSE(r["help"]["text"].get<std::string>().empty());
    CHECK(contains(r["help"]["markdown"].get<std::string>(), "## What it does"));
    CHECK(r["helpUri"] == kWebDocs + r["name"].get<std::string>() + ".md");
    CHECK(std::set<std::string>{"note", "warning", "error"}.count(r["defaultConfiguration"]["level"]));
    CHECK(std::set<std::string>{"recommendation", "warning", "error"}.count(r["properties"]["problem.severity"]));
  }
  CHECK(ids.size() == rules.size());
  const json& results = run["results"];
  REQUIRE(results.size() == 3);
  for (const json& res : results) {
    CHECK_FALSE(res["message"]["text"].get<std::string>().empty());
    REQUIRE(res["locations"].size() >= 1);
    CHECK(res["locations"].size() <= 10);
    CHECK(rules[res["ruleIndex"].get<size_t>()]["id"] == res["ruleId"]);
    const std::string hash = res["partialFingerprints"]["primaryLocationLineHash"];
    CHECK(hash.size() > 3);
    CHECK(contains(hash, ":"));
    const json& region = res["locations"][0]["physicalLocation"]["region"];
    CHECK(region["startLine"].get<int>() >= 1);
    CHECK(region["startColumn"].get<int>() >= 1);
    CHECK(region.contains("endLine"));
    CHECK(region.contains("endColumn"));
  }
  // Levels, exclusive end columns, repository-relative and percent-encoded URIs.
  CHECK(results[0]["level"] == "error");
  CHECK(results[1]["level"] == "warning");
  CHECK(results[2]["level"] == "note");
  const json& loc0 = results[0]["locations"][0]["physicalLocation"];
  CHECK(loc0["artifactLocation"]["uri"] == "printer/sys/config.g");
  CHECK(loc0["artifactLocation"]["uriBaseId"] == "%SRCROOT%");
  CHECK(loc0["region"] == json{{"startLine", 2}, {"startColumn", 1}, {"endLine", 2}, {"endColumn", 13}});
  CHECK(results[1]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "printer/sys/all%20standby.g");
  CHECK(results[1]["locations"][0]["physicalLocation"]["region"]["endLine"] == 2);
  CHECK(run["originalUriBaseIds"]["%SRCROOT%"]["uri"] == "file:///repo/");
  CHECK(run["columnKind"] == "unicodeCodePoints");
  // Notes are related locations, fixes are fixes.
  const json& rel = results[0]["relatedLocations"];
  REQUIRE(rel.size() == 1);
  CHECK(rel[0]["id"] == 1);
  CHECK(rel[0]["message"]["text"] == "tool 1 is created here");
  CHECK(rel[0]["physicalLocation"]["artifactLocation"]["uri"] == "printer/sys/all%20standby.g");
  const json& fix = results[0]["fixes"][0];
  CHECK(fix["description"]["text"] == "append 'Z0'");
  const json& rep = fix["artifactChanges"][0]["replacements"][0];
  CHECK(fix["artifactChanges"][0]["artifactLocation"]["uri"] == "printer/sys/config.g");
  CHECK(rep["deletedRegion"] == json{{"startLine", 2}, {"startColumn", 13}, {"endLine", 2}, {"endColumn", 13}});
  CHECK(rep["insertedContent"]["text"] == " Z0");
}

TEST_CASE("sarif: URIs are relative to the base even from a subfolder, outside it they are file URIs", "[sarif]") {
  Sample s;
  json doc = sarif_of(s, "/repo", "/repo/configs");
  CHECK(doc["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] ==
        "configs/printer/sys/config.g");
  doc = sarif_of(s, "/elsewhere", "/repo");
  const json& al = doc["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"];
  CHECK(al["uri"] == "file:///repo/printer/sys/config.g");
  CHECK_FALSE(al.contains("uriBaseId"));
}

TEST_CASE("sarif: fingerprints follow the line's text, not its number", "[sarif]") {
  SourceManager sm;
  const SourceFile& a = sm.add("a.g", "/sys/a.g", "M9999\nM9999\n");
  const SourceFile& b = sm.add("b.g", "/sys/b.g", "; moved down\n  M9999\nM9999\n");
  auto diag = [](FileId f, uint32_t at) {
    Diagnostic d;
    d.code = "RRF101";
    d.name = "unknown-command";
    d.loc = Location{f, Span{at, at + 5}};
    d.message = "m";
    return d;
  };
  RenderOptions o;
  o.rules = &builtin_rules();
  o.uri_base = o.cwd = "/r";
  auto hashes = [&](std::vector<Diagnostic> ds) {
    std::ostringstream os;
    render_sarif(os, sm, ds, o);
    std::vector<std::string> h;
    const json doc = json::parse(os.str());
    for (const json& r : doc["runs"][0]["results"]) h.push_back(r["partialFingerprints"]["primaryLocationLineHash"]);
    return h;
  };
  auto ha = hashes({diag(a.id(), 0), diag(a.id(), 6)});
  auto hb = hashes({diag(b.id(), 15), diag(b.id(), 21)});
  CHECK(ha == hb);
  CHECK(ha[0].ends_with(":1"));
  CHECK(ha[1].ends_with(":2"));
}

TEST_CASE("gitlab: fingerprints stay unique for files whose paths show alike", "[gitlab]") {
  // Names that differ only in invalid UTF-8 show alike (U+FFFD); "x/./c.g" and "x/c.g" name one path. Found by
  // fuzz_render: two findings on the same line text got one fingerprint, and GitLab would have kept one.
  SourceManager sm;
  std::vector<Diagnostic> ds;
  for (const char* name : {"x/a\x95.g", "x/a\x96.g", "x/./c.g", "x/c.g", "x/plain.g"}) {
    const SourceFile& f = sm.add(name, std::string("/sys/") + name, "M9999\n");
    Diagnostic d;
    d.code = "RRF101";
    d.name = "unknown-command";
    d.loc = Location{f.id(), Span{0, 5}};
    d.message = "m";
    ds.push_back(d);
  }
  RenderOptions o;
  o.uri_base = o.cwd = "/r";
  std::ostringstream os;
  render_gitlab(os, sm, ds, o);
  const json doc = json::parse(os.str());
  REQUIRE(doc.size() == 5);
  std::set<std::string> fingerprints;
  for (const json& e : doc) CHECK(fingerprints.insert(e["fingerprint"].get<std::string>()).second);
  CHECK(doc[0]["location"]["path"] == doc[1]["location"]["path"]);  // shown alike
}

TEST_CASE("sarif: valid against the SARIF 2.1.0 schema", "[sarif][schema]") {
  const fs::path schema = fs::path(RRFLINT_SOURCE_DIR) / "../shared/schemas/sarif-schema-2.1.0.json";
  if (!fs::exists(schema)) {
    RRFLINT_SKIPPED("SARIF schema validation: " << schema.string() << " not found");
    return;
  }
  if (std::system("/usr/bin/python3 -c 'import jsonschema' >/dev/null 2>&1") != 0) {
    RRFLINT_SKIPPED(
        "SARIF schema validation: /usr/bin/python3 with jsonschema not available "
        "(scripts/setup.sh --test installs python3-jsonschema)");
    return;
  }
  TempTree t;
  Sample s;
  RenderOptions o;
  o.rules = &builtin_rules();
  o.uri_base = o.cwd = "/repo";
  {
    std::ofstream out(t / "out.sarif");
    render_sarif(out, s.sm, s.diags, o);
  }
  {
    std::ofstream out(t / "empty.sarif");
    render_sarif(out, s.sm, {}, o);
  }
  t.write("validate.py",
          "import json, sys, jsonschema\n"
          "schema = json.load(open(sys.argv[1]))\n"
          "cls = jsonschema.validators.validator_for(schema)\n"
          "cls.check_schema(schema)\n"
          "bad = 0\n"
          "for p in sys.argv[2:]:\n"
          "    for e in cls(schema).iter_errors(json.load(open(p))):\n"
          "        bad += 1\n"
          "        print(p, list(e.absolute_path), e.message)\n"
          "sys.exit(1 if bad else 0)\n");
  const std::string cmd = "/usr/bin/python3 " + shell_quote((t / "validate.py").string()) + " " +
                          shell_quote(schema.string()) + " " + shell_quote((t / "out.sarif").string()) + " " +
                          shell_quote((t / "empty.sarif").string()) + " > " + shell_quote((t / "log").string()) +
                          " 2>&1";
  const int rc = std::system(cmd.c_str());
  INFO(t.read("log"));
  CHECK(rc == 0);
}

TEST_CASE("github: escaping, order, multi-line findings", "[github]") {
  Sample s;
  RenderOptions o;
  o.rules = &builtin_rules();
  o.uri_base = o.cwd = "/repo";
  o.docs_base = kWebDocs;
  std::ostringstream os;
  render_github(os, s.sm, s.diags, o);
  std::vector<std::string> lines;
  std::istringstream in(os.str());
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].starts_with(
      "::error file=printer/sys/config.g,line=2,endLine=2,col=1,endColumn=13,title=rrflint RRF301 "
      "g10-tool-before-definition::'G10 P1' names tool 1, which does not exist yet%0Anote: printer/sys/all "
      "standby.g:1:1: tool 1 is created here%0Ahelp: append 'Z0' (rrflint check --fix)%0A"
      "https://docs.example.org/rrflint/rules/g10-tool-before-definition.md"));
  // Multi-line: no col/endColumn; '%' in the message is escaped.
  CHECK(lines[1].starts_with(
      "::warning file=printer/sys/all standby.g,line=1,endLine=2,title=rrflint RRF101 unknown-command::'M9998' is "
      "not a command: 50%25 of 'odd', really%0A"));
  CHECK(lines[2].starts_with("::notice file=printer/sys/config.g,line=4,endLine=4,col=1,endColumn=6,"));
  // A local (file://) docs base would not open on github.com: the annotation names the command instead.
  o.docs_base = "file:///usr/share/doc/rrflint/rules/";
  std::ostringstream local;
  render_github(local, s.sm, s.diags, o);
  CHECK_FALSE(contains(local.str(), "file://"));
  CHECK(contains(local.str(), "(rrflint check --fix)%0Arrflint rule RRF301\n"));
}

TEST_CASE("sarif: helpUri only for a web docs base, and never an informationUri", "[sarif]") {
  Sample s;
  for (const std::string base : {"file:///usr/share/doc/rrflint/rules/", ""}) {
    INFO(base);
    json doc = sarif_of(s, "/repo", "/repo", base);
    const json& driver = doc["runs"][0]["tool"]["driver"];
    CHECK_FALSE(driver.contains("informationUri"));
    for (const json& r : driver["rules"]) {
      CHECK_FALSE(r.contains("helpUri"));
      CHECK(contains(r["help"]["markdown"].get<std::string>(), "## What it does"));  // the page travels inline
    }
  }
  json doc = sarif_of(s, "/repo", "/repo", "http://intranet/rrflint/rules");
  CHECK(doc["runs"][0]["tool"]["driver"]["rules"][0]["helpUri"].get<std::string>().starts_with(
      "http://intranet/rrflint/rules/"));
  CHECK_FALSE(doc["runs"][0]["tool"]["driver"].contains("informationUri"));
}

TEST_CASE("github: property values escape ':' and ','", "[github]") {
  SourceManager sm;
  const SourceFile& f = sm.add("filaments/ABS, ASA: hot/config.g", "/filaments/x/config.g", "M9999\n");
  Diagnostic d;
  d.code = "RRF101";
  d.name = "unknown-command";
  d.loc = Location{f.id(), Span{0, 5}};
  d.message = "line one\nline two\r";
  RenderOptions o;
  o.rules = &builtin_rules();
  o.uri_base = o.cwd = "/repo";
  std::ostringstream os;
  render_github(os, sm, {d}, o);
  const std::string out = os.str();
  CHECK(contains(out, "file=filaments/ABS%2C ASA%3A hot/config.g,"));
  // sanitize() already replaced the control characters of the message; nothing raw can break the line.
  CHECK(std::count(out.begin(), out.end(), '\n') == 1);
}

TEST_CASE("github: past GitHub's limits, errors first, the rest in a group and a summary", "[github]") {
  SourceManager sm;
  std::string text;
  for (int i = 0; i < 40; ++i) text += "M9999\n";
  const SourceFile& f = sm.add("sys/config.g", "/sys/config.g", text);
  std::vector<Diagnostic> ds;
  for (int i = 0; i < 40; ++i) {
    Diagnostic d;
    d.code = "RRF101";
    d.name = "unknown-command";
    d.severity = i < 12 ? Severity::Info : i < 25 ? Severity::Warning : Severity::Error;  // 12 infos, 13 w, 15 e
    d.loc = Location{f.id(), Span{static_cast<uint32_t>(i * 6), static_cast<uint32_t>(i * 6 + 5)}};
    d.message = "m";
    ds.push_back(d);
  }
  RenderOptions o;
  o.rules = &builtin_rules();
  o.uri_base = o.cwd = "/r";
  std::ostringstream os;
  render_github(os, sm, ds, o);
  std::vector<std::string> lines;
  std::istringstream in(os.str());
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  auto count_prefix = [&](std::string_view p) {
    return std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.starts_with(p); });
  };
  CHECK(count_prefix("::error ") == 10);
  CHECK(count_prefix("::warning ") == 10);
  CHECK(count_prefix("::notice file=") == 9);  // one notice slot is kept for the summary
  CHECK(lines[0].starts_with("::error "));
  CHECK(lines[10].starts_with("::warning "));
  CHECK(count_prefix("::group::rrflint: 11 more findings") == 1);
  CHECK(count_prefix("sys/config.g:") == 11);
  CHECK(lines.back().starts_with("::notice title=rrflint::11 of 40 findings are not shown as annotations"));
}

TEST_CASE("json-lines: one object per line, the same objects as json", "[json]") {
  Sample s;
  RenderOptions o;
  o.rules = &builtin_rules();
  std::ostringstream jl, js;
  render_json_lines(jl, s.sm, s.diags, o);
  render_json(js, s.sm, s.diags, o);
  json doc = json::parse(js.str());
  CHECK(doc["version"] == 1);
  std::istringstream in(jl.str());
  size_t n = 0;
  for (std::string line; std::getline(in, line); ++n) CHECK(json::parse(line) == doc["diagnostics"][n]);
  CHECK(n == 3);
  CHECK(doc["diagnostics"][0]["url"] == "docs/rules/g10-tool-before-definition.md");  // no base: the repository path
  o.docs_base = kWebDocs;
  std::ostringstream with_base;
  render_json(with_base, s.sm, s.diags, o);
  CHECK(json::parse(with_base.str())["diagnostics"][0]["url"] == rule_url(kWebDocs, "g10-tool-before-definition"));
  CHECK(doc["diagnostics"][0]["notes"][0]["end_column"] == 6);
}

TEST_CASE("json, json-lines: a large report written in pieces on several threads is the same bytes", "[json]") {
  Sample s;
  RenderOptions o;
  o.rules = &builtin_rules();
  // Enough findings for several rounds of pieces, and a count that leaves a short last piece.
  std::vector<Diagnostic> many;
  for (size_t i = 0; i < 23'123; ++i) many.push_back(s.diags[i % s.diags.size()]);
  for (const std::vector<Diagnostic>* diags : {&many, &s.diags}) {
    std::string one_json, one_lines;
    for (unsigned threads : {1u, 2u, 3u, 8u}) {
      INFO("threads " << threads << ", findings " << diags->size());
      o.threads = threads;
      std::ostringstream js, jl;
      render_json(js, s.sm, *diags, o);
      render_json_lines(jl, s.sm, *diags, o);
      if (threads == 1) {
        one_json = js.str();
        one_lines = jl.str();
        CHECK(json::parse(one_json)["diagnostics"].size() == diags->size());
        continue;
      }
      CHECK(js.str() == one_json);
      CHECK(jl.str() == one_lines);
    }
  }
  // No findings: an empty array, whatever the threads.
  o.threads = 4;
  std::ostringstream none;
  render_json(none, s.sm, {}, o);
  CHECK(none.str().starts_with("{\n  \"diagnostics\": [],\n"));
}

TEST_CASE("json, json-lines: a fix's text keeps its line endings, invalid UTF-8 becomes U+FFFD", "[json]") {
  // The replacement of an inserted line (RRF307's M568) used to come out with U+FFFD for its "\n": a tool that
  // applied the JSON's fixes would have joined the lines with garbage. SARIF always kept it.
  Sample s;
  s.diags[0].fix->edits[0].replacement = "\r\nM568 P1 S0\x01\tx\xff";
  s.diags[0].message = "a message with a line\nfeed";
  RenderOptions o;
  o.rules = &builtin_rules();
  std::ostringstream jl, js;
  render_json_lines(jl, s.sm, s.diags, o);
  render_json(js, s.sm, s.diags, o);
  const json doc = json::parse(js.str());
  CHECK(doc["diagnostics"][0]["fix"]["edits"][0]["replacement"] == "\r\nM568 P1 S0\x01\tx\xEF\xBF\xBD");
  CHECK(doc["diagnostics"][0]["message"] ==
        "a message with a line\xEF\xBF\xBD"
        "feed");  // messages: as before
  std::istringstream in(jl.str());
  std::string line;
  std::getline(in, line);
  CHECK(json::parse(line)["fix"]["edits"][0]["replacement"] == "\r\nM568 P1 S0\x01\tx\xEF\xBF\xBD");
  CHECK(valid_utf8("a\nb\xc3") == "a\nb\xEF\xBF\xBD");
  CHECK(sanitize("a\nb\xc3") ==
        "a\xEF\xBF\xBD"
        "b\xEF\xBF\xBD");
}

TEST_CASE("sanitize and the JSON writer: a byte that matters anywhere in a string of any length", "[json][render]") {
  // Both skip plain text 8 bytes at a time: put the byte at every place of strings up to 3 words long.
  const std::string fffd = "\xEF\xBF\xBD";
  // What sanitize makes of each: a control byte (not a tab) becomes U+FFFD, so does each byte of an invalid
  // sequence; the rest is kept.
  enum Kind { Kept, Control, Invalid };
  std::vector<std::pair<std::string, Kind>> cases;
  for (const char* b : {"\x01", "\x1f", "\x7f", "\n"}) cases.emplace_back(b, Control);
  for (const char* b : {"\t", "\"", "\\", " ", "~", "\xC3\xA9", "\xF0\x9F\x98\x80"}) cases.emplace_back(b, Kept);
  for (const char* b : {"\xff", "\x80", "\xC3", "\xED\xA0\x80"}) cases.emplace_back(b, Invalid);
  for (size_t len = 0; len <= 24; ++len)
    for (size_t pos = 0; pos <= len; ++pos)
      for (const auto& [bytes, kind] : cases) {
        const std::string s = std::string(pos, 'a') + bytes + std::string(len - pos, 'b');
        std::string middle = bytes;
        if (kind == Control) middle = fffd;
        if (kind == Invalid) middle.clear();
        for (size_t k = 0; kind == Invalid && k < bytes.size(); ++k) middle += fffd;
        const std::string want = std::string(pos, 'a') + middle + std::string(len - pos, 'b');
        INFO("len " << len << ", pos " << pos << ", bytes " << json(valid_utf8(bytes)).dump());
        REQUIRE(sanitize(s) == want);
        REQUIRE(valid_utf8(s) == (kind == Invalid ? want : s));
        std::string out;
        JsonWriter(out, 2).value(sanitize(s));
        REQUIRE(out == json(sanitize(s)).dump());
        out.clear();
        JsonWriter(out, 2).value(valid_utf8(s));
        REQUIRE(out == json(valid_utf8(s)).dump());
      }
}
