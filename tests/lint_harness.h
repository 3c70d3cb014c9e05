// What the fixture runner (tests/fixtures_test.cc) and the rule-docs test (tests/rule_docs_test.cc) share: an
// in-memory SD card linted with lint_machine, its findings reduced to file, line, rule and message, and the
// words of a `; rrflint-options:` line.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lint/engine/linter.h"
#include "rules/registry.h"

namespace rrflint::harness {

/// Options of one case: the lint options, and what only the fix check uses.
struct CaseOptions {
  LintOptions lint;
  bool unsafe_fixes = false;
};

/// A finding reduced to what the tests compare.
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

/// Lints a card given as sd_path -> text ("/sys/config.g", "/macros/x.g").
std::unique_ptr<LintRun> lint_card(const std::map<std::string, std::string>& card, const LintOptions& options);

/// Lines as rrflint counts them (LF, CRLF and lone CR), as [begin, end) offsets without the terminator.
std::vector<std::pair<size_t, size_t>> split_lines(std::string_view t);

/// Reads the options of a `; rrflint-options: --firmware 3.3 --board duet2 --tool-changer --unsafe-fixes
/// --extend-select RULE` line into `o` (a `;` after the words ends them). False when the line holds no such
/// comment. Each word it does not understand adds a message to `problems`.
bool read_options_line(std::string_view line, CaseOptions& o, std::vector<std::string>& problems);

}  // namespace rrflint::harness
