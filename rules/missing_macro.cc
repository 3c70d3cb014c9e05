// RRF501 missing-macro: M98 names a file that is not on the SD card.
#include <fmt/format.h>

#include <map>

#include "lint/card/card.h"
#include "lint/engine/linter.h"
#include "rules/macro_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF501",
    .name = "missing-macro",
    .severity = Severity::Warning,
    .summary = "M98 names a macro file that does not exist on the SD card.",
    .docs = R"md(
## What it does
Resolves every `M98 P"…"` the way RRF does (relative paths under `/sys` or the `M505` folder, `0:/…` and `/…`
absolute, case-insensitive like the SD card) and reports a file that is not there.

## Why is this bad?
RRF prints the warning `Macro file x.g not found` and carries on: whatever the macro was meant to set up (tools,
offsets, fans) silently does not happen. A common cause is a macro under `/macros` called with a relative path,
which RRF looks for under `/sys`.

An `M98` inside a branch that runs only when its file exists is not judged: `if fileexists("x.g")` (RRF 3.5's
`fileexists()`, which resolves its path against the system folder as M98 does, so `"0:/sys/x.g"` is the same
file), or an `elif`/`else` after a branch of the same chain that tests `!fileexists("x.g")`. Only a string
literal is read there; the paths are compared after resolving both.

A top-level folder (such as `/macros`) of which the linted copy holds no file at all (printer-config repositories often keep only `sys/`) is not
judged: the file may well be on the card.

## Example
```gcode
M98 P"macros/levels.g"   ; looks for /sys/macros/levels.g
```

## Use instead
```gcode
M98 P"0:/macros/levels.g"
if fileexists("0:/sys/levels.g")   ; an optional file
  M98 P"levels.g"
```

## References
- rrflint: [M98 and macros](../firmware-behaviour.md#m98-and-macros)
- Duet3D G-code dictionary: [M98: call macro/subprogram](https://docs.duet3d.com/User_manual/Reference/Gcodes#m98-call-macrosubprogram), [Filenames and Paths](https://docs.duet3d.com/User_manual/Reference/Gcodes#filenames-and-paths)
- RepRapFirmware 3.5.3: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (case 98), [MassStorage.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/Storage/MassStorage.cpp) (`CombineName()`)
)md",
};

/// The SD paths that `fileexists("…")` tests in a condition, resolved against the system folder the way
/// SysFileExists does, each with whether it is negated (`!fileexists(…)`). Only string literals are read.
std::vector<std::pair<std::string, bool>> fileexists_tests(std::string_view cond, std::string_view sys_dir) {
  std::vector<std::pair<std::string, bool>> out;
  const std::string lower = to_lower(cond);
  for (size_t at = lower.find("fileexists"); at != std::string::npos; at = lower.find("fileexists", at + 1)) {
    size_t i = at + 10;
    while (i < cond.size() && (cond[i] == ' ' || cond[i] == '\t')) ++i;
    if (i >= cond.size() || cond[i] != '(') continue;
    do ++i;
    while (i < cond.size() && (cond[i] == ' ' || cond[i] == '\t'));
    if (i >= cond.size() || cond[i] != '"') continue;
    const size_t close = cond.find('"', i + 1);
    if (close == std::string_view::npos) continue;
    size_t b = at;
    while (b > 0 && (cond[b - 1] == ' ' || cond[b - 1] == '\t')) --b;
    const bool negated = b > 0 && cond[b - 1] == '!';
    if (auto p = resolve_sd_path(sys_dir, cond.substr(i + 1, close - i - 1))) out.emplace_back(to_lower(*p), negated);
  }
  return out;
}

bool tests(const ParsedFile& pf, const Line& h, std::string_view sys_dir, const std::string& path, bool negated) {
  for (const auto& [p, neg] : fileexists_tests(pf.text(h.meta_arg), sys_dir))
    if (p == path && neg == negated) return true;
  return false;
}

/// Is line `li` inside a branch that runs only when the file at `path` exists: an if/elif testing
/// `fileexists(path)`, or an elif/else after a branch of its chain testing `!fileexists(path)`?
bool guarded_by_fileexists(const ParsedFile& pf, size_t li, std::string_view sys_dir, const std::string& path) {
  uint32_t threshold = pf.lines[li].indent;
  for (size_t k = li; k-- > 0 && threshold > 0;) {
    const Line& h = pf.lines[k];
    if (h.kind == LineKind::Blank || h.kind == LineKind::Comment || h.indent >= threshold) continue;
    threshold = h.indent;
    if (h.kind != LineKind::Meta) continue;
    if ((h.meta == MetaKind::If || h.meta == MetaKind::Elif) && tests(pf, h, sys_dir, path, false)) return true;
    if (h.meta != MetaKind::Elif && h.meta != MetaKind::Else) continue;
    for (size_t j = k; j-- > 0;) {  // the earlier branches of the same chain
      const Line& b = pf.lines[j];
      if (b.kind == LineKind::Blank || b.kind == LineKind::Comment || b.indent > h.indent) continue;
      if (b.indent < h.indent || b.kind != LineKind::Meta) break;
      if ((b.meta == MetaKind::If || b.meta == MetaKind::Elif) && tests(pf, b, sys_dir, path, true)) return true;
      if (b.meta == MetaKind::If) break;
    }
  }
  return false;
}

void check(const EndContext& cx, Sink& out) {
  std::map<std::string, bool> dirs;  // top folder -> has a file on the card (asked once per folder, not per call)
  for (const GraphEvent& e : cx.graph.events) {
    if (e.kind != GraphEvent::Kind::MissingFile || !event_is_m98(cx, e)) continue;
    // A folder with no file at all on the card (a repository that keeps only sys/) says nothing about the SD card.
    const size_t second = e.path.find('/', 1);
    const std::string top = second == std::string::npos ? std::string() : e.path.substr(0, second);
    if (!top.empty()) {
      auto [d, fresh] = dirs.try_emplace(top, false);
      if (fresh) d->second = cx.machine.has_dir(top);
      if (!d->second) continue;
    }
    // `if fileexists("x.g")` around `M98 P"x.g"`: the call runs only when the file is there.
    const ParsedFile& pf = cx.machine.unit(cx.graph.nodes[e.node].unit).parsed;
    if (guarded_by_fileexists(pf, event_command(cx, e).line, cx.options.sys_dir, to_lower(e.path))) continue;
    std::string hint;
    const std::string lower = to_lower(e.path);
    // A path is quoted whole up to 120 bytes (a long path is still one name), cut beyond.
    if (lower.starts_with("/sys/macros/"))
      hint = fmt::format(": did you mean '0:/macros/{}'?", clip(e.path.substr(12), 120));
    out.report(kMeta, event_path_loc(cx, e),
               fmt::format("macro file '{}' does not exist: RRF warns 'Macro file not found' and carries on{}",
                           clip(e.path, 120), hint));
  }
}

}  // namespace

extern const Rule missing_macro{.meta = kMeta, .check_end = check};

}  // namespace rrflint
