// RRF116 duplicate-parameter: RRF reads the first of two parameters with one letter and ignores the second.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF116",
    .name = "duplicate-parameter",
    .severity = Severity::Warning,
    .tag = RuleTag::Unnecessary,
    .summary = "A parameter letter given twice in one command; RRF ignores the second.",
    .docs = R"md(
## What it does
Reports the second parameter with the same letter in one command (`M584 X0 Y1 X2`), when both have a value
and the values differ. An exact repeat (`F18000 … F18000`, `B0 B0`) changes nothing and is not reported.
Lowercase axes (`'a`) and upper-case letters are different parameters. Letters inside unquoted words
(`Cout1`), and in `( … )` after a command outside CNC mode, are left to RRF103 and RRF112.

## Why is this bad?
RRF looks a parameter up by scanning the command for its letter and stops at the first match, so the second
value is silently ignored. It is usually a copy-paste slip, or two settings that were meant for different
letters.

## Example
```gcode
M584 X0 Y1 Z2 X3
M906 X800 Y800 Z800 Y1000
```

## Use instead
```gcode
M584 X0:3 Y1 Z2
M906 X800 Y1000 Z800
```

## References
- rrflint: [Parameters](../firmware-behaviour.md#parameters)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`Seen()` returns the first match)
- [DSF ParserAsync.cs](https://github.com/Duet3D/DuetSoftwareFramework/blob/v3.5.3/src/DuetAPI/Commands/Code/ParserAsync.cs) (keeps the first as well)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  if (!pf.prefilters.any_repeated_letter) return;  // the parse's summary: no command has the flag
  for (const uint32_t ci : pf.prefilters.commands_with(pf.commands, CommandTable::Flag::RepeatedLetter)) {
    const Command& c = pf.commands[ci];
    // Outside CNC mode a '(' does not start a comment; what follows it is RRF112's concern.
    uint32_t stop = c.span.end;
    if (lex::contains(t, c.span, '('))
      lex::for_each_plain(t, c.span, [&](uint32_t k) {
        if (t[k] != '(') return true;
        stop = k;
        return false;
      });
    // A letter straight after another letter is part of an unquoted word (`Cout1` gives C, O, U, T1): RRF103.
    // Likewise the x of a hex byte in raw text (`M540 P0x02:0x80`).
    auto in_word = [&](const Param& p) {
      if (p.span.begin == 0) return false;
      const char before = t[p.span.begin - 1];
      return lex::is_alpha(before) || (before == '0' && (p.letter == 'X' || p.letter == 'x'));
    };
    auto usable = [&](const Param& p) {
      return p.letter != 0 && p.kind != ValueKind::None && p.span.begin < stop && !lex::is_raw_text(c, p) &&
             !in_word(p);
    };
    for (const Param& p : pf.params(c)) {
      if (!usable(p)) continue;
      ParamRef first = pf.find(c, p.letter);
      if (first.is(p) || !usable(*first)) continue;
      // Report each later duplicate once: only against the first occurrence.
      const std::string name = p.letter >= 'a' ? fmt::format("'{}", p.letter) : std::string(1, p.letter);
      // An exact repeat (`S150 S150`) changes nothing: RRF reads the first, which says the same.
      if (pf.text(p.value) == pf.text(first->value)) continue;
      Report r =
          out.report(kMeta, cx.at(p.span),
                     fmt::format("'{}' is ignored: '{}' already has '{}', and RRF uses the first '{}'",
                                 clip(pf.text(p.span)), clip(lex::word(pf, c)), clip(pf.text(first->span)), name));
      r.note(cx.at(first->span), fmt::format("the first '{}' is here", name));
    }
  }
}

}  // namespace

extern const Rule duplicate_parameter{.meta = kMeta, .check_file = check};

}  // namespace rrflint
