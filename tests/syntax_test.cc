// File-level syntax findings with every rule on: a CR-only file reports nothing but RRF107 after line 1 (on
// targets where CR does not end a line), and a byte-order mark is one finding, not also a syntax error.
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "lint/engine/linter.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

std::vector<std::string> findings(const std::string& config, const std::string& firmware) {
  SourceManager sm;
  MemoryReader reader;
  reader.add("/sys/config.g", config);
  LintOptions o;
  o.select = {"ALL"};
  o.firmware = Version::parse(firmware);
  const MachineResult r = lint_machine(sm, reader, builtin_rules(), o);
  std::vector<std::string> out;
  for (const Diagnostic& d : r.diagnostics)
    out.push_back(fmt::format("{}:{}", sm.get(d.loc.file).position(d.loc.span.begin).line, d.code));
  return out;
}

}  // namespace

TEST_CASE("syntax: a CR-only file is one line to 3.5: only RRF107 is reported after line 1", "[syntax]") {
  // Line 3 is a Bad command, line 4 a G10 before any tool, line 5 an unknown code.
  const std::string text = "; config\rM83\rX10 Y20\rG10 P3 S200\rM412 S1\r";
  CHECK(findings(text, "3.5") == std::vector<std::string>{"1:RRF107"});
  // 3.4.5 ends lines at CR: every finding stays, and RRF107 is silent.
  const std::vector<std::string> old = findings(text, "3.4.5");
  CHECK(std::find(old.begin(), old.end(), "3:RRF100") != old.end());
  CHECK(std::find(old.begin(), old.end(), "5:RRF101") != old.end());
  CHECK(std::none_of(old.begin(), old.end(), [](const std::string& s) { return s.ends_with("RRF107"); }));
}

TEST_CASE("syntax: a byte-order mark is one finding", "[syntax]") {
  CHECK(findings("\xEF\xBB\xBFM83\nG21\n", "3.5") == std::vector<std::string>{"1:RRF118"});
  CHECK(findings("\xEF\xBB\xBF; config\nM83\n", "3.5") == std::vector<std::string>{"1:RRF118"});
}

TEST_CASE("syntax: invalid UTF-8 is one finding per file", "[syntax]") {
  CHECK(findings("; 60\xB0\x43\nM117 \"60\xB0\x43\"\nM117 \"ok \xC3\xA4\"\n", "3.5") ==
        std::vector<std::string>{"1:RRF119"});
  CHECK(findings("; 60\xC2\xB0\x43\nM550 P\"Drucker \xC3\xA4\"\n", "3.5").empty());
}
