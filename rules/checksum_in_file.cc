// RRF110 checksum-in-file: `N…` line numbers and `*…` checksums in a file; a wrong checksum drops the line.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF110",
    .name = "checksum-in-file",
    .severity = Severity::Warning,
    .summary = "A line number (N…) or checksum (*…) in a file.",
    .docs = R"md(
## What it does
Reports lines that start with a line number `N<digits>`, and checksums `*<digits>` after such a line number.
For a 1–3 digit checksum rrflint computes the XOR checksum RRF expects and says whether it matches.

## Why is this bad?
Line numbers and checksums belong to a serial link, not to a file. RRF checks a checksum and **silently drops
the line** when it does not match (no message unless G-code debugging is on); any later edit of such a line
breaks its checksum. A checksum of 4, or 6 or more digits is always wrong. A line number alone replaces RRF's
own line count in error messages, which then point at the wrong line.

## Example
```gcode
N10 M584 X0 Y1 Z2 E3*99
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
```

## References
- rrflint: [Line numbers and checksums](../firmware-behaviour.md#line-numbers-and-checksums)
- Duet3D G-code dictionary: [Checking](https://docs.duet3d.com/User_manual/Reference/Gcodes#checking) (line numbers, checksums and CRCs)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`Put()` line-number and checksum states, `LineFinished()`)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  if (!pf.prefilters.any_line_number) return;  // the parse's summary
  for (const Line& line : pf.lines) {
    if (!line.line_number) continue;
    const uint32_t n = lex::indentation(pf, line).end;  // the 'N'
    uint32_t ne = n + 1;
    while (ne < line.span.end && lex::is_digit(t[ne])) ++ne;
    const std::string number = clip(t.substr(n, ne - n));
    if (!line.checksum) {
      out.report(kMeta, cx.at(Span{n, ne}),
                 fmt::format("line number '{}' in a file: RRF reports errors with this number instead of the real "
                             "line number",
                             number));
      continue;
    }
    // The checksum follows the code after blanks: find the '*' RRF stopped at.
    uint32_t star = line.code.end;
    while (star < line.span.end && t[star] != '*') ++star;
    if (star >= line.span.end) continue;
    uint32_t se = star + 1;
    while (se < line.span.end && lex::is_digit(t[se])) ++se;
    const std::string_view sum = t.substr(star, se - star);
    const size_t digits = sum.size() - 1;
    std::string verdict;
    if (digits >= 1 && digits <= 3) {
      unsigned expected = 0;
      for (uint32_t k = n; k < star; ++k) expected ^= static_cast<unsigned char>(t[k]);
      unsigned given = 0;
      for (char ch : sum.substr(1)) given = given * 10 + static_cast<unsigned>(ch - '0');
      verdict = given == expected
                    ? fmt::format("it matches now, but any edit of the line makes RRF drop it silently")
                    : fmt::format("it is wrong (RRF computes *{}), so RRF silently drops this line", expected);
    } else if (digits == 5) {
      verdict = "a wrong CRC makes RRF drop the line silently";
    } else {
      verdict = fmt::format("a checksum of {} digits is never valid, so RRF silently drops this line", digits);
    }
    out.report(kMeta, cx.at(Span{n, ne}),
               fmt::format("line number '{}' and checksum '{}' in a file: {}", number, clip(sum), verdict))
        .note(cx.at(Span{star, se}), "the checksum");
  }
}

}  // namespace

extern const Rule checksum_in_file{.meta = kMeta, .check_file = check};

}  // namespace rrflint
