// RRF106 blank-before-colon: a blank before ':' silently ends a colon-separated list.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF106",
    .name = "blank-before-colon",
    .severity = Severity::Warning,
    .fix = FixAvailability::Always,
    .summary = "A blank before ':' ends a colon-separated list early.",
    .docs = R"md(
## What it does
Reports a blank or tab in front of a `:` in a colon-separated list parameter (`E3 :4`, `X80 : 80`).
A value after a blank that does not start with `:` (`Y80 409:409`, where `E` was meant) has no letter at all:
that is [value-without-letter](value-without-letter.md) (RRF120). In `X80 409 :5` each rule reports its own
part: RRF120 the `409`, this rule the `:5`.

## Why is this bad?
After each value RRF continues the list only if the very next character is `:`. A blank there ends the list:
the values after it are silently ignored, so `M584 E3 :4` creates one extruder instead of two. A blank *after*
the `:` is harmless.

## Example
```gcode
M584 X0 Y1 Z2 E3 :4
M906 E800 : 800
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3:4
M906 E800:800
```

## Fix safety
The fix removes the blanks before each `:` of the list. It is safe: it makes RRF read the whole list, as
written.

## References
- rrflint: [Numbers and lists](../firmware-behaviour.md#numbers-and-lists)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`GetFloatArray()` and its siblings: the list goes on only at a `:`)
- See also: [value-without-letter](value-without-letter.md) (RRF120), for a value after a blank that is not a `:`
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  if (!pf.prefilters.any_blank_before_colon) return;  // the parse's summary: no command has the flag
  for (const uint32_t ci : pf.prefilters.commands_with(pf.commands, CommandTable::Flag::BlankBeforeColon)) {
    const Command& c = pf.commands[ci];
    for (const Param& p : pf.params(c)) {
      if (!p.blank_before_colon || p.letter == 0) continue;
      std::vector<Span> blanks;  // each run of blanks before a ':'
      lex::for_each_plain(t, p.value, [&](uint32_t k) {
        if (t[k] != ':' || k == p.value.begin || !lex::is_blank(t[k - 1])) return true;
        uint32_t b = k;
        while (b > p.value.begin && lex::is_blank(t[b - 1])) --b;
        blanks.push_back(Span{b, k});
        return true;
      });
      if (blanks.empty()) continue;
      const Span first = blanks.front();
      Fix fix = Fix::safe("remove the blank before ':'");
      for (Span s : blanks) fix.edits.push_back(Edit::remove(cx.at(s)));
      const std::string letter = p.letter >= 'a' ? fmt::format("'{}", p.letter) : std::string(1, p.letter);
      out.report(kMeta, cx.at(Span{first.begin, first.end + 1}),
                 fmt::format("blank before ':' ends the list: RRF reads '{}{}' and ignores '{}'", letter,
                             clip(t.substr(p.value.begin, first.begin - p.value.begin)),
                             clip(t.substr(first.end, p.value.end - first.end))))
          .fix(std::move(fix));
    }
  }
}

}  // namespace

extern const Rule blank_before_colon{.meta = kMeta, .check_file = check};

}  // namespace rrflint
