// RRF118 byte-order-mark: a UTF-8 byte-order mark at the start of a file spoils its first line.
#include <fmt/format.h>

#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF118",
    .name = "byte-order-mark",
    .severity = Severity::Warning,
    .fix = FixAvailability::Always,
    .summary = "The file starts with a UTF-8 byte-order mark, which standalone RRF reads as part of the first line.",
    .docs = R"md(
## What it does
Reports a file whose first three bytes are the UTF-8 byte-order mark (EF BB BF), which some Windows editors
write at the start of every file they save. rrflint reads the rest of the first line as if the mark were not
there, so this is the one finding about it.

## Why is this bad?
Standalone RepRapFirmware has no notion of a byte-order mark: it reads the three bytes as the first characters
of line 1. The line then starts with neither `G`, `M`, `T` nor a meta-command keyword, so the first command is
lost with a `Bad command` error (a first line that is a `;` comment becomes such an error too). In SBC mode the
DuetSoftwareFramework reads the file as text and drops the mark, so the same file behaves differently there.

## Example
A config.g saved as "UTF-8 with BOM" (the mark is invisible in most editors):
```gcode
﻿M550 P"Printer"
```

## Use instead
Save the file as UTF-8 without a byte-order mark:
```gcode
M550 P"Printer"
```

## Fix safety
The fix removes the three bytes of the mark. It is safe: nothing else in the file changes, and the first line
then reads as its author wrote it.

## References
- rrflint: [Lines and line endings](../firmware-behaviour.md#lines-and-line-endings), [Command words](../firmware-behaviour.md#command-words)
- https://github.com/Duet3D/RepRapFirmware/blob/3.6-dev/src/GCodes/GCodeBuffer/StringParser.cpp (`Put()` stores
  every byte of a line; `DecodeCommand()` reports a line that does not start with a command letter)
- https://docs.duet3d.com/User_manual/Reference/Gcodes
)md",
};

void check(const FileContext& cx, Sink& out) {
  const SourceFile& src = cx.source();
  if (!src.text().starts_with("\xEF\xBB\xBF")) return;
  // What line 1 holds after the mark: a command (lost) or a comment or nothing (then a 'Bad command' of its own).
  const std::string_view first = src.slice(src.line_span(0)).substr(3);
  const size_t k = first.find_first_not_of(" \t");
  const bool code = k != std::string_view::npos && first[k] != ';';
  Fix fix = Fix::safe("remove the byte-order mark", Edit::remove(cx.at(Span{0, 3})));
  out.report(kMeta, cx.at(Span{0, 3}),
             code ? "file starts with a UTF-8 byte-order mark: standalone RRF reads it as part of the first command, "
                    "which is lost ('Bad command')"
                  : "file starts with a UTF-8 byte-order mark: standalone RRF reads it as part of line 1, which "
                    "becomes a 'Bad command' error")
      .fix(std::move(fix));
}

}  // namespace

extern const Rule byte_order_mark{.meta = kMeta, .check_file = check};

}  // namespace rrflint
