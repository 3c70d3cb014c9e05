// RRF101 unknown-command: a G/M code the target firmware does not implement, with no macro standing in.
#include <fmt/format.h>

#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF101",
    .name = "unknown-command",
    .severity = Severity::Warning,
    .summary = "A G or M code that the target firmware does not implement and no macro file provides.",
    .docs = R"md(
## What it does
Checks every G and M code against the table of codes each RRF version implements (2.05 to 3.6, read from the
firmware's dispatch code). A code the target does not implement is reported unless the SD card has the macro
RRF runs in its place: `/sys/Gnn.g`, `/sys/Mnn.g` or (3.4+) `/sys/Mnn.f.g`.

## Firmware versions
A **hazard**: each version implements its own set of codes. It is judged at the target only.

## Why is this bad?
RRF answers `Mnnn: Command is not supported` and does nothing. Usually the code is a typo (`M596` for `M569`),
a command from another firmware (Marlin's `M851`), or a command newer than the firmware on the board.

## Example
```gcode
M420 S1         ; Marlin's "enable bed levelling"
M900 K0.05      ; Marlin's linear advance
```

## Use instead
```gcode
G29 S1          ; load the saved height map
M572 D0 S0.05   ; pressure advance
```

## References
- rrflint: [Command words](../firmware-behaviour.md#command-words)
- Duet3D G-code dictionary: [Custom GCodes](https://docs.duet3d.com/User_manual/Reference/Gcodes#custom-gcodes), [GCodes not implemented](https://docs.duet3d.com/User_manual/Reference/Gcodes#gcodes-not-implemented)
- RepRapFirmware 3.5.3: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (`TryMacroFile()`, `HandleResult()`)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const int vi = code_version_index(cx.target.version);
  const ParsedFile& pf = cx.parsed();
  // By code: a code that exists, with no fractional command, clears all of its commands at once.
  auto check_command = [&](uint32_t i) {
    const CommandTable::Code k = pf.commands.code(i);  // from the record: most commands stop here
    if (k.letter == 'T' || k.number < 0) return;
    if (implemented(k.letter, k.number, k.fraction, vi)) return;
    const Command& c = pf.commands[i];
    // Before 3.4 a fraction is ignored when the base code exists.
    if (c.fraction >= 0 && cx.target.version < kRrf3_4 && implemented(c.letter, c.number, -1, vi)) return;
    std::string name = c.fraction >= 0 ? fmt::format("{}{}.{}", c.letter, c.number, c.fraction)
                                       : fmt::format("{}{}", c.letter, c.number);
    if (cx.machine.has_file("/sys/" + name + ".g")) return;
    bool elsewhere = false;
    for (int v = 0; v < kCodeVersions; ++v) elsewhere = elsewhere || implemented(c.letter, c.number, c.fraction, v);
    std::string why = elsewhere
                          ? fmt::format("RRF {} does not implement it (other versions do)", cx.target.version.str())
                          : fmt::format("RRF does not implement it");
    out.report(kMeta, cx.at(c.word),
               fmt::format("'{}' is not a command: {}, so it answers '{}: Command is not supported'; a /sys/{}.g "
                           "macro would run instead",
                           name, why, name, name));
  };
  for (const ParsedFile::UsedCode& code : pf.used_codes()) {
    if (code.letter == 'T' || (!code.any_fraction && implemented(code.letter, code.number, -1, vi))) continue;
    for (const uint32_t i : code.commands) check_command(i);
  }
  for (const uint32_t i : pf.unlisted_codes()) check_command(i);
}

}  // namespace

extern const Rule unknown_command{.meta = kMeta, .check_file = check, .whole_card = true};

}  // namespace rrflint
