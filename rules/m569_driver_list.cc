// RRF220 m569-driver-list: M569 (no fraction) with a list of drivers configures only the first of them, or, from
// 3.4 with more drivers than visible axes, none.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/append_fix.h"
#include "rules/lex_common.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF220",
    .name = "m569-driver-list",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary =
        "M569 with a list of drivers configures only the first: RRF reads lists only for M569.3, M569.4 and "
        "M569.8.",
    .docs = R"md(
## What it does
Reports an `M569` whose `P` names several drivers (`M569 P0:1:2 S1`), the way `M584`, `M906` and `M350` take
lists. It stays silent on one driver, on a `P` from an expression, on the fractions that read lists
(`M569.3`, `M569.4`, `M569.8`) and on the other fractions.

## Why is this bad?
`M569` without a fraction configures one driver. Up to 3.3 RRF reads the first driver of `P` and ignores the
rest of the list; from 3.4 it reads the whole list (`GCodes::ConfigureDriver()`) but stops after the first driver
unless the fraction is 3, 4 or 8. So `M569 P0:1:2 S0` sets the direction of driver 0 only: drivers 1 and 2 keep
their defaults (forwards), with no message. From 3.4 a list longer than the number of visible axes is refused
whole with `array too long, max length = <n>`, and no driver is configured.

## Example
```gcode
; rrflint-options: --firmware 3.5
M569 P0:1:2 S0 D3
```

## Use instead
```gcode
; rrflint-options: --firmware 3.5
M569 P0 S0 D3
M569 P1 S0 D3
M569 P2 S0 D3
```

## Fix safety
The fix writes one `M569` per driver, each with the other parameters of the line, on lines of their own with the
same indentation. It is unsafe: the drivers after the first are configured only once it is applied. There is no
fix when the line holds another command, or does not parse whole (an unterminated string or `{`).

## References
- rrflint: [M569 per driver](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M569](https://docs.duet3d.com/User_manual/Reference/Gcodes#m569-set-motor-driver-direction-enable-polarity-mode-and-step-pulse-timing)
- RepRapFirmware 3.5: [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes3.cpp) (`ConfigureDriver()`), [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodeBuffer/StringParser.cpp) (`GetDriverIdArray()`, `CheckArrayLength()`)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 569)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const auto P = get_driver_list(pf, c, 'P');
  if (!P.known() || P.value.size() < 2) return;
  const MachineState& s = cx.state;
  std::string rest;
  for (size_t i = 1; i < P.value.size(); ++i) rest += (i > 1 ? ", " : "") + P.value[i].str();
  const bool refused = s.firmware >= kRrf3_4 && s.axes_known && !s.unknown_baseline &&
                       P.value.size() > static_cast<size_t>(s.visible_axes);
  const std::string what =
      refused ? fmt::format(
                    "names {} drivers, more than the {} visible axes: RRF refuses it with 'array too long, max "
                    "length = {}' and configures no driver",
                    P.value.size(), s.visible_axes, s.visible_axes)
              : fmt::format("configures only driver {}: M569 without a fraction takes one driver, and RRF ignores {}",
                            P.value[0].str(), rest);
  Report r = out.report(kMeta, cx.at(P.param->span),
                        fmt::format("{} {}; give each driver its own M569", tools::quote(pf, c), what));
  // The fix: one M569 per driver, on lines of their own, when the command is alone on its line and parses whole
  // (each copy of an unterminated string, or of an expression a ';' cuts open, would be a new syntax error).
  const Line& line = pf.lines[c.line];
  if (line.command_count != 1 || !tools::parses_whole(pf, c)) return;
  const std::string_view text = pf.source->text();
  const std::string before(text.substr(c.span.begin, P.param->span.begin - c.span.begin));
  const std::string after(text.substr(P.param->span.end, c.span.end - P.param->span.end));
  const std::string new_line = lex::new_line_after(pf, line);
  std::string lines;
  for (size_t i = 0; i < P.value.size(); ++i)
    lines += (i ? new_line : std::string()) + before + "P" + P.value[i].str() + after;
  r.fix(
      Fix::unsafe(fmt::format("write one M569 per driver ({})", P.value.size()), Edit::replace(cx.at(c.span), lines)));
}

}  // namespace

extern const Rule m569_driver_list{.meta = kMeta, .check_node = check, .on = "M569"};

}  // namespace rrflint
