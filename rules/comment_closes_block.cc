// RRF109 comment-closes-block: before 3.6.0-beta.3 a comment at column 0 ends every open block.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"
#include "rules/version_gate.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF109",
    .name = "comment-closes-block",
    .severity = Severity::Error,
    .fix = FixAvailability::Always,
    .summary = "A comment at column 0 ends the open if/while block on firmware before 3.6.0-beta.3.",
    .docs = R"md(
## What it does
On targets before RRF 3.6.0-beta.3, reports a whole-line `;` comment at column 0 that sits inside an `if`,
`elif`, `else` or `while` block:
- `error` when the next code line is `else` or `elif`;
- `warning` when the next code line is still indented under the block, so it belonged to it.

A column-0 comment after the last line of a block (the next code line is back at the block's own level) is
harmless and not reported. Indented comments never matter.

## Firmware versions
A **hazard** of RRF before 3.6.0-beta.3, whose parser ends a block at a column-0 comment. At such a target it keeps
its severity. When no `--firmware` is given and the files do not rule out such a version (the target is newer, but
nothing in the files needs a version that new), it is reported as `info` with a note that names the versions and
the evidence; see [Firmware target](../firmware-behaviour.md#firmware-target).

## Why is this bad?
RRF stores a column-0 comment as a command at indent 0, and every line at indent 0 ends the open blocks.
An `else`/`elif` after it then fails with `'else' did not follow 'if'` when the condition was false: that is a
meta-command error, which aborts the rest of config.g. When the block continues after the comment, its
remaining lines run even though the condition was false, or, in a `while` loop, once after the loop instead of
in every pass. RRF 3.6.0-beta.3 fixed this (Duet3D/RepRapFirmware issue 860).

## Example
```gcode
; rrflint-options: --firmware 3.5
if sensors.probes[0].value[0] > 500
  M291 P"Probe triggered" S1
; explain the next step
  M112
else
  M98 P"probe-ok.g"
```

## Use instead
```gcode
; rrflint-options: --firmware 3.5
if sensors.probes[0].value[0] > 500
  M291 P"Probe triggered" S1
  ; explain the next step
  M112
else
  M98 P"probe-ok.g"
```

## Fix safety
The fix indents the comment like the line before it, which is what RRF 3.6.0-beta.3 and later do anyway. It is
safe: it keeps the block as its indentation shows it.

## References
- rrflint: [Comments](../firmware-behaviour.md#comments) (column-0 comments and blocks), [Errors and aborts](../firmware-behaviour.md#errors-and-aborts)
- Duet3D meta commands: [Indentation of comments](https://docs.duet3d.com/User_manual/Reference/Gcode_meta_commands#indentation-of-comments), [Blocks and indentation](https://docs.duet3d.com/User_manual/Reference/Gcode_meta_commands#blocks-and-indentation)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`Put()`, `CheckMetaCommand()`, `ProcessElseCommand()`)
- [RepRapFirmware issue 860](https://github.com/Duet3D/RepRapFirmware/issues/860) (fixed for 3.6.0-beta.3)
)md",
};

constexpr Version kFixedIn{3, 6, 0, 1, 3};  // 3.6.0-beta.3

struct Block {
  uint32_t indent;       // the indent of the block's lines
  MetaKind opener;       // if/elif/else/while, or None for a plain block (extra indentation)
  uint32_t head;         // the line that opened it
  uint32_t head_indent;  // and its indent
};

bool is_code(LineKind k) { return k == LineKind::Commands || k == LineKind::Meta || k == LineKind::Bad; }

bool conditional(MetaKind k) {
  return k == MetaKind::If || k == MetaKind::Elif || k == MetaKind::Else || k == MetaKind::While;
}

void check(const FileContext& cx, Sink& out) {
  constexpr auto before_fix = [](Version v) { return v < kFixedIn; };
  const std::optional<gate::Gate> g = gate::hazard(cx.target, before_fix, Severity::Error);
  if (!g) return;
  constexpr std::string_view kVersions = "before 3.6.0-beta.3";
  const std::string on = gate::on(*g, cx.target, kVersions);
  const Severity warning = g->at == HazardAt::Target ? Severity::Warning : Severity::Info;
  const ParsedFile& pf = cx.parsed();
  const LineTable& lines = pf.lines;
  std::vector<Block> open;  // blocks with indent > 0, innermost last, as the lines' indentation shows them
  // The previous code line. Lines are read from their records field by field: most lines are code lines, and
  // decoding each whole (its comment) took a third of the rule's time.
  constexpr uint32_t kNone = UINT32_MAX;
  uint32_t prev = kNone, prev_indent = 0;
  MetaKind prev_meta = MetaKind::None;
  for (size_t i = 0; i < lines.size(); ++i) {
    const LineKind kind = lines.kind(i);
    if (is_code(kind)) {
      const uint32_t indent = lines.indent(i);
      while (!open.empty() && indent < open.back().indent) open.pop_back();
      if (prev != kNone && indent > prev_indent && (open.empty() || indent > open.back().indent))
        open.push_back(Block{indent, prev_meta, prev, prev_indent});
      prev = static_cast<uint32_t>(i);
      prev_indent = indent;
      prev_meta = lines.meta(i);
      continue;
    }
    if (kind != LineKind::Comment || open.empty() || prev == kNone) continue;
    // A run of column-0 comments (blank lines may sit between them): the first one closes the blocks.
    const Line line = lines[i];
    std::vector<Span> run{line.span};
    size_t j = i + 1;
    for (; j < lines.size() && !is_code(lines.kind(j)); ++j)
      if (lines.kind(j) == LineKind::Comment) run.push_back(lines.span(j));
    i = j - 1;
    if (j >= lines.size()) continue;
    const Line next = lines[j];

    Fix fix = Fix::safe("indent the comment like the block");
    const std::string indent(pf.text(lex::indentation(pf, lines[prev])));
    for (const Span& c : run) fix.edits.push_back(Edit::insert(cx.at(Span{c.begin, c.begin}), indent));
    const Span at{line.span.begin, line.span.begin + 1};
    const uint32_t next_no = cx.source().position(next.span.begin).line;

    if ((next.meta == MetaKind::Else || next.meta == MetaKind::Elif) && prev_indent > next.indent) {
      // The block the else/elif continues is the one opened at the else's own level.
      const Block* head = nullptr;
      for (const Block& b : open)
        if (b.head_indent == next.indent && (b.opener == MetaKind::If || b.opener == MetaKind::Elif)) head = &b;
      if (!head) continue;  // an else/elif with no if is a syntax error (RRF100)
      Report r =
          out.report(kMeta, g->severity, cx.at(at),
                     fmt::format("comment at column 0 ends the open blocks on {}: the '{}' on line {} then fails "
                                 "with \"'{}' did not follow 'if'\" when the condition is false, which aborts the "
                                 "rest of the file",
                                 on, meta_keyword(next.meta), next_no, meta_keyword(next.meta)));
      r.note(cx.at(lines.code(head->head)), fmt::format("the '{}' opens here", meta_keyword(head->opener)));
      gate::explain(r, *g, cx.target, cx.at(at), kVersions);
      r.fix(std::move(fix));
      continue;
    }
    // The blocks the next line would have continued: those at or below its indent.
    const Block* escaped = nullptr;
    for (const Block& b : open)
      if (b.indent <= next.indent && conditional(b.opener)) escaped = &b;
    if (!escaped) continue;  // the comment follows the last line of the block: harmless
    const bool loop = escaped->opener == MetaKind::While;
    Report r =
        out.report(kMeta, warning, cx.at(at),
                   fmt::format("comment at column 0 ends the '{}' block on {}: line {} and the rest of the block {}",
                               meta_keyword(escaped->opener), on, next_no,
                               loop ? "run once after the loop instead of in every pass"
                                    : "run even when the condition is false"));
    r.note(cx.at(lines.code(escaped->head)), fmt::format("the '{}' block opens here", meta_keyword(escaped->opener)));
    gate::explain(r, *g, cx.target, cx.at(at), kVersions);
    r.fix(std::move(fix));
  }
}

}  // namespace

extern const Rule comment_closes_block{.meta = kMeta, .check_file = check};

}  // namespace rrflint
