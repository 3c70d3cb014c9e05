// libFuzzer target: lints arbitrary bytes as an SD card of two files with every rule enabled, renders the
// findings as text and JSON, and applies every fix. Run it with scripts/fuzz.sh (tests/fuzz/RESULTS.md).
//
// Input layout: byte 0 picks the firmware target and board (fuzz::options_of); the rest is split at the first 0xFF
// byte into /sys/config.g and /sys/m.g (so `M98 P"m.g"` in the first part reaches the second). Without 0xFF the
// whole rest is config.g. Seeds: tests/fuzz/make_seeds.py. Each input is linted a second time on three threads
// (files parsed in parts, every prefilter off), which must report the same, and each file is parsed again without the
// short path for simple lines, which must record the same (fuzz::check_parses, fuzz::check_threads_agree).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "tests/fuzz/fuzz_input.h"

using namespace rrflint;

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
  const LintOptions o = fuzz::options_of(sel);

  SourceManager sources;
  MachineResult r = lint_machine(sources, reader, builtin_rules(), o);

  fuzz::check_parses(*r.machine);

  std::ostringstream sink;
  RenderOptions ro;
  render_text(sink, sources, r.diagnostics, ro);
  render_json(sink, sources, r.diagnostics, ro);

  fuzz::check_threads_agree(reader, o, sources, r);

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
