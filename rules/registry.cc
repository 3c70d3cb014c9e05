#include "rules/registry.h"

#include "lint/engine/suppress.h"

namespace rrflint {

#define RULE(ident) extern const Rule ident;
#include "rules/rules.def"
#undef RULE

const RuleSet& builtin_rules() {
  static const RuleSet rules = [] {
    std::vector<const Rule*> v = {
#define RULE(ident) &ident,
#include "rules/rules.def"
#undef RULE
    };
    for (const Rule* r : engine_rules()) v.push_back(r);
    return RuleSet(std::move(v));
  }();
  return rules;
}

}  // namespace rrflint
