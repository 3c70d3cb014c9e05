// RRF105 exponent-swallows-parameter: `X80E420` is one number with an exponent to RRF, not X80 and E420.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF105",
    .name = "exponent-swallows-parameter",
    .severity = Severity::Warning,
    .fix = FixAvailability::Always,
    .summary = "An E straight after a number is read as an exponent, not as an E parameter.",
    .docs = R"md(
## What it does
Reports a number directly followed by `E` or `e` and digits, with no blank in between: `M92 X80E420`,
`M584 X0 Y1 Z2E3`. A signed exponent such as `1e-3` is taken as deliberate scientific notation and not reported.

## Why is this bad?
RRF's parser does not start a parameter at an `E` that follows a digit, so the `E` value is never seen. A
floating-point value takes the rest as an exponent (`X80E420` sets X to infinity); an integer or driver value
stops at the `E` and keeps its value, so `M584 … Z2E3` silently creates no extruder. In SBC mode the
DuetSoftwareFramework parser splits the two parameters, so the same file behaves differently on the two set-ups.

## Example
```gcode
M584 X0 Y1 Z2E3
M92 X80 Y80 Z400E420
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M92 X80 Y80 Z400 E420
```

## Fix safety
The fix inserts a blank before the `E`. It is safe: it gives the line the meaning it has in SBC mode and that
its author intended.

## References
- rrflint: [Parameters](../firmware-behaviour.md#parameters), [The SBC parser](../firmware-behaviour.md#the-sbc-parser)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`FindParameters()`, `Seen()`: no parameter letter E after a digit)
- [RRFLibraries NumericConverter.cpp](https://github.com/Duet3D/RRFLibraries/blob/3.5-dev/src/General/NumericConverter.cpp) (exponents)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  if (!pf.prefilters.any_exponent) return;  // the parse's summary: no command has the flag
  for (const uint32_t ci : pf.prefilters.commands_with(pf.commands, CommandTable::Flag::Exponent)) {
    const Command& c = pf.commands[ci];
    for (const Param& p : pf.params(c)) {
      if (!p.exponent_letter || p.letter == 0) continue;
      uint32_t at = 0;
      lex::for_each_plain(t, p.value, [&](uint32_t k) {
        if ((t[k] == 'E' || t[k] == 'e') && k > p.value.begin && lex::is_digit(t[k - 1]) && k + 1 < p.value.end &&
            lex::is_digit(t[k + 1])) {
          at = k;
          return false;
        }
        return true;
      });
      if (at == 0) continue;
      uint32_t e = at + 1;
      while (e < p.value.end && (lex::is_digit(t[e]) || t[e] == '.' || t[e] == ':')) ++e;
      const std::string letter = p.letter >= 'a' ? fmt::format("'{}", p.letter) : std::string(1, p.letter);
      Fix fix = Fix::safe(fmt::format("insert a blank before '{}'", t[at]), Edit::insert(cx.at(Span{at, at}), " "));
      out.report(kMeta, cx.at(Span{at, e}),
                 fmt::format("'{}' straight after the number is read as an exponent of {}'s value '{}', not as an "
                             "'E' parameter: RRF sets no E value here (SBC mode reads one)",
                             clip(t.substr(at, e - at)), letter, clip(t.substr(p.value.begin, at - p.value.begin))))
          .fix(std::move(fix));
    }
  }
}

}  // namespace

extern const Rule exponent_swallows_parameter{.meta = kMeta, .check_file = check};

}  // namespace rrflint
