// The boot graph pushes a file run's commands a stretch at a time: a stretch ends where a block begins or ends,
// where lines written into a file begin or end (they do not run: ParsedFile::written_commands), and where a branch
// known at boot begins or ends (lint/boot/branches.h: a branch known not to run does not run; the commands directly
// in a branch known to run run for certain). Conditions are evaluated when the walk reaches their chain.
#pragma once

#include <functional>
#include <vector>

#include "lint/boot/branches.h"
#include "lint/boot/const_eval.h"

namespace rrflint {

class Stretches {
 public:
  /// Evaluates the condition of the if/elif on line `line` with the values known when the walk reaches it.
  using Condition = std::function<ConstValue(uint32_t line)>;
  Stretches(const ParsedFile& pf, const std::vector<Chain>& chains, Condition cond)
      : pf_(pf), chains_(chains), cond_(std::move(cond)) {}

  struct Stretch {
    uint32_t end;   // the stretch is [from, end)
    bool runs;      // false: written into a file, or in a branch known not to run
    bool certain;   // directly in a branch known to run
    bool in_block;  // inside an if/else/while block (unless certain: maybe)
  };
  /// The stretch that starts at command `from` (walked in increasing order), at most up to `end`.
  Stretch next(uint32_t from, uint32_t end);

 private:
  struct Override {
    CommandRange range;
    bool runs;
  };
  void reach(uint32_t ci);  // evaluates the chains whose first command is at or before ci
  void evaluate(const Chain& chain);

  const ParsedFile& pf_;
  const std::vector<Chain>& chains_;
  Condition cond_;
  size_t chain_ = 0, block_ = 0, written_ = 0, over_ = 0;
  std::vector<Override> overrides_;  // in order, from the chains evaluated so far
};

}  // namespace rrflint
