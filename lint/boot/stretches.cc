#include "lint/boot/stretches.h"

#include <algorithm>

namespace rrflint {

void Stretches::evaluate(const Chain& chain) {
  for (size_t i = 0; i < chain.branches.size(); ++i) {
    const Branch& b = chain.branches[i];
    const ConstValue v = b.kind == MetaKind::Else ? ConstValue::boolean(true) : cond_(b.line);
    if (v.kind != ConstValue::Kind::Bool) return;  // unknown: this branch and the next ones stay "maybe"
    if (!v.b) {
      overrides_.push_back({b.commands, false});
      continue;
    }
    for (const CommandRange& d : b.direct) overrides_.push_back({d, true});
    for (size_t j = i + 1; j < chain.branches.size(); ++j) overrides_.push_back({chain.branches[j].commands, false});
    return;
  }
}

void Stretches::reach(uint32_t ci) {
  while (chain_ < chains_.size() && chains_[chain_].first_command <= ci) evaluate(chains_[chain_++]);
}

Stretches::Stretch Stretches::next(uint32_t from, uint32_t end) {
  reach(from);
  if (chain_ < chains_.size()) end = std::min(end, std::max(from + 1, chains_[chain_].first_command));
  const auto& written = pf_.written_commands;
  while (written_ < written.size() && written[written_].second <= from) ++written_;
  if (written_ < written.size() && written[written_].first <= from)
    return {std::min(end, written[written_].second), false, false, false};
  if (written_ < written.size()) end = std::min(end, written[written_].first);
  while (over_ < overrides_.size() && overrides_[over_].range.second <= from) ++over_;
  bool certain = false;
  if (over_ < overrides_.size()) {
    const Override& o = overrides_[over_];
    if (o.range.first <= from) {
      if (!o.runs) return {std::min(end, o.range.second), false, false, false};
      certain = true;
      end = std::min(end, o.range.second);
    } else {
      end = std::min(end, o.range.first);
    }
  }
  const auto& blocks = pf_.block_commands;
  while (block_ < blocks.size() && blocks[block_].second <= from) ++block_;
  const bool in = block_ < blocks.size() && blocks[block_].first <= from;
  if (block_ < blocks.size()) end = std::min(end, in ? blocks[block_].second : blocks[block_].first);
  return {end, true, certain, in};
}

}  // namespace rrflint
