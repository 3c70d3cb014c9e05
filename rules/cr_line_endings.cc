// RRF107 cr-line-endings: a file whose lines end with CR only is one line to RRF 3.4.6+/3.5.0b2+.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/version_gate.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF107",
    .name = "cr-line-endings",
    .severity = Severity::Error,
    .fix = FixAvailability::Always,
    .summary = "The file ends its lines with CR only, which RRF reads as one single line.",
    .docs = R"md(
## What it does
Reports a file whose lines end with a lone carriage return (old Mac line endings) and no line feed, on targets
from RRF 3.4.6 (3.4 series) or 3.5.0-beta.2.

## Firmware versions
A **hazard** of RRF 3.4.6 and later on the 3.4 line and of 3.5.0-beta.2 and later. At such a target it is an error.
When no `--firmware` is given and the files do not rule out such a version (the target is newer, but nothing in the
files needs a version that new), it is reported as `info` with a note that names the versions and the evidence; see
[Firmware target](../firmware-behaviour.md#firmware-target).

## Why is this bad?
When RRF reads a file it discards CR characters; only LF ends a line. A CR-only file is therefore **one single
line**. If it starts with a `;` comment (as every config-tool file does) the whole file is a comment and
config.g silently does nothing; otherwise only the first command runs, or the line overflows with
`GCode command too long`. Before 3.4.6 a CR still ended a line, and the rule stays silent.

Since the firmware never sees lines 2 to the end as lines, rrflint reports nothing else on them: this finding is
the file's one finding there (fix it, and the other findings show up). On earlier targets nothing is hidden.

## Example
A file saved with CR line endings by an old editor.

## Use instead
Save the file with LF (or CRLF) line endings.

## Fix safety
The fix replaces every lone CR with LF. It is safe: it changes only line endings.

## References
- rrflint: [Lines and line endings](../firmware-behaviour.md#lines-and-line-endings)
- Duet3D meta commands: [Line Endings](https://docs.duet3d.com/User_manual/Reference/Gcode_meta_commands#line-endings)
- RepRapFirmware `Put()` in [3.4.5 StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.4.5/src/GCodes/GCodeBuffer/StringParser.cpp) (CR ends a line) and [3.4.6 StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.4.6/src/GCodes/GCodeBuffer/StringParser.cpp) (CR is dropped in files)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const SourceFile& src = cx.source();
  if (!src.endings().cr_only()) return;
  const std::optional<gate::Gate> g = gate::hazard(cx.target, cr_is_not_a_line_end, kMeta.severity);
  if (!g) return;
  constexpr std::string_view kVersions = "from 3.4.6 (3.4 series) and from 3.5.0-beta.2";
  Fix fix = Fix::safe("replace CR line endings with LF");
  std::string_view t = src.text();
  for (uint32_t i = 0; i < t.size(); ++i)
    if (t[i] == '\r') fix.edits.push_back(Edit::replace(cx.at(Span{i, i + 1}), "\n"));
  const Span first = src.line_span(0);
  const bool comment_first = !t.empty() && src.slice(first).find_first_not_of(" \t") != std::string_view::npos &&
                             src.slice(first)[src.slice(first).find_first_not_of(" \t")] == ';';
  const Location at = cx.at(Span{first.end, std::min(first.end + 1, src.size())});
  Report r = out.report(
      kMeta, g->severity, at,
      fmt::format("the file uses CR-only line endings: {} {} all {} lines as one line{}",
                  gate::on(*g, cx.target, kVersions), g->at == HazardAt::Target ? "reads" : "read", src.line_count(),
                  comment_first ? ", and since it starts with a comment the whole file does nothing" : ""));
  gate::explain(r, *g, cx.target, at, kVersions);
  r.fix(std::move(fix));
}

}  // namespace

extern const Rule cr_line_endings{.meta = kMeta, .check_file = check, .raw_bytes = true};

}  // namespace rrflint
