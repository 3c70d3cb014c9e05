// The command documentation table (lint/boot/command_docs.h): its shape (sorted, one entry a code, short one-line
// texts, anchors that are slugs of the code's heading, upper-case parameter letters once each), that it holds only
// codes RRF has, and that every code the machine model or a rule interprets has an entry.
//
// "Interprets" is read from the code itself, so that a new handled code without an entry fails here:
// - the G codes ModelBuilder::changes_state() lets through to the model (asked for every G code and fraction);
// - the M codes of the `case N:` labels of interpret_command(), interpret_device_command() and
//   interpret_motion_command() (lint/boot/model_*.cc), found in their source text; changes_state() passes every M
//   code without a fraction, so it cannot tell which ones the model reads;
// - every ('G', N) / ('M', N) pair written in lint/ and rules/ sources (Command::is, with_code, the graph's
//   M98/M501/M505 list), the command table and this table's own files excepted;
// - the `on` list of every built-in rule (and T when a rule is called for T commands).
// The scan of the source text is checked to still find the codes it is known to find, so a rename that blinds
// it fails too.
// (Linting the fixtures and collecting the handled codes they use would miss a handled code no fixture uses
// yet; the switches themselves are the list.)
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "lint/boot/command_docs.h"
#include "lint/boot/firmware.h"
#include "lint/boot/model.h"
#include "lint/engine/rule.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

using Code = std::pair<char, int>;  // ('M', 563); fractions are handled where they occur

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  REQUIRE(in.good());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path source_dir() { return RRFLINT_SOURCE_DIR; }

/// The text of the body of the function whose definition starts with `signature`, braces matched.
std::string function_body(const std::string& text, const std::string& signature) {
  const size_t at = text.find(signature);
  INFO(signature);
  REQUIRE(at != std::string::npos);
  const size_t open = text.find('{', at);
  REQUIRE(open != std::string::npos);
  int depth = 0;
  for (size_t i = open; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"' || c == '\'') {  // a literal: skip to its closing quote ('{' is one in model_commands.cc)
      for (++i; i < text.size() && text[i] != c; ++i)
        if (text[i] == '\\') ++i;
    } else if (text.compare(i, 2, "//") == 0) {
      i = text.find('\n', i);
      if (i == std::string::npos) break;
    } else if (c == '{') {
      ++depth;
    } else if (c == '}' && --depth == 0) {
      return text.substr(open, i - open + 1);
    }
  }
  FAIL("unbalanced braces after " << signature);
  return {};
}

/// The M codes of the `case N:` labels of the model's command switches.
std::set<int> model_switch_codes() {
  const std::pair<const char*, const char*> kSwitches[] = {
      {"lint/boot/model_commands.cc", "void interpret_command("},
      {"lint/boot/model_devices.cc", "void interpret_device_command("},
      {"lint/boot/model_motion.cc", "void interpret_motion_command("},
  };
  std::set<int> codes;
  const std::regex label(R"(\bcase\s+(\d+)\s*:)");
  for (const auto& [file, signature] : kSwitches) {
    const std::string body = function_body(read_file(source_dir() / file), signature);
    for (std::sregex_iterator it(body.begin(), body.end(), label), end; it != end; ++it)
      codes.insert(std::stoi((*it)[1]));
  }
  return codes;
}

/// Every ('G', N) / ('M', N) written in the sources of lint/ and rules/.
std::set<Code> source_code_pairs() {
  std::set<Code> codes;
  const std::regex pair(R"('([GM])',\s*(\d+)\b)");
  for (const char* dir : {"lint", "rules"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(source_dir() / dir)) {
      const std::string name = e.path().filename().string();
      const std::string ext = e.path().extension().string();
      if (!e.is_regular_file() || (ext != ".cc" && ext != ".h") || name.rfind("command_docs", 0) == 0) continue;
      const std::string text = read_file(e.path());
      for (std::sregex_iterator it(text.begin(), text.end(), pair), end; it != end; ++it)
        codes.insert({(*it)[1].str()[0], std::stoi((*it)[2])});
    }
  return codes;
}

/// The anchor prefix of a code, by the slug rule of command_docs.cc: "M569.1" -> "m5691".
std::string slug_of_name(const std::string& name) {
  std::string s;
  for (char c : name)
    if (std::isalnum(static_cast<unsigned char>(c)))
      s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string names(const std::vector<std::string>& v) { return fmt::format("{}", fmt::join(v, " ")); }

}  // namespace

TEST_CASE("command docs: sorted, one entry a code, and found by command_doc", "[command_docs]") {
  const auto docs = command_docs();
  REQUIRE(docs.size() >= 100);
  auto key = [](const CommandDoc& d) { return std::tuple(d.letter, d.number, d.fraction); };
  for (size_t i = 1; i < docs.size(); ++i) {
    INFO(command_name(docs[i - 1]) << " then " << command_name(docs[i]));
    CHECK(key(docs[i - 1]) < key(docs[i]));
  }
  for (const CommandDoc& d : docs) CHECK(command_doc(d.letter, d.number, d.fraction) == &d);
  CHECK(command_doc('M', 9999, -1) == nullptr);
  CHECK(command_doc('G', 10, 1) == nullptr);  // G10.1 is not G10
  REQUIRE(command_doc('M', 563, -1) != nullptr);
  CHECK(command_doc('M', 563, -1)->title == "Define or remove a tool");
  // Every T command is the one command T.
  REQUIRE(command_doc('T', 3, -1) != nullptr);
  CHECK(command_doc('T', 3, -1) == command_doc('T', -1, -1));
  CHECK(command_name(*command_doc('T', 0, -1)) == "T");
  CHECK(command_name(*command_doc('M', 569, 1)) == "M569.1");
  CHECK(command_doc_url(*command_doc('M', 563, -1)) ==
        "https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool");
}

TEST_CASE("command docs: every entry has short one-line texts and an anchor of its own code", "[command_docs]") {
  const std::regex slug("[a-z0-9]+(-[a-z0-9_~]+)*");
  for (const CommandDoc& d : command_docs()) {
    const std::string name = command_name(d);
    INFO(name);
    CHECK(std::string_view("GMT").find(d.letter) != std::string_view::npos);
    CHECK(!d.title.empty());
    CHECK(d.title.size() <= 60);
    CHECK(d.title.find('\n') == std::string_view::npos);
    CHECK(!d.summary.empty());
    CHECK(d.summary.size() <= 200);
    CHECK(d.summary.find('\n') == std::string_view::npos);
    CHECK(d.summary.back() == '.');
    const std::string anchor(d.anchor);
    CHECK(std::regex_match(anchor, slug));
    CHECK(anchor.rfind(slug_of_name(name) + "-", 0) == 0);  // the heading starts "M569.1: ..."
    std::set<char> seen;
    for (const ParamDoc& p : d.params) {
      INFO("parameter " << p.letter);
      CHECK(p.letter >= 'A');
      CHECK(p.letter <= 'Z');
      CHECK(seen.insert(p.letter).second);
      CHECK(!p.text.empty());
      CHECK(p.text.size() <= 90);
      CHECK(p.text.find('\n') == std::string_view::npos);
    }
  }
}

TEST_CASE("command docs: only codes RRF has", "[command_docs]") {
  // A code RRF lacks in every version rrflint knows (lint/boot/command_table.inc) gets no entry.
  for (const CommandDoc& d : command_docs()) {
    INFO(command_name(d));
    if (d.letter == 'T') CHECK(d.number == -1);
    else CHECK(code_versions(d.letter, d.number, d.fraction) != 0);
  }
}

TEST_CASE("command docs: every code the model and the rules interpret has an entry", "[command_docs]") {
  std::vector<std::string> missing;
  auto need = [&](char letter, int number, int fraction, const char* why) {
    if (!command_doc(letter, number, fraction))
      missing.push_back(
          fmt::format("{}{}{} ({})", letter, number, fraction < 0 ? "" : fmt::format(".{}", fraction), why));
  };
  for (char letter : {'G', 'M'})
    for (int n = 0; n < 1000; ++n)
      for (int f = -1; f <= 9; ++f)
        if (letter == 'G' && ModelBuilder::changes_state(CommandTable::Code{letter, n, static_cast<int8_t>(f), 0}))
          need(letter, n, f, "ModelBuilder::changes_state");

  const std::set<int> switches = model_switch_codes();
  for (int n : {92, 98, 106, 140, 143, 308, 350, 563, 568, 574, 584, 950}) {
    INFO("the scan of the model's switches no longer finds M" << n);
    CHECK(switches.count(n) == 1);
  }
  for (int n : switches) need('M', n, -1, "a case of the model's switches");
  // The forward pass steps the model only for the codes changes_state() lets through: exactly the switches' M
  // codes (a case missing there is never reached; an extra code costs a decode per command for nothing).
  for (int n = 0; n < 10000; ++n)
    for (int f = -1; f <= 9; ++f) {
      INFO("M" << n << (f < 0 ? "" : "." + std::to_string(f)));
      CHECK(ModelBuilder::changes_state(CommandTable::Code{'M', n, static_cast<int8_t>(f), 0}) ==
            (f < 0 && switches.count(n) == 1));
    }

  const std::set<Code> pairs = source_code_pairs();
  for (Code c : {Code{'M', 98}, Code{'M', 501}, Code{'M', 505}, Code{'G', 10}, Code{'M', 911}}) {
    INFO("the scan of the sources no longer finds " << c.first << c.second);
    CHECK(pairs.count(c) == 1);
  }
  for (const auto& [letter, number] : pairs) need(letter, number, -1, "named in lint/ or rules/");

  size_t triggers = 0;
  for (const Rule* r : builtin_rules().all()) {
    Triggers t;
    REQUIRE(parse_triggers(r->on, t));
    triggers += t.codes.size();
    for (const auto& [letter, number] : t.codes) need(letter, number, -1, "a rule's `on` list");
    if (t.any_t && !command_doc('T', 0, -1)) missing.push_back("T (a rule's `on` list)");
  }
  CHECK(triggers > 0);
  INFO("no entry in lint/boot/command_docs_*.cc: " << names(missing));
  CHECK(missing.empty());
}

TEST_CASE("command docs: the codes config.g files commonly use have entries", "[command_docs]") {
  // The everyday codes of a config.g, whether or not the model reads them: hover text should not stop at the
  // commands rrflint understands best.
  const char* kCommon[] = {"G0",   "G1",   "G4",   "G10",  "G11",  "G21",  "G28",  "G29",  "G30",  "G31",  "G32",
                           "G90",  "G91",  "M0",   "M98",  "M80",  "M81",  "M82",  "M83",  "M92",  "M104", "M106",
                           "M109", "M116", "M140", "M143", "M190", "M201", "M203", "M204", "M205", "M207", "M208",
                           "M302", "M303", "M307", "M308", "M350", "M376", "M400", "M501", "M540", "M550", "M551",
                           "M552", "M553", "M554", "M557", "M558", "M563", "M564", "M566", "M567", "M568", "M569",
                           "M570", "M572", "M574", "M575", "M584", "M586", "M591", "M593", "M665", "M669", "M671",
                           "M906", "M911", "M913", "M915", "M917", "M929", "M950", "M999", "T"};
  std::vector<std::string> missing;
  for (const char* name : kCommon) {
    const std::string s = name;
    const char letter = s[0];
    const int number = s.size() > 1 ? std::stoi(s.substr(1)) : -1;
    if (!command_doc(letter, number, -1)) missing.push_back(s);
  }
  INFO("no entry: " << names(missing));
  CHECK(missing.empty());
}
