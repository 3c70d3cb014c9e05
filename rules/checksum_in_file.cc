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
    .fix = FixAvailability::Sometimes,
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

## Fix safety
The fix removes the line number, and the checksum after it. Without a checksum it is safe: only RRF's error
messages change, to the real line number. With a 1–3 digit checksum that matches it is safe: the line runs now and
runs the same after. With a checksum that does not match, or a CRC (rrflint does not check CRCs), the fix is
unsafe: RRF drops that line now, and after the fix it would run; read the line before you apply it.

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
    const bool has_code = line.code.begin < line.code.end && !line.after_nul;
    if (!line.checksum) {
      Report r = out.report(kMeta, cx.at(Span{n, ne}),
                            fmt::format("line number '{}' in a file: RRF reports errors with this number instead of "
                                        "the real line number",
                                        number));
      if (has_code && line.code.begin >= ne)
        r.fix(Fix::safe("remove the line number", Edit::remove(cx.at(Span{n, line.code.begin}))));
      continue;
    }
    const Span cs = checksum_span(t, line);  // the '*' RRF stopped at, and its digits
    if (cs.empty()) continue;
    const uint32_t star = cs.begin, se = cs.end;
    const std::string_view sum = t.substr(star, se - star);
    const size_t digits = sum.size() - 1;
    std::string verdict;
    bool matches = false;
    if (digits >= 1 && digits <= 3) {
      unsigned expected = 0;
      for (uint32_t k = n; k < star; ++k) expected ^= static_cast<unsigned char>(t[k]);
      unsigned given = 0;
      for (char ch : sum.substr(1)) given = given * 10 + static_cast<unsigned>(ch - '0');
      matches = given == expected;
      verdict = matches ? fmt::format("it matches now, but any edit of the line makes RRF drop it silently")
                        : fmt::format("it is wrong (RRF computes *{}), so RRF silently drops this line", expected);
    } else if (digits == 5) {
      verdict = "a wrong CRC makes RRF drop the line silently";
    } else {
      verdict = fmt::format("a checksum of {} digits is never valid, so RRF silently drops this line", digits);
    }
    Report r = out.report(kMeta, cx.at(Span{n, ne}),
                          fmt::format("line number '{}' and checksum '{}' in a file: {}", number, clip(sum), verdict));
    r.note(cx.at(Span{star, se}), "the checksum");
    // Only blanks and a comment may follow the checksum: other text there is not code, and would become code.
    uint32_t rest = se;
    while (rest < line.span.end && (t[rest] == ' ' || t[rest] == '\t')) ++rest;
    if (!has_code || star < line.code.end || (rest < line.span.end && t[rest] != ';')) continue;
    // The fix rewrites the line from its start to the end of the checksum (an edit of part of that is withdrawn,
    // lint/engine/linter.cc). Safe only when the checksum matches: the line runs now and will run the same. A line
    // RRF drops now (or may drop: a CRC rrflint does not check) would start to run.
    std::string text(t.substr(line.span.begin, n - line.span.begin));
    text += t.substr(line.code.begin, line.code.end - line.code.begin);
    const Edit edit = Edit::replace(cx.at(Span{line.span.begin, se}), std::move(text));
    if (matches) r.fix(Fix::safe("remove the line number and checksum", edit));
    else if (digits == 5)
      r.fix(Fix::unsafe("remove the line number and CRC (if the CRC is wrong, the line would run)", edit));
    else r.fix(Fix::unsafe("remove the line number and checksum (RRF drops this line now; it would run)", edit));
  }
}

}  // namespace

extern const Rule checksum_in_file{.meta = kMeta, .check_file = check};

}  // namespace rrflint
