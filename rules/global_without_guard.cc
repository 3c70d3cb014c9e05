// RRF504 global-without-guard: `global x = …` at boot without an exists() guard.
#include <fmt/format.h>

#include <set>
#include <vector>

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

bool code_line(const Line& l) {
  return l.kind == LineKind::Meta || l.kind == LineKind::Commands || l.kind == LineKind::Bad;
}

// Reports the unguarded declarations of one file in a single pass. The stack holds, innermost last, each line that
// encloses the current one (the nearest earlier code line of smaller indentation, then the one enclosing that, and
// so on): a declaration is guarded when one of them is an if/elif/while testing exists(global.…), or an elif/else
// of an if-chain where an earlier if/elif does. A walk back from each declaration instead was quadratic: with
// nothing enclosing a declaration at indentation 0, it walked to the start of the file.
void check_file(const FileUnit& fu, Sink& out) {
  const ParsedFile& pf = fu.parsed;
  struct Open {
    uint32_t indent;
    bool tests;     // it, or the if-chain it ends, tests exists(global.…)
    bool if_chain;  // an if or elif, which a following elif or else at its indentation continues
    bool guarded;   // it or an enclosing line tests exists(global.…)
  };
  std::vector<Open> open;
  for (size_t li = 0; li < pf.lines.size(); ++li) {
    const Line& l = pf.lines[li];
    if (!code_line(l)) continue;
    while (!open.empty() && open.back().indent > l.indent) open.pop_back();
    bool chain_tests = false;
    if (!open.empty() && open.back().indent == l.indent) {
      if (open.back().if_chain) chain_tests = open.back().tests;
      open.pop_back();
    }
    const bool enclosed = !open.empty() && open.back().guarded;
    if (l.meta == MetaKind::Global && !l.meta_name.empty() && !enclosed)
      out.report(kMeta, Location{fu.source->id(), l.code},
                 fmt::format("'global {}' has no 'exists(global.{})' guard: when config.g runs again (M502, M98 "
                             "P\"config.g\") it fails with 'variable already exists' and aborts the rest of config.g",
                             clip(pf.text(l.meta_name)), clip(pf.text(l.meta_name))));
    const bool opener = l.meta == MetaKind::If || l.meta == MetaKind::Elif || l.meta == MetaKind::While;
    const bool tests = (opener && pf.text(l.meta_arg).find("exists(global.") != std::string_view::npos) ||
                       ((l.meta == MetaKind::Elif || l.meta == MetaKind::Else) && chain_tests);
    open.push_back({l.indent, tests, l.meta == MetaKind::If || l.meta == MetaKind::Elif, enclosed || tests});
  }
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
  for (uint32_t u : boot_units) check_file(cx.machine.unit(u), out);
}

}  // namespace

extern const Rule global_without_guard{.meta = kMeta, .check_end = check};

}  // namespace rrflint
