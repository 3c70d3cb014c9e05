// RRF900 unused-suppression: a suppression comment that suppresses nothing. Produced by the suppression pass
// (lint/engine/suppress.cc) at the end of every run; this file holds its metadata and docs.
#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF900",
    .name = "unused-suppression",
    .severity = Severity::Info,
    .fix = FixAvailability::Sometimes,
    .tag = RuleTag::Unnecessary,
    .summary = "A suppression comment that suppresses nothing.",
    .docs = R"md(
## What it does
Reports a `; rrflint: disable…` comment, or one rule named in it, that did not suppress any finding in this run:
a same-line `disable=` on a line without that finding, a `disable-next-line=` whose next code line is clean, a
`disable=` … `enable=` range or a `disable-file=` with no such finding inside, and an `enable=` that closes no
range. Only rules that are enabled in this run count: a suppression for a rule switched off by `--select`,
`--ignore`, the config file or its `per-file-ignores` is never reported.

## Why is this bad?
A suppression outlives the problem it was written for. Once the line is fixed, the comment only hides the
next, different mistake of the same kind on that line, and tells readers that something is wrong where nothing
is.

## Example
```gcode
; rrflint-options: --extend-select unknown-command
M584 X0 Y1 Z2 ; rrflint: disable=unknown-command
```

## Use instead
```gcode
M584 X0 Y1 Z2
```

## Fix safety
Safe. The fix removes the comment: the whole line when the comment is alone on its line, otherwise the comment
and the blanks before it. When only some of the named rules are unused, it removes just those names from the
list. A suppression of `unused-suppression` itself is judged last, after it had the chance to silence the
other findings of this rule. There is no fix when the comment's `;` also cut an expression short
(`semicolon-in-expression`, RRF113): the comment then holds the rest of the expression, which was meant as code.

## References
- rrflint README, "Suppressing findings" (the comment syntax)
- ruff's [`RUF100`](https://docs.astral.sh/ruff/rules/unused-noqa/) (unused-noqa)
- `lint/engine/suppress.cc`
)md",
};

}  // namespace

extern const Rule unused_suppression{.meta = kMeta};

}  // namespace rrflint
