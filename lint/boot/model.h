// The machine model: what the boot sequence builds, in one forward pass over the command graph.
//
// Every fact remembers the node (command) that created or last changed it. Facts set from expressions,
// param.*, or inside if/while blocks are *maybe*/unknown, and rules never fire on them.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lint/boot/firmware.h"
#include "lint/boot/graph.h"
#include "lint/syntax/values.h"

namespace rrflint {

inline constexpr int kMaxAxisSlots = 32;

/// A number that may be unknown, with the node that set it.
struct Fact {
  double value = 0;
  bool known = true;
  NodeId origin = kNoNode;  // kNoNode: the power-on default
};

struct Axis {
  char letter = 'X';  // 'X'…'D' or lowercase 'a'…'z'
  std::vector<DriverId> drivers;
  NodeId created = kNoNode;  // kNoNode for the default X, Y, Z
  NodeId drivers_set = kNoNode;
  bool maybe = false;  // created inside a conditional block
  bool rotational = false;
};

struct Sensor {
  NodeId created = kNoNode;
  std::string type;
  bool maybe = false;
};

struct Heater {
  NodeId created = kNoNode;
  int sensor = -1;
  bool maybe = false;
  bool monitor_installed = false;  // default monitor (tool/bed defaults) or a user M143
  double limit = 2000;             // highest over-temperature limit; 2000 with no monitor
                                   // (docs/firmware-behaviour.md#heaters-and-their-monitors)
  NodeId monitor_origin = kNoNode;
  bool user_monitor = false;
  bool model_set = false;  // M307 seen
  /// Over-temperature limit of each monitor (M143 P0–P2); -1 where that monitor is disabled or checks
  /// something else (C1, C-1). `limit` is the highest of these, or 2000 when there is none.
  std::array<double, 3> monitor_limits{-1, -1, -1};
};

struct Fan {
  NodeId created = kNoNode;
  bool maybe = false;
};

struct Probe {
  NodeId created = kNoNode;
  int type = -1;
  bool maybe = false;
};

/// A set of physical axis indices (bit i = axis index i) that may be unknown.
struct AxisMap {
  uint32_t bits = 0;
  bool known = true;
  NodeId origin = kNoNode;  // the M563 parameter that set it, or kNoNode for the default
};

struct Tool {
  int number = 0;
  std::string name;
  std::vector<int64_t> drives, heaters, fans;
  bool drives_known = true, heaters_known = true;
  bool has_d = false, has_h = false;
  bool spindle = false;  // M563 R
  AxisMap xmap, ymap, zmap;
  std::array<Fact, kMaxAxisSlots> offsets{};  // indexed by physical axis index
  std::array<bool, kMaxAxisSlots> probed{};   // offset loaded while running M501 (or M585)
  std::vector<double> active, standby;        // per heater; empty = off (ABS_ZERO)
  bool temps_known = true;
  NodeId created = kNoNode;
  NodeId last_configured = kNoNode;  // the last G10/M568/M207/M567 that set something on it
  bool maybe = false;                // created inside a conditional block (it may not exist)
};

enum class MachineMode : uint8_t { FFF, CNC, Laser };

struct Workplace {
  std::array<Fact, kMaxAxisSlots> origin{};
};

struct MachineState {
  Version firmware;
  Board board = Board::Unknown;
  bool unknown_baseline = false;  // linting a lone macro with no boot sequence: anything may already exist

  std::vector<Axis> axes;  // by creation index; X, Y, Z exist by default
  int visible_axes = 3;
  NodeId visible_set = kNoNode;
  bool axes_known = true;  // false after an M584 we could not read (expressions, conditionals)

  int extruders = 0;
  std::vector<DriverId> extruder_drivers;
  NodeId extruders_set = kNoNode;
  bool extruders_known = true;

  std::map<int, Sensor> sensors;
  std::map<int, Heater> heaters;
  std::map<int, Fan> fans;
  std::map<int, Probe> probes;
  bool sensors_known = true, heaters_known = true, fans_known = true, probes_known = true;
  int bed_heater = -1;

  std::map<int, Tool> tools;
  bool tools_known = true;  // false after an M563 with an unknown tool number: any tool may exist
  /// Tools whose last M563 failed after deleting them (`bad drive number`): the M563 node. Rules that
  /// would report "tool n does not exist" stay silent for these, so one mistake gives one finding.
  std::map<int, NodeId> failed_tools;
  /// Axis letters an M584 named but could not create (board limit): the M584 node.
  std::map<char, NodeId> failed_axes;

  int current_tool = kNoTool;
  bool current_tool_known = true;
  NodeId current_tool_set = kNoNode;

  std::array<Workplace, 10> workplaces{};  // 1…9 used (G54…G59.3)
  NodeId m501 = kNoNode;                   // the M501 that loaded config-override.g
  bool running_m501 = false;
  int kinematics = 0;  // M669 K value (0 Cartesian)
  NodeId kinematics_set = kNoNode;
  bool kinematics_known = true;  // false after an M669 K{…}, M667 S{…} or one inside a conditional block
  MachineMode mode = MachineMode::FFF;
  NodeId mode_set = kNoNode;

  // Lookups.
  int axis_index(char letter) const;  // -1 if absent
  bool axis_visible(int index) const { return index >= 0 && index < visible_axes; }
  const Tool* tool(int n) const {
    auto it = tools.find(n);
    return it == tools.end() ? nullptr : &it->second;
  }
  /// Is tool n known not to exist? (False when it may exist because of unknown facts.)
  bool tool_certainly_absent(int n) const { return tools_known && !unknown_baseline && !tools.count(n); }
  std::string axis_letters(uint32_t bits) const;  // "U", "X+U"
};

/// Letters of axes in RRF's creation order for one M584 (docs/firmware-behaviour.md#axes-and-m584).
std::string_view allowed_axis_letters();

/// Does a graph node run? Ordered: No < Maybe < Yes.
enum class Runs : uint8_t {
  No,     // never: a tool-change macro for a tool that certainly does not exist
  Maybe,  // perhaps: inside an if/while here or in a caller, or a tool macro for a tool that may not exist; the
          // node's effects are then unknown
  Yes,    // certainly
};

/// The forward pass. `step` applies one graph node to the state.
class ModelBuilder {
 public:
  ModelBuilder(const Machine& m, const Graph& g, Version fw, Board board);
  MachineState initial_state() const;
  void step(MachineState& s, NodeId id) const { step(s, id, g_.nodes[id]); }
  /// The same with the node already decoded (`n` is g_.nodes[id]).
  void step(MachineState& s, NodeId id, const Node& n) const;
  /// Does node `id` run? (Tool macros for a tool that does not exist do not run.)
  Runs runs(NodeId id) const { return exec_[id]; }
  /// Must be called for nodes in order, before step(): decides whether the node runs.
  void decide(const MachineState& s, NodeId id) { decide(s, id, g_.nodes[id]); }
  void decide(const MachineState& s, NodeId id, const Node& n);
  /// decide() for the command nodes [begin, end) of one run (NodeTable::Stretch; `n` is the first): they run alike.
  void decide_commands(const MachineState& s, NodeId begin, NodeId end, const Node& n);
  /// Can a command of this code change the state? Most cannot (moves, settings): step() does nothing for them,
  /// and the forward pass need not call it.
  static bool changes_state(const CommandTable::Code& c) {
    return (c.letter == 'M' && c.fraction < 0) || c.is('G', 10);
  }

 private:
  void apply_command(MachineState& s, NodeId id, const Node& n) const;
  void enter_tool_macro(MachineState& s, const Node& n, Runs e) const;
  const Machine& m_;
  const Graph& g_;
  Version fw_;
  Board board_;
  std::vector<Runs> exec_;
};

}  // namespace rrflint
