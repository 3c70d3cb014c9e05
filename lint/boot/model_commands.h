// The per-command part of the forward pass (lint/boot/model_commands.cc), called by ModelBuilder.
#pragma once

#include "lint/boot/model.h"

namespace rrflint {

/// Applies one command that changes the model (changes_state) to `s`; `maybe`: it may not run (an `if` branch).
void interpret_command(MachineState& s, const ParsedFile& pf, const Command& c, NodeId id, bool maybe);

}  // namespace rrflint
