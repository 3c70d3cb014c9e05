// The rule registry: every rule rrflint ships (rules/rules.def) plus the suppression pass's own two
// (lint/engine/suppress.h). Front ends hand this set to the engine (lint_machine, enabled_rules, renderers);
// the engine never looks rules up on its own.
#pragma once

#include "lint/engine/rule.h"

namespace rrflint {

/// Every built-in rule, sorted by code.
const RuleSet& builtin_rules();

}  // namespace rrflint
