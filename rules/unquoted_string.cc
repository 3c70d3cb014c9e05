// RRF103 unquoted-string: a string parameter written without the quotes RRF 3 requires.
#include <algorithm>

#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "lint/syntax/byte_classes.h"
#include "rules/edit_parses.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF103",
    .name = "unquoted-string",
    .severity = Severity::Error,
    .fix = FixAvailability::Sometimes,
    .summary = "A string parameter is given without the quotes RRF 3 requires.",
    .docs = R"md(
## What it does
Checks the string parameters that RRF 3 reads with `GetQuotedString()`: pin names (`M950 C`, `M308 P`, `M574 P`,
`M558 C`, `M591 C`), the sensor type and name of `M308` (`Y`, `A`), the tool name `M563 S`, and the macro file
name of `M98 P` from RRF 3.5. It reports a value that does not start with `"` (or `{` for an expression) right
after the letter, including a blank between the letter and the quote (`P "xstop"`; for `M98` in every RRF 3
version, since older ones take the blank and the quotes as part of the file name).

Numbers given as pin names (`C3`) are reported only for `M950` and `M308`, which exist only in RRF 3: in
RRF 2 `M558 C3` and `M591 C3` were endstop numbers. An unquoted `M98` file name is reported when the target is
given (`--firmware`) as 3.5 or later, or when the files show 3.5 features; an inferred target alone is not
enough, since the unquoted name itself suggests a config written for 3.4 or earlier.

## Firmware versions
A **hazard** of the versions that need quotes for the parameter. It is judged at the target only. An unquoted M98
file name needs a given target or evidence of 3.5 or later.

## Why is this bad?
RRF answers `expected a string expression` and rejects the command: the pin, sensor, endstop or tool is not
configured. RRF 3 also splits an unquoted `xstop` into parameters `X`, `S`, `T`, `O`, `P`. For `M98`, RRF 3.4
and earlier accepted an unquoted name; from 3.5 the macro is not run at all.

## Example
```gcode
M574 X1 S1 Pxstop
M950 H0 C bedheat T0
M98 Pmacros/leds.g
```

## Use instead
```gcode
M574 X1 S1 P"xstop"
M950 H0 C"bedheat" T0
M98 P"macros/leds.g"
```

## Fix safety
Removing a blank between the letter and its quoted string is safe. Adding quotes around unquoted text is
unsafe: rrflint takes the text up to the next blank (for `M98`, the rest of the line), which may not be all
that was meant. Neither fix is offered when the line, fixed, would not parse: a string that the line never
closes (`M98 P "a.g ; note`), or a control byte in text that would be quoted.

## References
- rrflint: [Strings](../firmware-behaviour.md#strings)
- Duet3D G-code dictionary: [Quoted strings](https://docs.duet3d.com/User_manual/Reference/Gcodes#quoted-strings), [M98: call macro/subprogram](https://docs.duet3d.com/User_manual/Reference/Gcodes#m98-call-macrosubprogram)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`GetQuotedString()`), [GCodeBuffer.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/GCodeBuffer.cpp) (`GetReducedString()`), [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (case 98); [3.4.6 GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.4.6/src/GCodes/GCodes2.cpp) (case 98 still unquoted)
)md",
};

struct StringParam {
  int number;        // M code
  char letter;       // parameter letter
  bool numbers_too;  // report a plain number as well (commands that exist only in RRF 3)
  std::string_view what;
};

// The entries of one code are adjacent (check() walks a code's commands once for all its letters).
constexpr StringParam kStringParams[] = {
    {98, 'P', true, "macro file name"}, {950, 'C', true, "pin name"},    {308, 'P', true, "pin name"},
    {308, 'Y', true, "sensor type"},    {308, 'A', true, "sensor name"}, {574, 'P', false, "pin name"},
    {558, 'C', false, "pin name"},      {591, 'C', false, "pin name"},   {563, 'S', false, "tool name"},
};

// M98 P uses GetQuotedString from 3.5.0-rc.1; the other parameters need quotes in every RRF 3.
Version needs_quotes_from(int number) { return number == 98 ? kRrf3_5_0_rc1 : kRrf3_0; }

void check_param(const FileContext& cx, const Command& c, const Param& p, const StringParam& sp, bool quotes_needed,
                 Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  if (p.letter == 0) return;
  const uint32_t after = p.span.begin + 1;  // right after the letter
  // The line's code, not the command: RRF would also end the command at the 'm' of an unquoted "thermistor".
  const uint32_t end = pf.lines.code(c.line).end;
  if (after >= end) return;  // no value at all: a different mistake
  const char letter = sp.letter;
  uint32_t b = after;
  while (b < end && lex::is_blank(t[b])) ++b;
  if (b >= end) return;
  if (t[b] == '"' || t[b] == '{') {
    if (b == after) return;
    Report r =
        out.report(kMeta, cx.at(Span{p.span.begin, b + 1}),
                   fmt::format("blank between '{}' and the {} {} in '{}': {}", letter,
                               t[b] == '"' ? "quoted" : "expression for the", sp.what, clip(lex::word(pf, c)),
                               quotes_needed ? fmt::format("RRF looks for the {} right after the letter and fails with "
                                                           "'expected a string expression'",
                                                           t[b] == '"' ? "quote" : "'{'")
                                             : std::string("RRF takes the blank and what follows as the file name, "
                                                           "quotes included, and finds no such file")));
    // Not when the string or expression never closes on the line: without the blank it would be read as one (the
    // blank made M98 take the rest of the line as a name), a new syntax error.
    if (tools::edit_parses(pf, c.line, Span{after, b}, "", c.cnc))
      r.fix(Fix::safe(fmt::format("remove the blank after '{}'", letter), Edit::remove(cx.at(Span{after, b}))));
    return;
  }
  if (!quotes_needed) return;
  // Unquoted text: for M98 the rest of the command, otherwise up to the next blank.
  uint32_t e = b;
  if (sp.number == 98) e = end;
  else
    while (e < end && !lex::is_blank(t[e])) ++e;
  const std::string_view text = t.substr(b, e - b);
  bool has_letter = false;
  for (char ch : text) has_letter = has_letter || lex::is_alpha(ch);
  if (!has_letter && !sp.numbers_too) return;
  if (text.find('"') != std::string_view::npos || text.find('{') != std::string_view::npos) return;
  std::string why = sp.number == 98 ? fmt::format(
                                          "RRF {} needs quotes here and does not run the macro ('expected a string "
                                          "expression')",
                                          cx.target.version.str())
                                    : std::string(
                                          "RRF 3 needs quotes here and rejects the command ('expected a string "
                                          "expression')");
  Report r = out.report(kMeta, cx.at(Span{p.span.begin, e}),
                        fmt::format("unquoted {} '{}' in '{}': {}", sp.what, clip(text), clip(lex::word(pf, c)), why));
  // Not when the quoted text would not parse: a control byte ends a quoted string (RRF rejects it there).
  const std::string quoted = fmt::format("\"{}\"", text);
  if (tools::edit_parses(pf, c.line, Span{after, e}, quoted, c.cnc))
    r.fix(Fix::unsafe(fmt::format("quote '{}'", clip(text)), Edit::replace(cx.at(Span{after, e}), quoted)));
}

// Is the target certainly one that needs quotes for this command? An unquoted M98 file name is itself a sign of
// a config written for 3.4 or earlier, so an inferred target needs evidence (stated or a floor) of 3.5 or later.
bool needs_quotes(const Target& target, int number) {
  const Version from = needs_quotes_from(number);
  if (target.version < from) return false;
  if (number != 98 || target.version_given) return true;
  for (const Evidence& e : target.evidence)
    if (e.version >= kRrf3_5) return true;  // a hint or a floor
  return false;
}

// The letters (bit L - 'A') of `s` that occur outside strings and expressions with something other than '"' or
// '{' right after them. A letter not among them has a quoted value wherever it stands as a parameter, so
// check_param would find nothing: most commands are cleared by this scan, without lexing their parameters.
uint32_t letters_without_quote(std::string_view t, Span s) {
  if (may_confuse_quotes(t, s)) return ~0u;
  uint32_t out = 0;
  lex::for_each_plain(t, s, [&](uint32_t k) {
    const char ch = t[k];
    if (lex::is_alpha(ch) && (k + 1 >= s.end || (t[k + 1] != '"' && t[k + 1] != '{')))
      out |= 1u << ((ch & ~0x20) - 'A');
    return true;
  });
  return out;
}

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  if (cx.target.version < kRrf3_0) return;
  // By code, then by command, then by letter: a command's parameters are lexed once for all its letters.
  for (const StringParam& first : kStringParams) {
    if (&first != kStringParams && first.number == (&first)[-1].number) continue;  // the code was done
    const bool quotes_needed = needs_quotes(cx.target, first.number);
    // A blank before the quote of an M98 file name breaks every version; other checks need the target.
    if (!quotes_needed && first.number != 98) continue;
    for (const uint32_t i : pf.with_code('M', first.number)) {
      const Command& c = pf.commands[i];
      if (c.fraction >= 0) continue;
      // With the prefilters off (ParsedFile::Prefilters::off) the scan stands aside, so that the fixtures and the
      // fuzzers check it against check_param.
      const uint32_t unquoted = pf.prefilters.off ? ~0u : letters_without_quote(pf.source->text(), c.span);
      for (const StringParam* sp = &first; sp != std::end(kStringParams) && sp->number == first.number; ++sp)
        // RRF reads the first occurrence of the letter (Seen()).
        if (unquoted & (1u << (sp->letter - 'A')))
          if (ParamRef p = pf.find(c, sp->letter)) check_param(cx, c, *p, *sp, quotes_needed, out);
    }
  }
}

}  // namespace

extern const Rule unquoted_string{.meta = kMeta, .check_file = check};

}  // namespace rrflint
