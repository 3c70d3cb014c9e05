// libFuzzer target: a whole SD card from one buffer, in the card format of tests/fuzz/fuzz_input.h (config.g,
// config-override.g, tool-change macros, M98-called macros, files in /macros; M98 graphs with cycles), linted with
// every rule and every other macro as an entry of its own. Checks: every parse agrees with itself, every location
// lies inside its file, the text and JSON renderers run, and a lint on three threads reports the same, byte for
// byte. Run it with scripts/fuzz.sh (tests/fuzz/RESULTS.md).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "tests/fuzz/fuzz_input.h"

using namespace rrflint;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  fuzz::LintedCard card(data, size);
  const MachineResult& r = card.result;
  fuzz::check_parses(*r.machine);
  fuzz::check_locations(card.sources, r.diagnostics);
  std::ostringstream sink;
  render_text(sink, card.sources, r.diagnostics, RenderOptions{});
  fuzz::check_threads_agree(card.reader, card.options, card.sources, r);
  return 0;
}
