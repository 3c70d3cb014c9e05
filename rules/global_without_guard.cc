// RRF504 global-without-guard: `global x = …` at boot without an exists() guard.
#include <fmt/format.h>

#include <set>

#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF504",
    .name = "global-without-guard",
    .severity = Severity::Warning,
    .summary = "A global variable is declared at boot without an exists() guard.",
    .docs = R"md(
## What it does
Reports `global name = …` in config.g or a file it runs at boot, unless the declaration sits inside an `if`
(or the `else` of an `if`) whose condition tests `exists(global.…)`.

## Why is this bad?
config.g runs again on `M502` and on `M98 P"config.g"`. The second `global` declaration then fails with
`variable 'name' already exists`, a meta-command error that **aborts the rest of config.g**.

## Example
```gcode
global maxTemp = 280
```

## Use instead
```gcode
if !exists(global.maxTemp)
  global maxTemp = 280
```

## References
- rrflint: [Meta commands](../firmware-behaviour.md#meta-commands), [Errors and aborts](../firmware-behaviour.md#errors-and-aborts)
- Duet3D meta commands: [Global variable declaration](https://docs.duet3d.com/User_manual/Reference/Gcode_meta_commands#global-variable-declaration)
- RepRapFirmware 3.5.3: [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodeBuffer/StringParser.cpp) (`ProcessVarOrGlobalCommand()`), [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (a meta-command error aborts the file)
- [RepRapFirmware issue 704](https://github.com/Duet3D/RepRapFirmware/issues/704)
)md",
};

bool guarded(const ParsedFile& pf, size_t li) {
  uint32_t threshold = pf.lines[li].indent;
  for (size_t k = li; k-- > 0;) {
    const Line& l = pf.lines[k];
    if (l.kind != LineKind::Meta && l.kind != LineKind::Commands && l.kind != LineKind::Bad) continue;
    if (l.indent >= threshold) continue;
    // An enclosing block opener, or an else/elif whose if-chain is at the same indentation.
    const uint32_t level = l.indent;
    for (size_t j = k + 1; j-- > 0;) {
      const Line& c = pf.lines[j];
      if (c.kind != LineKind::Meta && c.kind != LineKind::Commands && c.kind != LineKind::Bad) continue;
      if (c.indent < level) break;
      if (c.indent > level) continue;
      if ((c.meta == MetaKind::If || c.meta == MetaKind::Elif || c.meta == MetaKind::While) &&
          pf.text(c.meta_arg).find("exists(global.") != std::string_view::npos)
        return true;
      if (j == k && (c.meta == MetaKind::Else || c.meta == MetaKind::Elif)) continue;  // walk its if-chain
      if (j != k && c.meta == MetaKind::Elif) continue;
      break;
    }
    threshold = level;
    if (level == 0) break;
  }
  return false;
}

void check(const EndContext& cx, Sink& out) {
  std::set<uint32_t> boot_units;
  for (const Segment& seg : cx.graph.segments) {
    if (!seg.boot) continue;
    cx.graph.nodes.find_if(seg.begin, seg.end, [&](NodeId, const Node& n) {
      if (n.kind == NodeKind::Enter) boot_units.insert(n.unit);
      return false;
    });
  }
  for (uint32_t u : boot_units) {
    const FileUnit& fu = cx.machine.unit(u);
    const ParsedFile& pf = fu.parsed;
    for (size_t li = 0; li < pf.lines.size(); ++li) {
      const Line& l = pf.lines[li];
      if (l.meta != MetaKind::Global || l.meta_name.empty()) continue;
      if (guarded(pf, li)) continue;
      out.report(kMeta, Location{fu.source->id(), l.code},
                 fmt::format("'global {}' has no 'exists(global.{})' guard: when config.g runs again (M502, M98 "
                             "P\"config.g\") it fails with 'variable already exists' and aborts the rest of config.g",
                             pf.text(l.meta_name), pf.text(l.meta_name)));
    }
  }
}

}  // namespace

extern const Rule global_without_guard{.meta = kMeta, .check_end = check};

}  // namespace rrflint
