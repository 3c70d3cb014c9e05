// RRF114 fractional-integer: a fraction where RRF reads an integer is silently dropped.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "lint/syntax/byte_classes.h"
#include "lint/syntax/values.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF114",
    .name = "fractional-integer",
    .severity = Severity::Warning,
    .summary = "A fractional value for a parameter RRF reads as an integer.",
    .docs = R"md(
## What it does
Reports a value with a non-zero fraction (`P0.5`) for parameters that RRF reads as whole numbers: tool, heater,
fan, sensor, probe, extruder and GPIO numbers and a few type selectors (`M563 P/D/H/F`, `M950 H/F/J/P/S/T`,
`M308 S`, `M106 P`, `M140`/`M141 H/P`, `M143 H`, `M307 H`, `M301 H`, `M570 H`, `G10 P/L`, `M568 P`, `M584 P`,
`M558 K/P`, `G31 K/P`, `M572 D`, `M591 D`, `M221 D`, `M207 P`, `M567 P`, `M116 P`), and a tool selection such
as `T1.5`. Driver numbers (`M569 P0.1`, `M584 X0.2`) are board.driver pairs, not fractions, and are not
checked. Expressions are not checked.

## Why is this bad?
RRF's integer reader stops at the `.` and keeps what came before, without a message: `M563 P0.5` defines tool
0. In a colon list the `.` also ends the list, so `M563 D0.5:1` gives the tool only extruder 0.

## Example
```gcode
M563 P1.5 D1 H2
M950 H1.1 C"out1" T1
```

## Use instead
```gcode
M563 P1 D1 H2
M950 H1 C"out1" T1
```

## References
- rrflint: [Numbers and lists](../firmware-behaviour.md#numbers-and-lists)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`ReadIValue()`, `ReadUIValue()`, `GetIntArray()`)
- [RRFLibraries SafeStrtod.cpp](https://github.com/Duet3D/RRFLibraries/blob/3.5-dev/src/General/SafeStrtod.cpp) (`StrToI32()`, `StrToU32()`)
)md",
};

struct IntParam {
  char letter;  // command letter
  int number;
  std::string_view params;  // the parameter letters read as integers
};

// Curated from the firmware's GetIValue/GetUIValue/GetLimitedUIValue/GetIntArray/GetUnsignedArray calls.
constexpr IntParam kIntParams[] = {
    {'M', 563, "PDHF"}, {'M', 950, "HFJPST"}, {'M', 308, "S"}, {'M', 106, "P"}, {'M', 140, "HP"}, {'M', 141, "HP"},
    {'M', 143, "H"},    {'M', 307, "H"},      {'M', 301, "H"}, {'M', 570, "H"}, {'G', 10, "PL"},  {'M', 568, "P"},
    {'M', 584, "P"},    {'M', 558, "KP"},     {'G', 31, "KP"}, {'M', 572, "D"}, {'M', 591, "D"},  {'M', 221, "D"},
    {'M', 207, "P"},    {'M', 567, "P"},      {'M', 116, "P"},
};

// The '.' of a number with a non-zero fraction ("0.5", "-1.25"), or npos. "1.0" and "2." are whole numbers. The '.'
// must follow the number's digits: RRF's reader stops at the first byte that cannot continue them, so in
// `0"x".5` it reads 0 and never meets the '.'.
size_t fraction_dot(std::string_view item) {
  const size_t dot = item.find('.');
  if (dot == std::string_view::npos) return dot;
  size_t at = 0;
  while (at < dot && lex::is_blank(item[at])) ++at;
  if (at < dot && (item[at] == '-' || item[at] == '+')) ++at;
  while (at < dot && lex::is_digit(item[at])) ++at;
  if (at != dot) return std::string_view::npos;
  for (size_t k = dot + 1; k < item.size() && lex::is_digit(item[k]); ++k)
    if (item[k] != '0') return dot;
  return std::string_view::npos;
}

// Could a '.' of `s` be in the value of one of `letters`? Each '.' outside strings and expressions belongs to the
// value of the last letter before it, unless that letter is an exponent E (then the parameters decide). A command
// whose dots are all in other values (G10 P0 X-0.4: P and L are the integer letters) needs no lexing.
bool dot_may_count(std::string_view t, Span s, std::string_view letters) {
  if (may_confuse_quotes(t, s)) return true;
  char last = 0;  // the last letter met, upper-cased; 0 before any
  bool may = false;
  lex::for_each_plain(t, s, [&](uint32_t k) {
    const char ch = t[k];
    if (lex::is_alpha(ch)) last = static_cast<char>(ch & ~0x20);
    else if (ch == '.' && (last == 0 || last == 'E' || letters.find(last) != std::string_view::npos)) may = true;
    return !may;
  });
  return may;
}

// Checks the integer parameters `letters` of `c`, a command of their code.
void check_command(const FileContext& cx, const Command& c, std::string_view letters, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  // A fraction makes it another command. The usual case: no '.' anywhere in the command, so no fraction (read
  // without lexing the parameters).
  if (c.fraction >= 0 || !lex::contains(pf.source->text(), c.span, '.')) return;
  // With the prefilters off (ParsedFile::Prefilters::off) this quick test stands aside, so that the fixtures and the
  // fuzzers check it against the full check.
  if (!pf.prefilters.off && !dot_may_count(pf.source->text(), c.span, letters)) return;
  uint32_t seen = 0;  // the letters met so far: RRF reads the first parameter with a letter
  for (const Param& param : pf.params(c)) {
    const Param* p = &param;
    const char letter = p->letter;
    if (letter < 'A' || letter > 'Z' || (seen & (1u << (letter - 'A')))) continue;
    seen |= 1u << (letter - 'A');
    if (letters.find(letter) == std::string_view::npos) continue;
    if (is_unknown_value(*p) || (p->kind != ValueKind::Number && p->kind != ValueKind::List)) continue;
    if (!lex::contains(pf.source->text(), p->value, '.')) continue;
    const std::vector<Span> items = list_items(pf, *p);
    for (size_t i = 0; i < items.size(); ++i) {
      const std::string_view item = pf.text(items[i]);
      const size_t dot = fraction_dot(item);
      if (dot == std::string_view::npos) continue;
      std::string kept(item.substr(0, dot));
      if (kept.find_first_of("0123456789") == std::string::npos) kept = "0";
      if (items.size() == 1) {
        out.report(kMeta, cx.at(items[i]),
                   fmt::format("'{}{}' in '{}': RRF reads {} as a whole number, uses {} and drops the fraction "
                               "silently",
                               letter, item, clip(lex::word(pf, c)), letter, kept));
      } else {
        const Span rest{items[i].begin + static_cast<uint32_t>(dot), p->value.end};
        out.report(
            kMeta, cx.at(items[i]),
            fmt::format("'{}' in the list '{}{}' of '{}': RRF reads whole numbers, uses {} and ends the "
                        "list at the '.', so '{}' is ignored",
                        item, letter, clip(pf.text(p->value)), clip(lex::word(pf, c)), kept, clip(pf.text(rest))));
      }
      break;  // RRF stops reading the parameter at the first '.'
    }
  }
}

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  for (const uint32_t i : pf.with_code('T', -1)) {
    const Command& c = pf.commands[i];
    if (c.fraction > 0 && c.has_number)
      out.report(kMeta, cx.at(c.word),
                 fmt::format("'{}' selects tool {}: RRF ignores the fraction of a tool number", clip(lex::word(pf, c)),
                             c.number));
  }
  for (const IntParam& ip : kIntParams)
    for (const uint32_t i : pf.with_code(ip.letter, ip.number)) check_command(cx, pf.commands[i], ip.params, out);
}

}  // namespace

extern const Rule fractional_integer{.meta = kMeta, .check_file = check};

}  // namespace rrflint
