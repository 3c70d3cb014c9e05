// RRF102 line-too-long: the stored part of a line exceeds the firmware's buffer.
#include <fmt/format.h>

#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF102",
    .name = "line-too-long",
    .severity = Severity::Error,
    .summary = "The stored part of a line is longer than the firmware's G-code buffer.",
    .docs = R"md(
## What it does
Counts the characters RRF stores for each line (leading indentation, the line number, checksums, comments
and CNC-mode `( )` comments are not stored; quoted strings and `{…}` text are) and reports lines longer than
the target's limit: 255 from RRF 3.4, 200 for 3.1–3.3, 160 before.

## Firmware versions
A **hazard** whose limit and outcome depend on the version (from 3.1 an overlong line aborts the file). It is
judged at the target only.

## Why is this bad?
From RRF 3.1 an over-long line raises `GCode command too long` while the line is checked for meta
commands, which **aborts the rest of config.g**. RRF 3.0 drops the line with `G-Code buffer … length overflow`
and carries on. Long `M587` network lines and long `M291` messages are the usual cause.

## Example
```gcode
M291 P"Load filament: heat the nozzle to the temperature of the filament, open the idler lever and push the filament through the extruder until it comes out of the nozzle, then close the lever, wipe the nozzle and press OK. Press Cancel to stop without loading." R"Load filament" S3
```

## Use instead
Shorten the line, or split it: put a long message in a `var` built in pieces, or split settings over two
commands where the command allows it.

## References
- rrflint: [Lines and line endings](../firmware-behaviour.md#lines-and-line-endings), [Errors and aborts](../firmware-behaviour.md#errors-and-aborts)
- Duet3D G-code dictionary: [Command Length](https://docs.duet3d.com/User_manual/Reference/Gcodes#command-length)
- RepRapFirmware 3.5.3: [Configuration.h](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Config/Configuration.h) (`MaxGCodeLength`), [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`CheckMetaCommand()`); [3.3 Configuration.h](https://github.com/Duet3D/RepRapFirmware/blob/3.3/src/Configuration.h) (`GCODE_LENGTH`)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const int limit = max_line_length(cx.target.version);
  const LineTable& lines = cx.parsed().lines;
  for (size_t li = 0; li < lines.size(); ++li) {
    // From the records: most lines are short, and only the long ones are decoded.
    if (lines.kind(li) == LineKind::Comment || lines.kind(li) == LineKind::Blank) continue;
    if (lines.stored_length(li) <= static_cast<uint32_t>(limit)) continue;
    const Line line = lines[li];
    const bool aborts = cx.target.version >= kRrf3_1;
    Span s{line.code.begin + static_cast<uint32_t>(limit), line.code.end};
    if (s.begin >= s.end) s = line.code;
    out.report(kMeta, cx.at(s),
               fmt::format("line stores {} characters, more than the {} RRF {} accepts: {}", line.stored_length, limit,
                           cx.target.version.str(),
                           aborts ? "'GCode command too long' aborts the rest of the file" : "the line is dropped"));
  }
}

}  // namespace

extern const Rule line_too_long{.meta = kMeta, .check_file = check};

}  // namespace rrflint
