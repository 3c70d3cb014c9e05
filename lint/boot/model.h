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
#include <unordered_map>
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

/// Steps/mm and microstepping of one axis or extruder drive (M92, M350). Steps/mm: RRF's defaults 80 (axes),
/// Z 800 (3.5+; 4000 before), E 420; microstepping x16 with interpolation (Move.cpp).
struct DriveSettings {
  Fact steps{80};
  Fact microsteps{16};
  bool interpolation = true;
  bool interpolation_known = true;
  NodeId interpolation_set = kNoNode;
  NodeId steps_rescaled = kNoNode;  // the last M350 that rescaled `steps` (new/old microstepping)
};

struct Axis {
  char letter = 'X';  // 'X'…'D' or lowercase 'a'…'z'
  std::vector<DriverId> drivers;
  NodeId created = kNoNode;  // kNoNode for the default X, Y, Z
  NodeId drivers_set = kNoNode;
  bool maybe = false;  // created inside a conditional block
  bool rotational = false;
  DriveSettings drive;
  /// M574: endstop position (X1 low end, X2 high end, X0 none), type S (omitted: 1, a switch), pins P as written.
  struct Endstop {
    Fact position{0}, type{1};
    std::string pins;  // "" when none was given; "?" when it is an expression
    NodeId set = kNoNode;
    bool maybe = false;
  } endstop;
};

struct Sensor {
  NodeId created = kNoNode;
  std::string type;
  bool maybe = false;
};

/// One over-temperature monitor slot (M143 P0–P2) as Heater::ConfigureMonitor sets it: a slot nobody set is
/// disabled (condition -1, sensor -1). Omitted parameters: sensor = the heater's sensor, limit = the slot's old
/// limit, action 0 (fault), condition 0 (temperature exceeded).
struct MonitorSlot {
  Fact limit{0, false};  // a slot never set has no limit
  Fact action{0}, condition{-1}, sensor{-1};
  NodeId set = kNoNode;  // the M143 (or the M563/M140/M141 default) that set it
  bool maybe = false;    // set inside a conditional block
};

/// M570 heater fault detection: fault time P (s), excursion T (°C), bad readings R; S as written (3.5 reads no S).
struct FaultDetection {
  Fact time{5}, excursion{15}, bad_readings{3};
  Fact timeout{0, false};  // M570 S: not given
  NodeId set = kNoNode;
};

/// M301 PID values (P, I, D); unknown until an M301 sets them.
struct Pid {
  Fact p{0, false}, i{0, false}, d{0, false};
  NodeId set = kNoNode;
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
  /// Each monitor slot in full (M143 P0–P2), RRF's reading; `monitor_limits` above stays the rules' view.
  std::array<MonitorSlot, 3> monitors{};
  NodeId default_monitor = kNoNode;  // the M563/M140/M141 that installed the default monitor, if any
  bool slots_set_by_user = false;    // an M143 set a slot (any of T S A C): no default monitor from then on
  bool default_monitor_maybe = false;
  Pid pid;
  FaultDetection fault;
};

struct Fan {
  NodeId created = kNoNode;
  bool maybe = false;
  /// M106 H (RRF 3: sensor numbers) and T (threshold, or low:high): thermostatic when H names a sensor.
  std::vector<int64_t> sensors;
  std::vector<double> thresholds{45};  // DefaultHotEndFanTemperature
  bool thermostatic = false;
  bool thermostat_known = true;  // false after an M106 H/T from an expression or inside an `if`
  NodeId thermostat_set = kNoNode;
};

struct Probe {
  NodeId created = kNoNode;
  int type = -1;
  bool maybe = false;
  /// G31: trigger height Z and offsets X Y (ZProbe::SetDefaults: 0.7, 0, 0); M558 re-creation resets them.
  Fact trigger_height{0.7}, x_offset{0}, y_offset{0};
  NodeId g31 = kNoNode;
};

/// An M950 port that is not a heater or fan: GPIO in (J), GPIO out (P), servo (S), spindle (R, 3.3+).
enum class PortKind : uint8_t { GpioIn, GpioOut, Servo, Spindle };
struct Port {
  std::string pin;  // as written; "?" for an expression
  NodeId created = kNoNode;
  bool maybe = false;
};

/// A command that uses a port or pin: M42 P / M280 P (GPIO out, servo), M581 P (GPIO in), M453 (spindle).
struct PortUse {
  PortKind kind = PortKind::GpioOut;
  int port = -1;  // -1: unknown (an expression)
  NodeId at = kNoNode;
  bool maybe = false;
};

/// M581 T<n>: the GPIO-in ports (P, RRF 3) that run trigger n on a rising (S1, the default) or falling (S0) edge;
/// S-1 removes the ports, P-1 clears them all (TriggerItem::Configure). T0 is the emergency stop, T1 a pause, the
/// others run sys/trigger<n>.g.
struct Trigger {
  std::vector<int64_t> rising, falling;
  bool ports_known = true;
  Fact condition{0};  // R: 0 always, 1 only while printing, 2 only while not printing
  NodeId set = kNoNode;
  bool maybe = false;
};

/// M591 D<extruder>: a filament monitor of type P on pin C.
struct FilamentMonitor {
  Fact type{0};
  std::string pin;  // as written; "?" for an expression
  NodeId created = kNoNode;
  bool maybe = false;
};

/// M671 leadscrew positions (X, Y lists) and the kinematics change that dropped them (Move::SetKinematics).
struct Leadscrews {
  std::vector<double> x, y;
  bool known = true;
  NodeId set = kNoNode;      // kNoNode: never set
  NodeId dropped = kNoNode;  // a later M669/M667/M665 that changed (or may have changed) the kinematics type
  bool dropped_maybe = false;
};

/// One drive's use of a driver (the drivers table): axis index or extruder number.
struct DriverUse {
  DriverId driver;
  bool extruder = false;
  int index = 0;
  bool local() const { return driver.board == 0; }  // board 0: the main board; > 0: a CAN expansion board
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

/// A device that takes pins (lint/boot/pins.cc): its kind and number, compared as numbers on the forward pass and
/// named only for a message ("heater 1", "the X endstop").
struct PinDevice {
  enum class Kind : uint8_t {
    Unknown,  // from an expression: any device's pins may have changed
    SdCard,
    LedStrip,
    Spindle,
    GpioIn,
    Fan,
    Heater,
    GpioOut,
    Servo,
    Sensor,
    ZProbe,
    Endstop,  // `number` is the axis letter
    FilamentMonitor,
    Laser,
  };
  Kind kind = Kind::Unknown;
  int64_t number = 0;

  bool known() const { return kind != Kind::Unknown; }
  std::string name() const;  // "heater 1", "sensor 2", "Z probe 0", "the X endstop", "the laser"…
  friend bool operator==(const PinDevice&, const PinDevice&) = default;
};

struct PinDeviceHash {
  size_t operator()(const PinDevice& d) const noexcept {
    return std::hash<uint64_t>()(static_cast<uint64_t>(d.number) * 16 + static_cast<uint64_t>(d.kind));
  }
};

/// The device holding a pin (MachineState::pins, lint/boot/pins.cc).
struct PinOwner {
  PinDevice device;
  std::string written;  // the pin as that device's command wrote it
  NodeId at = kNoNode;  // the command that gave it the pin
  bool maybe = false;   // that command may not have run, or the pin may have been refused
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
  std::array<DriveSettings, kMaxAxisSlots> extruder_drive{};  // M92 / M350 E values, by extruder number

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
  /// Numeric parameters of the M669/M667/M665 that configured the current kinematics ("M665 R" → Fact); a type
  /// change starts a new kinematics object and drops them.
  std::map<std::string, Fact> kinematics_params;
  Leadscrews leadscrews;

  std::map<int, Port> ports[4];  // by PortKind
  bool ports_known = true;       // false after an M950 J/P/S/R with an unknown number
  std::vector<PortUse> port_uses;
  std::map<int, Trigger> triggers;
  std::unordered_map<std::string, PinOwner> pins;  // by PinName::key: the pins devices hold (RRF 3), in no order
  std::unordered_map<PinDevice, std::vector<std::string>, PinDeviceHash> pins_held;  // the same by device (may be [])
  bool pins_known = true;                            // false after a device from an expression took or gave back pins
  std::map<int, FilamentMonitor> filament_monitors;  // by extruder
  bool filament_monitors_known = true;
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
  /// Every driver the axes and extruders use, in axis then extruder order (empty for an unknown list).
  std::vector<DriverUse> driver_uses() const;
  /// Is this driver used by more than one axis or extruder?
  bool driver_shared(DriverId d) const;
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
namespace detail {
// The M codes the model reads (ModelBuilder::changes_state), a flag per number below 1000.
struct ModelMCodes {
  bool read[1000] = {};
  constexpr ModelMCodes() {
    for (int n : {42,  92,  98,  106, 140, 141, 143, 207, 280, 301, 307, 308, 350, 451, 452, 453,
                  558, 563, 567, 568, 570, 574, 581, 584, 585, 591, 665, 667, 669, 671, 950})
      read[n] = true;
  }
};
inline constexpr ModelMCodes kModelMCodes{};
}  // namespace detail

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
  /// and the forward pass need not call it. The M codes are the `case` labels of interpret_command() and the
  /// switches it calls (lint/boot/model_*.cc); tests/command_docs_test.cc checks that the two lists agree.
  static bool changes_state(const CommandTable::Code& c) {
    if (c.letter == 'M')
      return c.fraction < 0 && c.number >= 0 && c.number < 1000 && detail::kModelMCodes.read[c.number];
    return c.is('G', 10) || c.is('G', 31);
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
