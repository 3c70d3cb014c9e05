// RRF120 value-without-letter: a value after a blank with no parameter letter of its own, which RRF ignores.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "lint/syntax/byte_classes.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF120",
    .name = "value-without-letter",
    .severity = Severity::Warning,
    .tag = RuleTag::Unnecessary,
    .summary = "A value with no parameter letter in front of it; RRF ignores it.",
    .docs = R"md(
## What it does
Reports a number, a list, a quoted string or a `{…}` expression that stands after a blank with no parameter
letter of its own: `M92 X80 Y80 409:409` (where `E409:409` was meant), `G4 10`, `M106 P0 0.5`,
`M106 P0 {global.fan}`. The value may follow the command word (`G4 10`), a complete value of another letter
(`Y80 409:409`), or an E or e right after a digit, which RRF reads as an exponent and not as a letter
(`M307 H0e 3`).

It leaves alone:
- a blank between a letter and its value: `X 10` is `X10` (RRF's number reader skips leading blanks), and a
  blank after a `:` (`X80: 80`) continues the list;
- a blank before a `:` (`E409 :409`): that is [blank-before-colon](blank-before-colon.md) (RRF106), which
  reports the rest of the list once;
- an expression after a blank that follows the letter directly (`X {a}`): it is that letter's value as far as
  rrflint's parser goes (RRF itself wants the `{` right after the letter, and answers `expected number after
  'X'`), not a value without a letter;
- commands whose argument is unquoted text that runs to the end of the line (`M23`, `M28`, `M30`, `M32`, `M36`,
  `M117`, and `M98`/`M550`/`M551`): the blanks are part of the text;
- text that is not a value (`( … )` outside CNC mode is RRF112's, a bare word is RRF103's), and commands without
  a code number (`T 0` is a bare `T`);
- a value glued to the command word with no blank before it (`G4-5`, `G4{5}`): RRF ignores it as well, but the
  rule looks only at values after a blank.

## Why is this bad?
RRF finds a parameter by its letter (`Seen()`) and reads the value right after it, up to the first character
that cannot continue it. A value with no letter in front of it is never looked up, so it is skipped without a
message: `M92 X80 Y80 409:409` leaves the extruder steps at their default, `G4 10` waits for nothing, and
`M106 P0 0.5` switches fan 0 fully on (S is missing, so the default 1.0 is used).

## Example
```gcode
M92 X80 Y80 Z400 409:409
M106 P0 0.5
G4 10
```

## Use instead
```gcode
M92 X80 Y80 Z400 E409:409
M106 P0 S0.5
G4 S10
M906 X 800 Y 800
```

## References
- rrflint: [Parameters](../firmware-behaviour.md#parameters)
- RepRapFirmware 3.5: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodeBuffer/StringParser.cpp) (`Seen()` scans for the letter; `ReadFloatValue()` reads the number after it)
- RRFLibraries: [NumericConverter.cpp](https://github.com/Duet3D/RRFLibraries/blob/3.5-dev/src/General/NumericConverter.cpp) (`Accumulate()` skips leading blanks, so `X 10` is `X10`)
- See also: [blank-before-colon](blank-before-colon.md) (RRF106), for `E409 :409`
)md",
};

/// Where a second value starts after a blank inside the value `v` of a lettered parameter (`80 409:409`), or
/// v.end. A blank after ':' continues the list; a blank before ':' ends it, and what follows is RRF106's.
uint32_t second_value(std::string_view t, Span v) {
  bool quoted = false;
  int braces = 0;
  for (uint32_t k = v.begin; k < v.end; ++k) {
    const char ch = t[k];
    if (ch == '"') quoted = !quoted;
    if (quoted || ch == '"') continue;
    if (ch == '{' || ch == '}') {
      braces += ch == '{' ? 1 : (braces > 0 ? -1 : 0);
      continue;
    }
    if (braces > 0 || !lex::is_blank(ch)) continue;
    uint32_t e = k;
    while (e < v.end && lex::is_blank(t[e])) ++e;
    if (e >= v.end || t[e] == ':') return v.end;
    if (t[k - 1] != ':') return e;
    k = e - 1;
  }
  return v.end;
}

/// The end of the stray text that starts at `b`: the value's end, or the blank before a ':' (RRF106 reports on).
uint32_t stray_end(std::string_view t, uint32_t b, Span v) {
  uint32_t end = v.end;
  lex::for_each_plain(t, Span{b, v.end}, [&](uint32_t k) {
    if (t[k] != ':' || !lex::is_blank(t[k - 1])) return true;
    end = k;
    return false;
  });
  while (end > b && lex::is_blank(t[end - 1])) --end;
  return end;
}

void check_command(const FileContext& cx, const Command& c, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  std::string_view before = lex::word(pf, c);  // what RRF reads up to the stray value
  for (const Param& p : pf.params(c)) {
    uint32_t b = p.value.begin;
    if (p.letter != 0) {
      b = second_value(t, p.value);
      before = pf.text(Span{p.span.begin, b});
      while (!before.empty() && lex::is_blank(before.back())) before.remove_suffix(1);
    }
    if (b >= p.value.end || !starts_value(t[b]) || lex::is_raw_text(c, p)) continue;
    // Only a value after a blank: one glued to the command word (`G4-5`, `G4{5}`) is ignored by RRF as well, but
    // it is not this rule's (may_hold_stray_value, which every normal run goes through, looks after blanks only).
    if (p.letter == 0 && !lex::is_blank(t[b - 1])) continue;
    // And not after a letter (`S"a"uses 1`: the S of `uses` takes the 1 in RRF, whatever the lexer made of the
    // text glued to the string); an exponent's E is no letter (`H0e 3`).
    if (!blanks_after_non_letter(t, c.span.begin, b)) continue;
    const Span stray{b, p.letter != 0 ? stray_end(t, b, p.value) : p.value.end};
    const std::string_view text = pf.text(stray);
    out.report(kMeta, cx.at(stray),
               fmt::format("'{}' has no parameter letter: RRF reads '{}' and ignores it (write the letter it is "
                           "meant for)",
                           clip(text), clip(before)));
  }
}

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  // A line's code holds its commands, so a line the parse left out of the set (ParsedFile::Prefilters) or that
  // may_hold_stray_value clears has no command it would pass: most lines are skipped without decoding them. With
  // the prefilters off that test is skipped too, so that the fixtures and the fuzzers check it against the rule.
  const bool quick = !pf.prefilters.off;
  for (const uint32_t li : pf.prefilters.stray_value_lines) {
    if (pf.lines.kind(li) != LineKind::Commands || (quick && !may_hold_stray_value(t, pf.lines.code(li)))) continue;
    const Line line = pf.lines[li];
    for (uint32_t i = line.first_command; i < line.first_command + line.command_count; ++i) {
      const Command c = pf.commands[i];
      if (!c.has_number || c.number_expr || takes_rest_of_line(c.letter, c.number)) continue;
      if (quick && !may_hold_stray_value(t, c.span)) continue;
      check_command(cx, c, out);
    }
  }
}

}  // namespace

extern const Rule value_without_letter{.meta = kMeta, .check_file = check};

}  // namespace rrflint
