// RRF506 unreadable-macro: a macro that config.g runs exists but cannot be linted (binary, unreadable, not a file).
#include <fmt/format.h>

#include <algorithm>

#include "lint/engine/linter.h"
#include "rules/macro_common.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF506",
    .name = "unreadable-macro",
    .severity = Severity::Error,
    .summary = "A macro that M98 or M501 runs exists but cannot be read as G-code.",
    .docs = R"md(
## What it does
Reports an `M98 P"…"` (or the `M501` that loads `config-override.g`) whose file is on the card but cannot be
linted, at the call, and any other macro of the card that cannot be linted, at the file: a binary file (many NUL bytes or other control characters in its first 8 KiB), a file rrflint may not read,
a FIFO or device, or a symbolic link that leads nowhere. The reason is in the message.

## Why is this bad?
rrflint cannot check what it cannot read, so this finding stands in for every finding the file might hold. On the
printer a binary or corrupted macro runs as garbage: each line RRF cannot parse is an error, and whatever the macro
was meant to set up does not happen. A file saved in UTF-16 by a Windows editor is a common cause: to RRF it is
binary.

## Example
```gcode no-test
M98 P"tools.g"   ; sys/tools.g was saved as UTF-16
```

## Use instead
Save the macro as plain text (UTF-8 or ASCII) and make it readable.

## References
- rrflint: [M98 and macros](../firmware-behaviour.md#m98-and-macros)
- [M98: Call macro/subprogram](https://docs.duet3d.com/User_manual/Reference/Gcodes#m98-call-macrosubprogram)
)md",
};

void check(const EndContext& cx, Sink& out) {
  const auto& problems = cx.machine.problems();
  auto problem_of = [&](const std::string& sd) {
    return std::find_if(problems.begin(), problems.end(),
                        [&](const LoadProblem& lp) { return to_lower(lp.sd_path) == to_lower(sd); });
  };
  std::vector<bool> reported(problems.size(), false);
  for (const GraphEvent& e : cx.graph.events) {
    if (e.kind != GraphEvent::Kind::UnreadableFile) continue;
    auto p = problem_of(e.path);
    if (p != problems.end()) reported[static_cast<size_t>(p - problems.begin())] = true;
    out.report(kMeta, event_path_loc(cx, e),
               fmt::format("macro file '{}' cannot be linted: {}", e.path,
                           p == problems.end() ? std::string("unreadable") : p->message));
  }
  // The other files of the card that could not be linted (macros nothing runs at boot), at the file itself.
  // config.g is not one of them: a config.g that cannot be linted is an error of the whole run, not a finding.
  const std::string config = to_lower(cx.options.sys_dir + "/config.g");
  for (size_t i = 0; i < problems.size(); ++i) {
    const LoadProblem& p = problems[i];
    if (reported[i] || p.file == kNoFile || to_lower(p.sd_path) == config) continue;
    out.report(kMeta, Location{p.file, Span{0, 0}},
               fmt::format("file '{}' cannot be linted: {}", p.sd_path, p.message));
  }
}

}  // namespace

extern const Rule unreadable_macro{.meta = kMeta, .check_end = check};

}  // namespace rrflint
