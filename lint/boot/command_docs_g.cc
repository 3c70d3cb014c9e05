// The G codes of the command documentation table (command_docs_parts.h; sources and anchors: command_docs.cc).
#include "lint/boot/command_docs_parts.h"

namespace rrflint::docs {
namespace {

constexpr std::span<const ParamDoc> kNone;  // a command without parameters
constexpr ParamDoc kMove[] = {{'X', "X target"},
                              {'Y', "Y target"},
                              {'Z', "Z target"},
                              {'E', "extrusion amount, one per extruder of the tool"},
                              {'F', "feed rate (mm/min), kept for later moves"},
                              {'H', "H1/H2/H3: homing move (check endstops, ignore limits)"},
                              {'R', "R1: return towards the position saved at the last pause"},
                              {'S', "laser power or spindle speed of this move"}};
constexpr ParamDoc kArc[] = {{'X', "end X"},
                             {'Y', "end Y"},
                             {'Z', "end Z (helical arc)"},
                             {'I', "X offset of the centre from the start"},
                             {'J', "Y offset of the centre from the start"},
                             {'K', "Z offset of the centre (XZ/YZ planes, 3.3+)"},
                             {'R', "radius, instead of I/J"},
                             {'E', "extrusion amount"},
                             {'F', "feed rate (mm/min)"}};
constexpr ParamDoc kG4[] = {{'P', "time (milliseconds)"}, {'S', "time (seconds)"}};
constexpr ParamDoc kG10[] = {{'P', "tool number, or workplace 1-9 with L2/L20"},
                             {'L', "L1 tool offsets, L2 workplace origin, L20 origin from the current position"},
                             {'X', "X offset (mm)"},
                             {'Y', "Y offset (mm)"},
                             {'Z', "Z offset (mm)"},
                             {'R', "standby temperatures, one per heater"},
                             {'S', "active temperatures, one per heater"}};
constexpr ParamDoc kG11[] = {{'P', "tool number (default: the current tool)"}};
constexpr ParamDoc kG28[] = {
    {'X', "home X (no axis named: home all)"}, {'Y', "home Y"}, {'Z', "home Z"}, {'U', "home U"}, {'E', "ignored"}};
constexpr ParamDoc kG29[] = {{'S', "S0 probe and save, S1 load, S2 clear, S3 save, S4 probe points from a file"},
                             {'P', "height map or probe-point file name"},
                             {'K', "probe number (3.1+)"}};
constexpr ParamDoc kG30[] = {{'P', "probe point number, for bed.g"},
                             {'X', "X of the point"},
                             {'Y', "Y of the point"},
                             {'Z', "Z height at the point (-9999: probe it)"},
                             {'H', "height correction"},
                             {'S', "S-1 report, S-2 set tool Z offset, S-3 set trigger height, Sn>0 level n points"},
                             {'K', "probe number (3.1+)"}};
constexpr ParamDoc kG31[] = {{'K', "probe number (default 0)"},
                             {'P', "trigger threshold reading"},
                             {'X', "probe X offset from the nozzle"},
                             {'Y', "probe Y offset from the nozzle"},
                             {'Z', "trigger height (mm)"},
                             {'C', "temperature coefficient up to 3.2; from 3.3 an axis offset"},
                             {'S', "calibration temperature"},
                             {'T', "temperature coefficients (3.3+)"},
                             {'H', "sensor read for temperature compensation"}};
constexpr ParamDoc kG32[] = {{'S', "passed on to bed.g"}};
constexpr ParamDoc kG38[] = {
    {'X', "X target"}, {'Y', "Y target"}, {'Z', "Z target"}, {'U', "other axes too"}, {'P', "probe number (3.1+)"},
    {'F', "feed rate"}};
constexpr ParamDoc kG53[] = {{'X', "machine-coordinate X of the move on the same line"}};
constexpr ParamDoc kG60[] = {{'S', "restore point slot (default 0)"}};
constexpr ParamDoc kG92[] = {
    {'X', "new X position"}, {'Y', "new Y position"}, {'Z', "new Z position"}, {'E', "new extruder position"}};

constexpr CommandDoc kDocs[] = {
    {'G', 0, -1, "Rapid move",
     "Moves like G1 in FFF mode; in CNC and laser mode it ignores F and moves as fast as M203 allows, and the laser "
     "does not fire.",
     "g0-rapid-move", kMove},
    {'G', 1, -1, "Linear move",
     "Moves the axes in a straight line to the given position and extrudes E, at feed rate F; H1-H3 make it a homing "
     "move that stops at an endstop.",
     "g1-controlled-linear-move", kMove},
    {'G', 2, -1, "Clockwise arc",
     "Moves along a clockwise arc in the selected plane, with the centre given by I/J/K or the radius by R.",
     "g2-controlled-arc-move", kArc},
    {'G', 3, -1, "Counter-clockwise arc",
     "Moves along a counter-clockwise arc in the selected plane, with the centre given by I/J/K or the radius by R.",
     "g3-controlled-arc-move", kArc},
    {'G', 4, -1, "Dwell", "Waits for the moves in the queue to finish, then pauses for P milliseconds or S seconds.",
     "g4-dwell", kG4},
    {'G', 10, -1, "Tool offsets and temperatures, workplace origin, or retract",
     "With P, R, S or a visible axis letter: offsets and temperatures of an existing tool; with L2/L20: a workplace "
     "origin; with none of these: firmware retraction.",
     "g10-set-workplace-coordinate-offset-or-tool-offset", kG10},
    {'G', 11, -1, "Unretract", "Undoes the firmware retraction of the current tool, using its M207 settings.",
     "g11-unretract", kG11},
    {'G', 20, -1, "Inches", "Coordinates and feed rates given after it are in inches.", "g20-set-units-to-inches",
     kNone},
    {'G', 21, -1, "Millimetres", "Coordinates and feed rates given after it are in millimetres (the default).",
     "g21-set-units-to-millimeters", kNone},
    {'G', 28, -1, "Home axes",
     "Runs homeall.g, or home<axis>.g for each axis named; at boot no axis is homed until it runs.", "g28-home", kG28},
    {'G', 29, -1, "Mesh bed compensation",
     "Without S runs mesh.g (or probes the M557 grid); S0 probes, S1 loads a height map, S2 turns compensation off, S3 "
     "saves the map.",
     "g29-mesh-bed-probe", kG29},
    {'G', 30, -1, "Single probe",
     "Probes the bed once at the current or given XY; with P it records a point for bed levelling, and S sets what is "
     "done with the result.",
     "g30-single-z-probe", kG30},
    {'G', 31, -1, "Probe offsets and trigger height",
     "Sets the trigger height, X/Y offsets and threshold of probe K, which M558 must have created; a later M558 that "
     "re-creates the probe resets them.",
     "g31-set-or-report-current-probe-status", kG31},
    {'G', 32, -1, "Run bed.g",
     "Runs bed.g to level or calibrate the bed (deltas: auto-calibration from its G30 points).", "g32-run-bedg-macro",
     kG32},
    {'G', 38, 2, "Probe towards a target, error if none",
     "Moves towards the target until the probe triggers and stops there; reports an error when the target is reached "
     "without a trigger (3.0+).",
     "g382-straight-probe", kG38},
    {'G', 38, 3, "Probe towards a target",
     "Moves towards the target until the probe triggers; no error when it does not (3.0+).", "g383-straight-probe",
     kG38},
    {'G', 38, 4, "Probe away until release, error if none",
     "Moves towards the target until the probe stops triggering; an error when it never releases (3.0+).",
     "g384-straight-probe", kG38},
    {'G', 38, 5, "Probe away until release",
     "Moves towards the target until the probe stops triggering; no error when it does not (3.0+).",
     "g385-straight-probe", kG38},
    {'G', 53, -1, "Machine coordinates for one line",
     "The moves on the rest of this line use machine coordinates, without workplace offsets.",
     "g53-use-machine-coordinates", kG53},
    {'G', 54, -1, "Workplace 1", "Selects coordinate system 1 (the default), whose origin G10 L2 P1 sets.",
     "g54-select-coordinate-system", kNone},
    {'G', 55, -1, "Workplace 2", "Selects coordinate system 2 (G10 L2 P2 sets its origin).",
     "g55-select-coordinate-system", kNone},
    {'G', 56, -1, "Workplace 3", "Selects coordinate system 3 (G10 L2 P3 sets its origin).",
     "g56-select-coordinate-system", kNone},
    {'G', 57, -1, "Workplace 4", "Selects coordinate system 4 (G10 L2 P4 sets its origin).",
     "g57-select-coordinate-system", kNone},
    {'G', 58, -1, "Workplace 5", "Selects coordinate system 5 (G10 L2 P5 sets its origin).",
     "g58-select-coordinate-system", kNone},
    {'G', 59, -1, "Workplace 6", "Selects coordinate system 6 (G10 L2 P6 sets its origin).",
     "g59-select-coordinate-system", kNone},
    {'G', 59, 1, "Workplace 7", "Selects coordinate system 7 (G10 L2 P7 sets its origin).",
     "g591-select-coordinate-system", kNone},
    {'G', 59, 2, "Workplace 8", "Selects coordinate system 8 (G10 L2 P8 sets its origin).",
     "g592-select-coordinate-system", kNone},
    {'G', 59, 3, "Workplace 9", "Selects coordinate system 9 (G10 L2 P9 sets its origin).",
     "g593-select-coordinate-system", kNone},
    {'G', 60, -1, "Save position", "Saves the current position in restore point S, for a later G0/G1 R.",
     "g60-save-current-position-to-slot", kG60},
    {'G', 90, -1, "Absolute positioning",
     "Axis coordinates after it are absolute (and extruder ones too, unless M83 says otherwise).",
     "g90-set-to-absolute-positioning", kNone},
    {'G', 91, -1, "Relative positioning",
     "Axis and extruder coordinates after it are relative to the current position.", "g91-set-to-relative-positioning",
     kNone},
    {'G', 92, -1, "Set position",
     "Declares the current position to be the given coordinates without moving; an axis set this way counts as homed.",
     "g92-set-user-position", kG92},
};
static_assert(strictly_sorted(kDocs));

}  // namespace

std::span<const CommandDoc> g_codes() { return kDocs; }

}  // namespace rrflint::docs
