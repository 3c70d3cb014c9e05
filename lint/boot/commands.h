// What RRF makes of a command, decided in one place: the machine model (lint/boot/model.cc) and every rule ask
// here, so that two readings of the same line can never disagree.
//
// - which form a G10 takes (tool offsets, a report, workplace origins, firmware retraction, a bad L);
// - whether an M563 defines a tool or only reports one, and its X/Y/Z axis maps;
// - the tool a G10 / M568 / M567 addresses (its P, or the current tool);
// - the role the firmware gives a file by its name (config.g, config-override.g, tpre<n>.g, homeall.g, …);
// - the pins a command takes for a device, and the device whose pins it gives back (lint/boot/pins.cc).
//
// The unknown-values rule holds throughout: where the answer depends on something the model does not know (an
// expression, the axes after an unreadable M584, a lone macro's unknown baseline), the answer is Unknown, and
// rules stay silent on it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lint/boot/model.h"

namespace rrflint {

/// The form RRF gives a G10 (docs/firmware-behaviour.md#g10-forms; GCodes2.cpp case 10).
enum class G10Form : uint8_t {
  Tool,        // tool offsets and/or temperatures: L1, or (no L) P, R, S, F on 3.3–3.4, or a visible axis letter
  Report,      // the tool form with nothing to set: only P and L1 (`G10 P0`), which reports the tool's settings
  Workplace,   // L2 / L20: workplace (coordinate system) origins
  Retraction,  // no L, none of the above: firmware retraction
  BadL,        // another L: `Bad or missing parameter`
  Unknown,     // L from an expression; or the form depends on the axes and they are not known
};

/// The G10's form. With `s`, the visible axes decide a G10 that has no L, P, R or S; without it (file rules,
/// look-ahead) such a G10 is Unknown. Axes that are not known (an unreadable M584, an axis created inside an
/// `if`, a lone macro's unknown baseline) make such a G10 Unknown as well.
G10Form g10_form(const ParsedFile& pf, const Command& c, const MachineState* s, Version fw);

/// Tool or Report: the G10 runs the tool-offset code (`SetOrReportOffsets`) and needs an existing tool.
inline bool is_tool_form(G10Form f) { return f == G10Form::Tool || f == G10Form::Report; }

/// Does this M563 define (create or re-create) a tool, rather than report one? Any of S D H X Y Z F R.
bool m563_defines(const ParsedFile& pf, const Command& c);

/// One M563 axis map (X, Y or Z) as RRF builds it (docs/firmware-behaviour.md#m563-tools): the given axis
/// indices ANDed with the visible axes, or the default (X→X, Y→Y, Z→Z) when the letter is absent. `known` is false
/// for an expression (then `bits` is 0).
struct M563Map {
  char letter = 'X';
  bool given = false;
  bool known = true;
  uint32_t bits = 0;
  std::vector<int64_t> indices;  // as written
  ParamRef param;
};
M563Map m563_map(const ParsedFile& pf, const Command& c, const MachineState& s, char letter);

/// Does M563 have a Z map on this firmware (3.5+)? Before that `Z` is ignored.
inline bool has_z_map(Version fw) { return fw >= kRrf3_5; }

/// The visible axes as a bit set of axis indices.
inline uint32_t visible_mask(const MachineState& s) {
  return s.visible_axes >= 32 ? 0xFFFFFFFFu : ((1u << s.visible_axes) - 1);
}

/// The tool a G10 / M568 / M567 addresses: its P, or the current tool.
struct ToolRef {
  int number = -1;          // -1: no tool (no P and no tool selected), when known
  bool known = false;       // false: a P from an expression, or the current tool is not known
  bool explicit_p = false;  // the command has a P
  bool none() const { return known && number < 0; }
};
ToolRef addressed_tool(const ParsedFile& pf, const Command& c, const MachineState& s);

/// The axis an M585 probes: the first visible axis it names (GCodes6.cpp `ProbeTool()`), as an axis index; -1 for
/// none (`No axis specified`).
int m585_axis(const ParsedFile& pf, const Command& c, const MachineState& s);

/// The kinematics type after this M669 K, M667 S (up to 3.4: S0 Cartesian, S1 CoreXY, S2 CoreXZ) or M665 L/D
/// (switches to linear delta, 3), as M669 K numbers it; nullopt when the command does not set it, -1 when the type
/// is unknown (an expression). RRF replaces the kinematics object only when the type changes (Move::SetKinematics).
std::optional<int> kinematics_set_by(const ParsedFile& pf, const Command& c, Version fw);

/// What an M671 does with the Z leadscrews (ZLeadscrewKinematics::Configure, the same from 2.05 to 3.5): X and Y
/// lists of equal length set them (Set; Unknown when a list is an expression); one list alone, or lists of
/// different lengths, are refused with "Specify 1, 2, 3 or 4 X and Y coordinates in M671" (Mismatch), a list of
/// more than 4 with "array too long, max length = 4" (TooLong); either way the leadscrews stay as they were. Without
/// X and Y it reports them or sets only S, P or F (Other).
enum class M671Form : uint8_t { Other, Set, Unknown, Mismatch, TooLong };
struct M671Read {
  M671Form form = M671Form::Other;
  std::vector<double> x, y;           // the lists (empty when absent or an expression)
  bool has_x = false, has_y = false;  // the parameter is there (known or not)
};
inline constexpr size_t kMaxLeadscrews = 4;
M671Read m671_read(const ParsedFile& pf, const Command& c);

/// Does the kinematics of this M669 K type read M671 (ZLeadscrewKinematics: Cartesian, CoreXY, CoreXYU, CoreXYUV,
/// SCARA, five-bar SCARA, Markforged)? CoreXZ refuses M671; deltas, polar and Hangprinter have no leadscrews.
bool has_leadscrews(int kinematics);

/// The one device letter of an M950 (Platform::ConfigurePort: "exactly one of FHJPSR must be given"): J, F, H, P, S,
/// and from the version that reads them R (spindles, 3.3), D (SD card: the 6HC's from 3.4, every board's from
/// 3.5.0-beta.4; an unknown board is taken to read it) and E (LED strip, 3.5.0-beta.4); 0 when it has none or
/// several. (The 6XD, which rrflint counts as a 6HC, had no D before 3.5.0-beta.4 either.)
char m950_device(const ParsedFile& pf, const Command& c, Version fw, Board board);

/// One pin as RRF looks it up (IoPort::RemoveBoardAddress, IoPort::Allocate, GCodeBuffer::GetReducedString): `key`
/// is "<board>.<name>", the name lowercased without '_' or '-' and without the '!', '^', '*' flags, the board 0 (the
/// main board) when the pin has no "<n>." prefix; `written` is the pin as the line has it.
struct PinName {
  std::string key, written;
};

/// Parses one pin ("!^io1.in", "121.temp0"); "nil" (no pin) gives an empty key.
PinName pin_name(std::string_view written);

/// What a command does to the pins of one device (IoPort::AssignPorts): first it gives back every pin the device
/// holds (a device re-created, deleted, or given new pins), then it takes `pins`, all or none: a pin held by another
/// device ("Pin 'x' is not free") makes RRF give back the ones it took and leaves the device without pins.
struct PinChange {
  PinDevice device;           // unknown (PinDevice::Kind::Unknown) when its number is an expression
  std::vector<PinName> pins;  // "nil" left out; empty: the device only gives its pins back
  ParamRef param;             // the parameter that names the pins (none for a change without pins)
  bool pins_known = true;     // false: the pins are an expression (the old ones are given back all the same)
};

/// The pin changes of an M950 (C), M308 (P), M558 (C), M574 (P), M591 (C) or M452 (C) on RRF 3; empty for other
/// commands, reports, and commands RRF rejects before it touches a pin. A device from an expression (`H{…}`) gives
/// one change with an unknown `device`: any device's pins may have changed.
std::vector<PinChange> pin_changes(const ParsedFile& pf, const Command& c, const MachineState& s);

/// The first pin of `ch` that RRF refuses: held by another device (`holder`), or named twice in `ch` (no holder).
/// nullopt when RRF gives the device all its pins.
struct PinClash {
  size_t index = 0;  // in ch.pins
  const PinOwner* holder = nullptr;
};
std::optional<PinClash> pin_clash(const MachineState& s, const PinChange& ch);

/// The model's side: applies a command's pin changes to `s.pins` (`maybe`: the command may not run).
void apply_pin_changes(MachineState& s, const std::vector<PinChange>& changes, NodeId id, bool maybe);

/// The role the firmware gives a file by its name (docs/firmware-behaviour.md#system-files).
enum class FileRole : uint8_t {
  Other,
  Config,             // sys/config.g (or config.g.bak, the fallback)
  ConfigOverride,     // sys/config-override.g, loaded by M501
  ToolFree,           // tfree<n>.g (n = -1: the generic tfree.g, 3.5+)
  ToolPre,            // tpre<n>.g
  ToolPost,           // tpost<n>.g
  Homing,             // homeall.g, homex.g … homez.g, home<axis>.g, homedelta.g
  Resurrect,          // resurrect.g, written by the firmware at a pause or power failure
  ResurrectPrologue,  // resurrect-prologue.g
  Daemon,             // daemon.g (3.1+), run again and again
  RunOnce,            // runonce.g, run once after config.g, then deleted
};

/// Does RRF drop the rest of this command's line? A command that runs a macro hands the line buffer to it, so the
/// commands after it on its line never run (docs: "Multiple commands on a single line"): M98; G28 (the homing
/// files); G32 (bed.g); G29 with no S (mesh.g; GCodes2.cpp case 29: S1, S2, S3 load, clear or save the height map
/// and run no macro). Not a T: its tool-change macros may or may not run, and RRF111 says so apart.
bool drops_rest_of_line(const ParsedFile& pf, const Command& c);

/// The role of the file at `sd_path` (any folder; the name is compared without case). For tool-change macros,
/// `*tool` is set to n, or -1 for the generic tfree.g / tpre.g / tpost.g.
FileRole file_role(std::string_view sd_path, int* tool = nullptr);

/// Is this a tool-change macro (tfree, tpre, tpost)?
inline bool is_tool_change_role(FileRole r) {
  return r == FileRole::ToolFree || r == FileRole::ToolPre || r == FileRole::ToolPost;
}

}  // namespace rrflint
