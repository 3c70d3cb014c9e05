// RRF108 mixed-indentation: tabs and spaces both indent one block, which RRF warns about.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF108",
    .name = "mixed-indentation",
    .severity = Severity::Warning,
    .summary = "Tabs and spaces both indent the lines of one block.",
    .docs = R"md(
## What it does
Follows RRF's own check: once a file has used a meta command (`if`, `while`, `var` …), RRF collects the
indentation characters of the lines up to the next line at column 0. When both tabs and spaces have been used
in that stretch, it warns once per file. rrflint reports the same line, once per file. Blank lines and indented
comments do not count. Different blocks may use different characters: a line at column 0 starts afresh.

## Why is this bad?
RRF counts a space as 1 and moves a tab on to the next multiple of 4. Lines that look aligned in an editor can
have different indents to RRF, which then ends a block early or opens a new one. RRF prints
`both space and tab characters used to indent blocks at/before line N`.

## Example
```gcode
if !move.axes[0].homed
	G28 X          ; a tab
    G28 Y          ; four spaces
```

## Use instead
```gcode
if !move.axes[0].homed
  G28 X
  G28 Y
```

## References
- rrflint: [Indentation and blocks](../firmware-behaviour.md#indentation-and-blocks)
- Duet3D meta commands: [Blocks and indentation](https://docs.duet3d.com/User_manual/Reference/Gcode_meta_commands#blocks-and-indentation)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`Put()` tab rule, `CheckMetaCommand()`, `CheckForMixedSpacesAndTabs()`)
)md",
};

void check(const FileContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  if (!pf.prefilters.any_tab_indent) return;  // the parse's summary: spaces alone never mix
  bool seen_meta = false;
  std::optional<Line> first_space;  // the first line since the last column-0 line that indented with a space
  std::optional<Line> first_tab;
  auto mixed = [&] { return seen_meta && first_space && first_tab; };
  for (const Line& line : pf.lines) {
    // Blank lines and indented comments take no part in blocks: skip them (RRF counts their blanks too, but
    // they cannot change what a block contains).
    if (line.kind == LineKind::Blank) continue;
    if (line.indent == 0) {
      first_space = first_tab = std::nullopt;
    } else {
      if (line.indent_spaces && !first_space) first_space = line;
      if (line.indent_tabs && !first_tab) first_tab = line;
    }
    if (line.kind == LineKind::Meta) seen_meta = true;
    if (line.indent > 0 && mixed()) {
      const bool tab_here = line.indent_tabs;
      std::optional<Line> other = tab_here ? first_space : first_tab;
      if (line.indent_tabs && line.indent_spaces) other = std::nullopt;
      Report r = out.report(
          kMeta, cx.at(lex::indentation(pf, line)),
          fmt::format("{}: RRF counts a tab as up to 4 blanks and warns 'both space and tab characters used to "
                      "indent blocks'",
                      other ? fmt::format("this block is indented with both tabs and spaces: {} here, {} above",
                                          tab_here ? "tabs" : "spaces", tab_here ? "spaces" : "tabs")
                            : std::string("this line is indented with both tabs and spaces")));
      if (other)
        r.note(cx.at(lex::indentation(pf, *other)), fmt::format("indented with {} here", tab_here ? "spaces" : "tabs"));
      return;  // once per file, like RRF
    }
    // Before the first meta command RRF starts every line afresh.
    if (!seen_meta) first_space = first_tab = std::nullopt;
  }
}

}  // namespace

extern const Rule mixed_indentation{.meta = kMeta, .check_file = check};

}  // namespace rrflint
