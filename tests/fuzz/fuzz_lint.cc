// libFuzzer target: lints arbitrary bytes as an SD card of two files with every rule enabled, renders the
// findings as text and JSON, and applies every fix. Build with clang (CMake option RRFLINT_FUZZ):
//
//   CXX=clang++ cmake -S . -B build-fuzz -DRRFLINT_FUZZ=ON -DBUILD_TESTING=OFF && cmake --build build-fuzz
//   build-fuzz/rrflint_fuzz -dict=tests/fuzz/rrf.dict -max_len=4096 tests/fuzz/corpus
//
// Input layout: byte 0 picks the firmware target and board; the rest is split at the first 0xFF byte into
// /sys/config.g and /sys/m.g (so `M98 P"m.g"` in the first part reaches the second). Without 0xFF the whole
// rest is config.g. The seeds in tests/fuzz/corpus/ are small hand-written configs. Each input is linted a
// second time on three threads (files parsed in parts), which must report the same, and each file is parsed
// again without the short path for simple lines, which must record the same.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "lint/engine/linter.h"
#include "lint/render/render.h"
#include "rules/registry.h"
#include "tests/param_check.h"

using namespace rrflint;

namespace {

constexpr Version kVersions[] = {Version(2, 5, 1), Version(3, 0, 0), Version(3, 2, 2), Version(3, 3, 0),
                                 Version(3, 4, 6), kRrf3_5_0_beta2,  Version(3, 5, 4), kLatestVersion};
constexpr Board kBoards[] = {Board::Unknown, Board::Duet2, Board::Duet3_6HC, Board::Duet3_Mini, Board::Maestro};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t sel = data[0];
  std::string rest(reinterpret_cast<const char*>(data + 1), size - 1);
  std::string config = rest, macro;
  if (size_t cut = rest.find('\xff'); cut != std::string::npos) {
    config = rest.substr(0, cut);
    macro = rest.substr(cut + 1);
  }

  MemoryReader reader;
  reader.add("/sys/config.g", config);
  if (!macro.empty()) reader.add("/sys/m.g", macro);
  LintOptions o;
  o.select = {"ALL"};
  if (sel & 0x80) o.firmware = kVersions[sel & 7];  // otherwise inferred from the text
  o.board = kBoards[(sel >> 3) % 5];
  o.tool_changer = sel & 0x40;

  SourceManager sources;
  MachineResult r = lint_machine(sources, reader, builtin_rules(), o);

  // Parameters are lexed twice (while parsing, and again on demand): both must see the same parameters.
  for (uint32_t u = 0; u < r.machine->unit_count(); ++u) {
    const ParsedFile& pf = r.machine->unit(u).parsed;
    for (const Command& c : pf.commands)
      if (!test::param_mismatch(pf, c).empty()) __builtin_trap();
    for (const Line& l : pf.lines)
      if (l.code.end > l.span.end || l.comment.end > l.span.end || l.span.end > pf.source->size()) __builtin_trap();
    // The ranges of commands inside blocks (the graph's runs) agree with every command's line.
    if (!test::block_commands_mismatch(pf).empty()) __builtin_trap();
    // The short path for simple lines records what the full lexer records.
    if (test::parse_dump(pf) != test::parse_dump(parse(*pf.source, ParseOptions{.fast_lines = false})))
      __builtin_trap();
  }

  std::ostringstream sink;
  RenderOptions ro;
  render_text(sink, sources, r.diagnostics, ro);
  render_json(sink, sources, r.diagnostics, ro);

  // Threads change nothing: the same card linted with files parsed in parts of a few bytes and the file rules
  // beside the forward pass reports the same findings, byte for byte.
  {
    LintOptions split = o;
    split.threads = 3;
    split.part_bytes = 8;
    SourceManager split_sources;
    MachineResult sr = lint_machine(split_sources, reader, builtin_rules(), split);
    std::ostringstream a, b;
    render_json(a, sources, r.diagnostics, ro);
    render_json(b, split_sources, sr.diagnostics, ro);
    if (a.str() != b.str()) __builtin_trap();
  }

  // Every fix must apply to its own file without going out of range.
  for (FileId f = 0; f < sources.size(); ++f) {
    std::vector<Edit> edits;
    for (const Diagnostic& d : r.diagnostics)
      if (d.fix)
        for (const Edit& e : d.fix->edits)
          if (e.loc.file == f) edits.push_back(e);
    std::string text(sources.get(f).text());
    apply_edits(text, edits);
  }
  return 0;
}
