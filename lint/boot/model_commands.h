// The per-command part of the forward pass (lint/boot/model_commands.cc), called by ModelBuilder.
#pragma once

#include "lint/boot/model.h"

namespace rrflint {

/// Applies one command that changes the model (changes_state) to `s`; `maybe`: it may not run (an `if` branch).
void interpret_command(MachineState& s, const ParsedFile& pf, const Command& c, NodeId id, bool maybe);

/// One command being applied, for the handlers of the files below.
struct CommandCx {
  MachineState& s;
  const ParsedFile& pf;
  const Command& c;
  NodeId id;
  bool maybe;
};

/// lint/boot/model_devices.cc: heater monitor slots, M301, M570, fan thermostats, M950 ports and their users,
/// M581 triggers, M591 filament monitors, G31. Called before the main reading of the same command.
void interpret_device_command(CommandCx& x);

/// lint/boot/model_motion.cc: M92 / M350 steps and microstepping, M574 endstops, M671 leadscrews and the
/// kinematics parameters (M665/M667/M669). Called before the main reading of the same command (the kinematics
/// type it compares against is still the old one).
void interpret_motion_command(CommandCx& x);

/// Sets monitor slot 0 to a default monitor (Heater::SetAsToolHeater / SetAsBedOrChamberHeater) unless the user
/// set the monitors; RRF does this only when the heater has a sensor.
void install_default_monitor(Heater& h, double limit, NodeId id, bool maybe);

/// Reads a number parameter into a Fact (kept as it is when absent); false when absent.
bool read_fact(CommandCx& x, char letter, Fact& f);

}  // namespace rrflint
