// libFuzzer target: the fix round trip on a card in the card format of tests/fuzz/fuzz_input.h. Fixes (unsafe ones
// too) are applied by the code of `rrflint check --fix --unsafe-fixes` (cli/fix.cc's run_fix_rounds: round after
// round, relinting after each, at most FixOptions::max_rounds rounds). Checks: every relint passes the location
// checks; no fix adds a syntax error (RRF100) to a file (but for the CR-to-LF fix, which shows RRF lines it did not
// see), nor breaks the checksum of a line (RRF110: RRF would drop the line), nor a parse error (--fix's safety net
// never steps in); the rounds come to an end, so that a second `--fix` on the result changes nothing. Run it with
// scripts/fuzz.sh (tests/fuzz/RESULTS.md).
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

// The findings per file of the kind `is` picks.
template <class Pred>
std::map<std::string, size_t> per_file(const SourceManager& sm, const std::vector<Diagnostic>& diags, Pred is) {
  std::map<std::string, size_t> n;
  for (const Diagnostic& d : diags)
    if (is(d) && d.loc.file != kNoFile) ++n[sm.get(d.loc.file).sd_path()];
  return n;
}

std::map<std::string, size_t> syntax_errors(const SourceManager& sm, const std::vector<Diagnostic>& diags) {
  return per_file(sm, diags, [](const Diagnostic& d) { return d.code == "RRF100"; });
}

// The lines RRF drops for a checksum that does not match (RRF110 says "drops this line").
std::map<std::string, size_t> dropped_lines(const SourceManager& sm, const std::vector<Diagnostic>& diags) {
  return per_file(sm, diags, [](const Diagnostic& d) {
    return d.code == "RRF110" && d.message.find("drops this line") != std::string::npos;
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  fuzz::LintedCard card(data, size);
  SourceManager& sm = card.sources;
  MachineResult& r = card.result;
  std::map<std::string, size_t> before = syntax_errors(sm, r.diagnostics);
  std::map<std::string, size_t> dropped = dropped_lines(sm, r.diagnostics);

  cli::FixOptions fo;
  fo.unsafe = true;
  const cli::FixRounds rounds = cli::run_fix_rounds(
      sm, r, fo, [](FileId) { return true; },
      [&](const std::string& sd, const std::string& text) { card.reader.add(sd, text); },
      [&] {
        // `r` is still the lint the round's fixes came from. A CR-only file is one line to RRF 3.6: its fix
        // (RRF107) shows RRF the lines, and the errors in them.
        std::set<std::string> split;
        for (const Diagnostic& d : r.diagnostics)
          if (d.code == "RRF107" && d.fix && d.loc.file != kNoFile) split.insert(sm.get(d.loc.file).sd_path());
        MachineResult next = lint_machine(sm, card.reader, builtin_rules(), card.options);
        fuzz::check_locations(sm, next.diagnostics);
        for (const auto& [file, k] : syntax_errors(sm, next.diagnostics)) {
          size_t& was = before[file];
          if (k > was && !split.contains(file)) __builtin_trap();  // a fix made a syntax error
          was = std::max(was, k);
        }
        for (const auto& [file, k] : dropped_lines(sm, next.diagnostics)) {
          size_t& was = dropped[file];
          if (k > was && !split.contains(file)) __builtin_trap();  // a fix broke a line's checksum
          was = std::max(was, k);
        }
        return next;
      });
  // The safety net of --fix never has to step in (a round that adds a parse error is a rule's bug), and the
  // fixes settle within --fix's rounds, so that a second `--fix` on the result changes nothing.
  if (!rounds.reverted.empty() || !rounds.settled) __builtin_trap();
  return 0;
}
