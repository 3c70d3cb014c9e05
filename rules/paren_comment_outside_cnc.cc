// RRF112 paren-comment-outside-cnc: `( … )` is a comment only in CNC mode (after M453).
#include <algorithm>

#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF112",
    .name = "paren-comment-outside-cnc",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary = "Text in parentheses used as a comment outside CNC mode.",
    .docs = R"md(
## What it does
Reports `( … )` after a command, outside quotes and `{…}`, on lines RRF reads in FFF or laser mode: before any
`M453` in the file, or after an `M451`/`M452`. Files that do not switch the mode themselves are skipped when
another file of the machine selects CNC mode (`M453`), since they may run in it. Unquoted text (`M117 Done (50%)`)
is copied as written and not reported; parentheses in meta-command expressions are arithmetic.

## Why is this bad?
The standalone firmware treats `( … )` as a comment only in CNC mode. Elsewhere the text stays part of the
command: its letters become parameters (`(fan off)` adds `F`, `A`, `N`, `O` …), and an `M` or `G` in it starts a
new command. In SBC mode the DuetSoftwareFramework parser always drops it, so the same line behaves differently
on the two set-ups.

## Example
```gcode
M106 P0 S0 (part fan off)
```

## Use instead
```gcode
M106 P0 S0 ; part fan off
```

## Fix safety
When the parentheses end the line and the line has no `;` comment, the fix turns them into a `;` comment. It
is unsafe: it changes what the standalone firmware reads, to what the author meant.

## References
- rrflint: [Comments](../firmware-behaviour.md#comments), [The SBC parser](../firmware-behaviour.md#the-sbc-parser)
- Duet3D G-code dictionary: [Comments](https://docs.duet3d.com/User_manual/Reference/Gcodes#comments), [M453](https://docs.duet3d.com/User_manual/Reference/Gcodes#m453-select-cnc-device-mode)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`Put()`: the `(` case tests the machine type)
- [DSF ParserAsync.cs](https://github.com/Duet3D/DuetSoftwareFramework/blob/v3.5.3/src/DuetAPI/Commands/Code/ParserAsync.cs)
)md",
};

bool sets_mode(const Command& c) { return c.is('M', 451) || c.is('M', 452) || c.is('M', 453); }

// Is `off` inside unquoted text that RRF copies as written (M117 text, M550 PName)?
bool in_raw_text(const ParsedFile& pf, const Line& line, uint32_t off) {
  for (uint32_t i = line.first_command; i < line.first_command + line.command_count; ++i) {
    const Command& c = pf.commands[i];
    for (const Param& p : pf.params(c))
      if (lex::is_raw_text(c, p) && off >= p.value.begin && off < p.value.end) return true;
  }
  return false;
}

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const std::string_view t = pf.source->text();
  // The machine mode is global: a file that never sets it may run in the CNC mode another file selects.
  std::vector<uint32_t> switches;  // the commands that set the mode, in order
  for (int n : {451, 452, 453})
    for (const uint32_t i : pf.with_code('M', n))
      if (sets_mode(pf.commands[i])) switches.push_back(i);
  std::sort(switches.begin(), switches.end());
  if (switches.empty() && cx.machine.uses_code('M', 453)) return;
  bool cnc = false;
  size_t next_switch = 0;
  for (const uint32_t li : pf.prefilters.paren_lines) {  // command lines whose code holds a '('
    // The mode switches of earlier lines (a switch applies from the next line).
    for (; next_switch < switches.size() && pf.commands[switches[next_switch]].line < li; ++next_switch)
      cnc = pf.commands[switches[next_switch]].number == 453;
    const Line& line = pf.lines[li];
    // The set may over-approximate (ParsedFile::Prefilters): only command lines, not meta commands, are checked.
    if (!cnc && line.kind == LineKind::Commands) {
      std::vector<Span> groups;
      lex::for_each_plain(t, line.code, [&](uint32_t k) {
        if (t[k] != '(' || in_raw_text(pf, line, k)) return true;
        if (!groups.empty() && k < groups.back().end) return true;  // nested '(' inside a group
        uint32_t e = k + 1;
        while (e < line.code.end && t[e] != ')') ++e;
        groups.push_back(Span{k, e < line.code.end ? e + 1 : line.code.end});
        return true;
      });
      for (const Span& g : groups) {
        Report r = out.report(kMeta, cx.at(g),
                              fmt::format("'{}' is not a comment outside CNC mode: standalone RRF reads its letters "
                                          "as parameters (SBC mode drops it); use ';' for a comment",
                                          clip(pf.text(g))));
        const bool last = g.end == line.code.end && g.end > g.begin + 1 && t[g.end - 1] == ')';
        if (last && line.comment.empty() && &g == &groups.back()) {
          std::string_view inner = t.substr(g.begin + 1, g.end - g.begin - 2);
          while (!inner.empty() && lex::is_blank(inner.front())) inner.remove_prefix(1);
          r.fix(Fix::unsafe("make it a ';' comment", Edit::replace(cx.at(g), fmt::format("; {}", inner))));
        }
      }
    }
  }
}

}  // namespace

extern const Rule paren_comment_outside_cnc{.meta = kMeta, .check_file = check, .whole_card = true};

}  // namespace rrflint
