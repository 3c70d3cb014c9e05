// libFuzzer target: the fix round trip on a card in the card format of tests/fuzz/fuzz_input.h. Fixes (unsafe ones
// too) are applied as `rrflint check --fix --unsafe-fixes` applies them (cli/fix.cc's apply_fixes, round after
// round, relinting after each, at most FixOptions::max_rounds rounds). Checks: every relint passes the location
// checks; no fix adds a syntax error (RRF100) to a file (but for the CR-to-LF fix, which shows RRF lines it did not
// see); the rounds come to an end, so that a second `--fix` on the result changes nothing. Run it with scripts/fuzz.sh
// (tests/fuzz/RESULTS.md).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>

#include "cli/cli.h"
#include "tests/fuzz/fuzz_input.h"

using namespace rrflint;

namespace {

std::map<std::string, size_t> syntax_errors(const SourceManager& sm, const std::vector<Diagnostic>& diags) {
  std::map<std::string, size_t> n;
  for (const Diagnostic& d : diags)
    if (d.code == "RRF100" && d.loc.file != kNoFile) ++n[sm.get(d.loc.file).sd_path()];
  return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  fuzz::LintedCard card(data, size);
  SourceManager& sm = card.sources;
  MachineResult& r = card.result;
  std::map<std::string, size_t> before = syntax_errors(sm, r.diagnostics);

  cli::FixOptions fo;
  fo.unsafe = true;
  // One round more than --fix runs: that round is the second `--fix`, which must find nothing left to apply.
  for (int round = 0; round <= fo.max_rounds; ++round) {
    std::map<FileId, std::string> texts;
    const size_t n = cli::apply_fixes(
        sm, r.diagnostics, fo, [](FileId) { return true; }, texts);
    if (n == 0) return 0;
    if (round == fo.max_rounds) __builtin_trap();  // the fixes do not settle
    // A CR-only file is one line to RRF 3.6: its fix (RRF107) shows RRF the lines, and the errors in them.
    std::set<std::string> split;
    for (const Diagnostic& d : r.diagnostics)
      if (d.code == "RRF107" && d.fix && d.loc.file != kNoFile) split.insert(sm.get(d.loc.file).sd_path());
    for (auto& [id, text] : texts) card.reader.add(sm.get(id).sd_path(), text);
    r = lint_machine(sm, card.reader, builtin_rules(), card.options);
    fuzz::check_locations(sm, r.diagnostics);
    for (const auto& [file, k] : syntax_errors(sm, r.diagnostics)) {
      size_t& was = before[file];
      if (k > was && !split.contains(file)) __builtin_trap();  // a fix made a syntax error
      was = std::max(was, k);
    }
  }
  return 0;
}
