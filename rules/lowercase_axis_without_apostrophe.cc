// RRF115 lowercase-axis-without-apostrophe: M584 `a3` is axis A; lowercase axes need `'a3`, and board support.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF115",
    .name = "lowercase-axis-without-apostrophe",
    .severity = Severity::Warning,
    .summary = "M584 names a lowercase axis without its apostrophe, or one the target board does not have.",
    .docs = R"md(
## What it does
Checks the axis letters of `M584`:
- a lowercase letter written without `'` (`a3`) in a command that otherwise uses upper case. Lower-case `x`,
  `y`, `z`, `e` and the non-axis letters `p`, `r`, `s` are taken as upper case and not reported, and a command
  written all in lower case is left alone;
- a lowercase axis with `'` beyond the target's highest lowercase axis letter: `'f` on Duet 2 and Duet 3 Mini
  from RRF 3.5, `'l` in RRF 3.3 and 3.4 (`'a`…`'z` only on the Duet 3 MB6HC/MB6XD).

## Firmware versions
A **hazard** whose limit depends on the version and the board. It is judged at the target only.

## Why is this bad?
RRF upper-cases every parameter letter that has no `'` in front: `M584 a3` creates (or remaps) axis `A`, not
axis `a`, and a letter that is not an axis letter (`f3`) is ignored. A `'g` on a board whose firmware only
knows `'a`…`'f` is not a parameter at all. Either way no error is shown and the axis the user meant does not
exist.

## Example
```gcode
M584 X0 Y1 Z2 a3      ; meant the lowercase axis a
M584 'g4              ; on a Duet 2
```

## Use instead
```gcode
M584 X0 Y1 Z2 'a3
M584 'f4
```

## References
- rrflint: [Parameters](../firmware-behaviour.md#parameters)
- Duet3D G-code dictionary: [M584: set drive mapping](https://docs.duet3d.com/User_manual/Reference/Gcodes#m584-set-drive-mapping) (lowercase axis letters)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`FindParameters()`, `Seen()`), [RepRapFirmware.h](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/RepRapFirmware.h) (`HighestAxisLetter`), [GCodes.h](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.h) (`AllowedAxisLetters`)
)md",
};

constexpr std::string_view kUpperAxes = "abcduvw";     // lowercase forms of M584's upper-case axis letters
constexpr std::string_view kTakenAsUpper = "xyzeprs";  // meant as X, Y, Z, E, P, R, S

std::string board_phrase(const Target& t) {
  return t.board == Board::Unknown ? std::string() : fmt::format(" on {}", board_name(t.board));
}

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  const char highest = highest_lowercase_axis(cx.target.board, cx.target.version);
  for (const uint32_t ci : pf.with_code('M', 584)) {
    const Command& c = pf.commands[ci];
    if (!c.is('M', 584)) continue;
    // A command written all in lower case means upper case throughout.
    bool upper_seen = !lex::is_lower(t[c.word.begin]);
    for (const Param& p : pf.params(c))
      if (p.letter != 0 && t[p.span.begin] != '\'' && !lex::is_lower(t[p.span.begin])) upper_seen = true;
    for (const Param& p : pf.params(c)) {
      if (p.letter == 0 || p.kind == ValueKind::None) continue;
      const char written = t[p.span.begin];
      if (written == '\'') {
        if (highest == 0 || p.letter <= highest) continue;
        out.report(kMeta, cx.at(p.span),
                   fmt::format("lowercase axis '{} is beyond '{}, the highest RRF {}{} knows: {} is ignored and "
                               "creates no axis",
                               p.letter, highest, cx.target.version.str(), board_phrase(cx.target), pf.text(p.span)));
        continue;
      }
      if (!lex::is_lower(written) || !upper_seen || kTakenAsUpper.find(written) != std::string_view::npos) continue;
      const std::string as_written(pf.text(p.span));
      const std::string meant = "'" + as_written;
      std::string support;
      if (highest == 0) support = ", but lowercase axes need RRF 3.3 or later";
      else if (written > highest)
        support = fmt::format(", but RRF {}{} knows lowercase axes up to '{} only", cx.target.version.str(),
                              board_phrase(cx.target), highest);
      if (kUpperAxes.find(written) != std::string_view::npos)
        out.report(kMeta, cx.at(p.span),
                   fmt::format("'{}' sets axis '{}': without an apostrophe RRF reads the letter as upper case; "
                               "the lowercase axis is written {}{}",
                               as_written, p.letter, meant, support));
      else
        out.report(kMeta, cx.at(p.span),
                   fmt::format("'{}' is ignored: '{}' is not an M584 axis letter; a lowercase axis is written "
                               "with an apostrophe, {}{}",
                               as_written, p.letter, meant, support));
    }
  }
}

}  // namespace

extern const Rule lowercase_axis_without_apostrophe{.meta = kMeta, .check_file = check};

}  // namespace rrflint
