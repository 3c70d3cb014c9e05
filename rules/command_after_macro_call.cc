// RRF111 command-after-macro-call: commands after M98/G28/G29/G32/T on one line are not executed.
#include <algorithm>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "lint/boot/commands.h"
#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF111",
    .name = "command-after-macro-call",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary = "Commands after a command that runs a macro (M98, G28, G29, G32, T) on the same line.",
    .docs = R"md(
## What it does
Reports a line that has more commands after `M98`, `G28`, `G29` (without `S`), `G32` or a `T` tool selection.
These commands run macro files (the called file, the homing files, `mesh.g`, `bed.g`, the tool-change files), and
a `T` command must be on a line of its own. `G29 S1`, `S2` and `S3` load, clear or save the height map and run no
macro: the rest of their line runs.

## Why is this bad?
RRF can put several commands on one line, but a command that runs a macro reuses the line buffer for the
macro's lines: the rest of the original line is not executed. The commands after it are silently skipped.
rrflint's machine model skips them too (after all of these but `T`): what they would create or set is not there
for the other rules.

## Example
```gcode
M98 P"leds.g" M106 P0 S0
T0 P0 M116
```

## Use instead
```gcode
M98 P"leds.g"
M106 P0 S0
T0 P0
M116
```

## Fix safety
The fix moves the commands after the macro call to a line of their own, with the same indentation. It is
unsafe: those commands have not run so far, and will once fixed. No fix is offered when they hold a syntax error:
on a line of their own RRF would read them, and the error would abort the file (RRF100); correct them first.

## References
- rrflint: [Several commands on one line](../firmware-behaviour.md#several-commands-on-one-line)
- Duet3D G-code dictionary: [Multiple commands on a single line](https://docs.duet3d.com/User_manual/Reference/Gcodes#multiple-commands-on-a-single-line)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`FindParameters()` ends a command at the next G or M)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  // The commands that run a macro and have another command after them on their line, in file order.
  std::vector<uint32_t> found;
  constexpr std::pair<char, int> kMacroCodes[] = {{'T', -1}, {'M', 98}, {'G', 28}, {'G', 29}, {'G', 32}};
  for (const auto& [letter, number] : kMacroCodes)
    for (const uint32_t i : pf.with_code(letter, number))
      if (i + 1 < pf.commands.size() && pf.commands[i + 1].line == pf.commands[i].line &&
          (letter == 'T' || drops_rest_of_line(pf, pf.commands[i])))
        found.push_back(i);
  std::sort(found.begin(), found.end());
  uint32_t done_line = UINT32_MAX;
  for (const uint32_t i : found) {
    const Command& c = pf.commands[i];
    if (c.line == done_line) continue;  // one finding per line
    done_line = c.line;
    const Line& line = pf.lines[c.line];
    const uint32_t last = line.first_command + line.command_count - 1;
    const Command& next = pf.commands[i + 1];
    const Span rest{next.span.begin, pf.commands[last].span.end};
    const std::string why = c.letter == 'T'
                                ? std::string("may not be executed: a 'T' command must be alone on its line")
                                : fmt::format("is not executed: '{}' runs a macro, and RRF drops the rest of the line",
                                              clip(lex::word(pf, c)));
    auto rep = out.report(
        kMeta, cx.at(rest),
        fmt::format("'{}' after '{}' on the same line {}", clip(pf.text(rest), 30), clip(lex::word(pf, c)), why));
    // Text with a syntax error stays where RRF drops it: on its own line the error would abort the file.
    if (!pf.any_error_from(rest.begin, std::max(rest.end, line.code.end)))
      rep.fix(Fix::unsafe(fmt::format("move '{}' to a line of its own", clip(pf.text(rest), 30)),
                          Edit::replace(cx.at(Span{c.span.end, next.span.begin}), lex::new_line_after(pf, line))));
  }
}

}  // namespace

extern const Rule command_after_macro_call{.meta = kMeta, .check_file = check};

}  // namespace rrflint
