// RRF901 unknown-rule-in-suppression: a suppression comment names a rule that does not exist, or is not a
// suppression directive rrflint understands. Produced by the suppression pass (lint/engine/suppress.cc).
#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF901",
    .name = "unknown-rule-in-suppression",
    .severity = Severity::Warning,
    .summary = "A suppression comment names a rule that does not exist.",
    .docs = R"md(
## What it does
Checks every `; rrflint:` comment. It reports a rule name or code that no rule has (with the closest name when
there is one: "did you mean 'unknown-command' (RRF101)?"), a directive keyword that is not `disable`,
`disable-next-line`, `disable-file` or `enable`, a directive without `=` and a list, and an empty list.

## Why is this bad?
A misspelt suppression silently suppresses nothing, so the finding it was meant to hide is still reported, or,
worse, the author believes a range is disabled when it is not. hadolint users lost time to exactly this
(a pragma that silently stopped working).

## Example
```gcode
M9999 ; rrflint: disable=unknown-comand
```

## Use instead
```gcode
M9999 ; rrflint: disable=unknown-command
```

## References
- rrflint README, "Suppressing findings" (the comment syntax)
- `lint/engine/suppress.cc`
)md",
};

}  // namespace

extern const Rule unknown_rule_in_suppression{.meta = kMeta};

}  // namespace rrflint
