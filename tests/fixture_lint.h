// Linting an in-memory SD card the way the fixture runner does, and rendering its findings as `rrflint check`
// prints them in the text format. Shared by tests/fixtures_test.cc and any test that lints a fixture-like card.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lint/engine/linter.h"
#include "rules/registry.h"

namespace rrflint::fixture {

/// A finding reduced to what the fixtures compare.
struct Finding {
  std::string sd_path;
  uint32_t line = 0;    // 1-based
  uint32_t column = 0;  // 1-based code points, as the text renderer prints it
  std::string rule;
  std::string message;
  const Diagnostic* diag = nullptr;  // into LintRun::result
};

struct LintRun {
  SourceManager sources;
  MachineResult result;
  std::vector<Finding> findings;  // in the order of result.diagnostics
};

/// Lints a card given as sd_path ("/sys/config.g") -> text. The display paths are the SD paths without the
/// leading '/' ("sys/config.g").
std::unique_ptr<LintRun> lint_card(const std::map<std::string, std::string>& card, const LintOptions& options);

/// `path:line:col: message` of every finding, in order: for comparing two runs.
std::vector<std::string> finding_lines(const LintRun& run);

/// The text report of a run, as `rrflint check --color never` prints it for this card: the findings sorted by path
/// and position, each with its snippet, notes and fix preview, then the summary and the rule links.
std::string render_text_report(const LintRun& run, bool unsafe_fixes = false);

}  // namespace rrflint::fixture
