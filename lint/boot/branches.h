// Branches known at boot: the top-level if/elif/else chains of a file, whose conditions the boot graph evaluates
// with the values known at boot (lint/boot/const_eval.h) when it reaches them. A branch known not to run is not
// run; the commands directly in a branch known to run run for certain (issue 15 §3, "values known at boot").
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "lint/syntax/parser.h"

namespace rrflint {

using CommandRange = std::pair<uint32_t, uint32_t>;  // [first, end) command indices

struct Branch {
  MetaKind kind = MetaKind::If;      // If, Elif or Else
  uint32_t line = 0;                 // the if/elif/else line (its condition: pf.lines[line].meta_arg)
  CommandRange commands;             // every command of the body, nested blocks included
  std::vector<CommandRange> direct;  // the body's commands outside its nested blocks
};

struct Chain {
  uint32_t first_command = 0;  // the first command at or after the `if` line: reaching it evaluates the chain
  std::vector<Branch> branches;
};

/// The file's if/elif/else chains at indent 0, outside any block, in order.
std::vector<Chain> top_level_chains(const ParsedFile& pf);

}  // namespace rrflint
