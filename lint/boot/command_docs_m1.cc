// M0 to M299 of the command documentation table (command_docs_parts.h; sources and anchors: command_docs.cc).
#include "lint/boot/command_docs_parts.h"

namespace rrflint::docs {
namespace {

constexpr std::span<const ParamDoc> kNone;  // a command without parameters
constexpr ParamDoc kStop[] = {{'H', "H1: leave the heaters on (before 3.4)"}};
constexpr ParamDoc kSpindle[] = {{'S', "spindle speed (RPM), or laser power in laser mode (M3)"},
                                 {'P', "spindle number (default: the current tool's)"}};
constexpr ParamDoc kM5[] = {{'P', "spindle number"}};
constexpr ParamDoc kMotors[] = {{'X', "X motor"},
                                {'Y', "Y motor"},
                                {'Z', "Z motor"},
                                {'E', "extruder motors"},
                                {'S', "M84 S: idle timeout (seconds)"}};
constexpr ParamDoc kM28[] = {{'P', "file name (also as the rest of the line)"}};
constexpr ParamDoc kM42[] = {{'P', "GPIO output port number (M950 P)"}, {'S', "value: 0-1 or 0-255"}};
constexpr ParamDoc kM80[] = {{'C', "pin that switches the supply (3.0+)"}};
constexpr ParamDoc kM81[] = {{'S', "S1: wait until the thermostatic fans have stopped"}};
constexpr ParamDoc kM92[] = {{'X', "X steps per mm"},
                             {'Y', "Y steps per mm"},
                             {'Z', "Z steps per mm"},
                             {'E', "extruder steps per mm, one per extruder"},
                             {'S', "microstepping the values are given for (converted to the current one)"}};
constexpr ParamDoc kM98[] = {{'P', "macro file name, relative to the system folder (quoted from 3.5)"},
                             {'R', "R1: the macro may be restarted after a power failure (3.4+)"}};
constexpr ParamDoc kHeatTool[] = {{'S', "active temperature"}, {'R', "standby temperature"}, {'T', "tool number"}};
constexpr ParamDoc kM106[] = {{'P', "fan number (M950 F); without it the print fan of the current tool"},
                              {'S', "speed, 0-1 or 0-255"},
                              {'H', "sensors that switch it on (thermostatic), -1 for none"},
                              {'T', "thermostatic threshold, or low:high range (degrees C)"},
                              {'C', "fan name"},
                              {'B', "blip time at start-up (seconds)"},
                              {'L', "lowest speed"},
                              {'X', "highest speed"},
                              {'R', "restore the speed saved at a pause"}};
constexpr ParamDoc kM107[] = {{'P', "fan number"}};
constexpr ParamDoc kM116[] = {{'P', "tool to wait for"},
                              {'H', "heaters to wait for"},
                              {'C', "chamber heater to wait for"},
                              {'S', "tolerance (degrees C)"}};
constexpr ParamDoc kM118[] = {{'P', "destination: 0 all, 1 USB, 2 PanelDue port, 3 HTTP, 4 Telnet, 6 MQTT"},
                              {'S', "the message"},
                              {'L', "log level"}};
constexpr ParamDoc kBed[] = {{'P', "bed heater index (M140) or chamber index (M141)"},
                             {'H', "heater number; H-1 removes it"},
                             {'S', "active temperature"},
                             {'R', "standby temperature"}};
constexpr ParamDoc kM143[] = {{'H', "heater number (default 1)"},
                              {'P', "monitor slot 0-2 (3.1+)"},
                              {'S', "temperature limit"},
                              {'A', "action: 0 fault, 1 switch off, 2 off until back in range, 3 shut down"},
                              {'C', "condition: 0 too high, 1 too low, -1 disabled"},
                              {'T', "sensor the monitor reads"}};
constexpr ParamDoc kWaitBed[] = {
    {'P', "bed or chamber index"}, {'S', "target (heating only)"}, {'R', "target (heating or cooling)"}};
constexpr ParamDoc kM200[] = {{'D', "filament diameters, 0 to turn volumetric extrusion off"}};
constexpr ParamDoc kPerAxis[] = {{'X', "X value"}, {'Y', "Y value"}, {'Z', "Z value"}, {'E', "extruder values"}};
constexpr ParamDoc kM203[] = {{'X', "X maximum (mm/min)"},
                              {'Y', "Y maximum"},
                              {'Z', "Z maximum"},
                              {'E', "extruder maximums"},
                              {'I', "lowest speed of any move"}};
constexpr ParamDoc kM204[] = {{'P', "acceleration of printing moves"}, {'T', "acceleration of travel moves"}};
constexpr ParamDoc kM205[] = {
    {'X', "X jerk (mm/s)"}, {'Y', "Y jerk (mm/s)"}, {'Z', "Z jerk (mm/s)"}, {'E', "extruder jerks (mm/s)"}};
constexpr ParamDoc kM207[] = {{'P', "tool number (default: every tool that exists)"},
                              {'S', "retraction length (mm)"},
                              {'R', "extra length on unretract (mm)"},
                              {'F', "retraction speed (mm/min)"},
                              {'T', "unretract speed (mm/min)"},
                              {'Z', "Z hop (mm)"}};
constexpr ParamDoc kM208[] = {{'S', "S0 (default) sets the maximums, S1 the minimums"},
                              {'X', "X limit, or min:max"},
                              {'Y', "Y limit, or min:max"},
                              {'Z', "Z limit, or min:max"}};
constexpr ParamDoc kM220[] = {{'S', "speed factor (percent)"}};
constexpr ParamDoc kM221[] = {{'D', "extruder number"}, {'S', "extrusion factor (percent)"}};
constexpr ParamDoc kM260[] = {{'A', "I2C address"}, {'B', "bytes to send"}, {'R', "number of bytes to read back"}};
constexpr ParamDoc kM261[] = {{'A', "I2C address"}, {'B', "number of bytes to read"}};
constexpr ParamDoc kM280[] = {{'P', "servo port number (M950 S)"},
                              {'S', "angle (degrees) or pulse width (microseconds)"}};
constexpr ParamDoc kM290[] = {{'Z', "Z babystep (mm); other axis letters too"},
                              {'R', "R1: relative (default), R0 absolute"},
                              {'S', "same as Z (older form)"}};
constexpr ParamDoc kM291[] = {{'P', "message"},
                              {'R', "title"},
                              {'S', "mode: 0-3 buttons, 4-7 choices and input (3.5+)"},
                              {'T', "timeout (seconds)"},
                              {'X', "allow jogging X"},
                              {'Y', "allow jogging Y"},
                              {'Z', "allow jogging Z"},
                              {'K', "choices (S4, 3.5+)"},
                              {'F', "default value (3.5+)"},
                              {'J', "J1: show a cancel button (3.5+)"}};
constexpr ParamDoc kM292[] = {
    {'P', "P1: cancel the operation"}, {'S', "reply value (3.5+)"}, {'Q', "sequence number of the message (3.5+)"}};

constexpr CommandDoc kDocs[] = {
    {'M', 0, -1, "Stop",
     "Ends a print when a print file runs it; sent while paused, cancels the print (cancel.g, else stop.g, else all "
     "heaters off); an error otherwise.",
     "m0-stop-or-unconditional-stop", kStop},
    {'M', 1, -1, "Sleep", "In RRF 3.5 the same as M0 (older versions ran sleep.g and turned the motors off too).",
     "m1-sleep-or-conditional-stop", kStop},
    {'M', 3, -1, "Spindle on, clockwise",
     "Starts the spindle of the current tool (or P) clockwise at S RPM; in laser mode sets the laser power of the "
     "moves that follow.",
     "m3-spindle-on-clockwise", kSpindle},
    {'M', 4, -1, "Spindle on, counter-clockwise",
     "Starts the spindle of the current tool (or P) counter-clockwise at S RPM.", "m4-spindle-on-counterclockwise",
     kSpindle},
    {'M', 5, -1, "Spindle off", "Stops the spindle (or, in laser mode, the laser).", "m5-spindle-off", kM5},
    {'M', 17, -1, "Enable motors", "Energises the motors named, or all of them (3.3+).", "m17-enable-motors", kMotors},
    {'M', 18, -1, "Disable motors",
     "Turns off the motors named, or all of them; axes whose motors go off are no longer homed.", "m18-disable-motors",
     kMotors},
    {'M', 28, -1, "Write a file",
     "Every line after it, up to M29, is written into the named file instead of being run.",
     "m28-begin-write-to-sd-card", kM28},
    {'M', 29, -1, "End of file writing", "Closes the file M28 opened; the lines between them did not run.",
     "m29-stop-writing-to-sd-card", kNone},
    {'M', 42, -1, "Set an output port", "Sets GPIO output port P, which M950 P must have created, to S.",
     "m42-switch-io-pin", kM42},
    {'M', 80, -1, "Power supply on", "Switches the ATX supply on through its PS_ON pin, which C names in RRF 3.",
     "m80-atx-power-on", kM80},
    {'M', 81, -1, "Power supply off",
     "Switches the ATX supply off, at once or (S1) once the thermostatic fans have stopped.", "m81-atx-power-off",
     kM81},
    {'M', 82, -1, "Absolute extrusion", "E values after it are absolute positions.",
     "m82-set-extruder-to-absolute-mode", kNone},
    {'M', 83, -1, "Relative extrusion", "E values after it are relative amounts (what most slicers for RRF use).",
     "m83-set-extruder-to-relative-mode", kNone},
    {'M', 84, -1, "Motors off / idle timeout",
     "Without S turns motors off like M18; with S sets the time after which idle motors drop to their idle current.",
     "m84-stop-idle-hold", kMotors},
    {'M', 92, -1, "Steps per mm",
     "Sets steps per mm of existing axes and extruders (a letter M584 creates later is lost); M350 afterwards rescales "
     "them.",
     "m92-set-axis-steps-per-unit", kM92},
    {'M', 98, -1, "Run a macro",
     "Runs the file P (relative to /sys or the M505 folder) at this point; a missing file is only a warning. Other "
     "parameters become param.X (3.3+).",
     "m98-call-macrosubprogram", kM98},
    {'M', 99, -1, "Return from a macro", "Ends the macro that runs it, back to its caller.",
     "m99-return-from-macrosubprogram", kNone},
    {'M', 104, -1, "Set hot end temperature",
     "Sets the active temperature of the tool's heaters (tool T or the current one) without waiting.",
     "m104-set-extruder-temperature", kHeatTool},
    {'M', 106, -1, "Fan settings",
     "Sets speed, name and thermostatic control of fan P, which M950 F must have created (else nothing on the line is "
     "set); without P the print fan.",
     "m106-fan-on", kM106},
    {'M', 107, -1, "Fan off", "Turns the print cooling fan off (same as M106 S0).", "m107-fan-off", kM107},
    {'M', 109, -1, "Set hot end temperature and wait",
     "Selects the tool when needed, sets its temperature and waits until it is reached.",
     "m109-set-extruder-temperature-and-wait", kHeatTool},
    {'M', 112, -1, "Emergency stop",
     "Stops everything at once and turns the heaters and motors off; the board needs a reset (M999) to go on.",
     "m112-emergency-stop", kNone},
    {'M', 116, -1, "Wait for temperatures",
     "Waits until the heaters of the tool, the named heaters, or all active ones are at their targets.",
     "m116-wait-for-temperature-to-be-reached", kM116},
    {'M', 117, -1, "Show a message", "Shows the rest of the line, quoted or not, on the display and web interface.",
     "m117-display-message", kNone},
    {'M', 118, -1, "Send a message", "Sends the text to the chosen channel (USB, PanelDue, web, log).",
     "m118-send-message-to-specific-target", kM118},
    {'M', 120, -1, "Push state", "Saves feed rate, positioning modes and similar state, for M121 to restore.",
     "m120-push", kNone},
    {'M', 121, -1, "Pop state", "Restores the state the last M120 saved.", "m121-pop", kNone},
    {'M', 140, -1, "Bed heater",
     "H names bed heater P and installs its default 125 C monitor if the heater exists and has none set by M143; S/R "
     "set its temperatures.",
     "m140-set-bed-temperature-fast-or-configure-bed-heater", kBed},
    {'M', 141, -1, "Chamber heater",
     "H names chamber heater P and installs its default monitor if the heater exists; S/R set its temperatures.",
     "m141-set-chamber-temperature-fast-or-configure-chamber-heater", kBed},
    {'M', 143, -1, "Heater monitor",
     "Writes monitor slot P of an existing heater: limit S, action A, condition C; the highest limit is what G10/M568 "
     "temperatures must stay under.",
     "m143-maximum-heater-temperature", kM143},
    {'M', 190, -1, "Wait for the bed", "Sets the bed temperature and waits for it.",
     "m190-wait-for-bed-temperature-to-reach-target-temp", kWaitBed},
    {'M', 191, -1, "Wait for the chamber", "Sets the chamber temperature and waits for it.",
     "m191-wait-for-chamber-temperature-to-reach-target-temp", kWaitBed},
    {'M', 200, -1, "Volumetric extrusion", "Sets filament diameters so that E values are volumes; D0 turns it off.",
     "m200-volumetric-extrusion", kM200},
    {'M', 201, -1, "Maximum accelerations", "Sets the acceleration limits (mm/s^2) of existing axes and extruders.",
     "m201-set-max-acceleration", kPerAxis},
    {'M', 201, 1, "Reduced accelerations",
     "Sets the accelerations used for probing, stall homing and similar special moves (3.4+).",
     "m2011-set-reduced-acceleration-for-special-move-types", kPerAxis},
    {'M', 203, -1, "Maximum speeds", "Sets the top speeds (mm/min) of existing axes and extruders.",
     "m203-set-maximum-feedrate", kM203},
    {'M', 204, -1, "Print and travel acceleration",
     "Sets the accelerations of extruding and non-extruding moves, within the M201 limits.",
     "m204-set-printing-and-travel-accelerations", kM204},
    {'M', 205, -1, "Jerk (mm/s)", "The same as M566 but in mm/s.", "m205-set-max-instantaneous-speed-change-in-mmsec",
     kM205},
    {'M', 206, -1, "Offset axes", "Shifts the axes by the given amounts (the older form of workplace offsets).",
     "m206-offset-axes", kPerAxis},
    {'M', 207, -1, "Firmware retraction settings",
     "Sets the G10/G11 retraction of tool P (which must exist), or of every tool that exists now when P is absent.",
     "m207-set-retract-length", kM207},
    {'M', 208, -1, "Axis limits", "Sets the minimum (S1) or maximum (S0) of existing axes, or both with min:max.",
     "m208-set-axis-max-travel", kM208},
    {'M', 220, -1, "Speed factor", "Scales the speed of the moves that follow, in percent.",
     "m220-set-speed-factor-override-percentage", kM220},
    {'M', 221, -1, "Extrusion factor", "Scales the extrusion of extruder D, in percent; the extruder must exist.",
     "m221-set-extrude-factor-override-percentage", kM221},
    {'M', 260, -1, "I2C send", "Sends bytes B to the I2C device at address A, reading R bytes back.",
     "m260-i2c-send-andor-request-data", kM260},
    {'M', 261, -1, "I2C read", "Reads B bytes from the I2C device at address A.", "m261-i2c-request-data", kM261},
    {'M', 280, -1, "Servo position", "Drives servo port P, which M950 S must have created, to angle or pulse S.",
     "m280-set-servo-position", kM280},
    {'M', 290, -1, "Babystepping",
     "Shifts Z (or another axis) by a small amount without a move command, relative or absolute.", "m290-baby-stepping",
     kM290},
    {'M', 291, -1, "Show a message box",
     "Shows message P with title R; S chooses whether it blocks and which buttons or input it offers.",
     "m291-display-message-and-optionally-wait-for-response", kM291},
    {'M', 292, -1, "Answer a message box", "Closes the current M291 box, cancelling with P1.",
     "m292-acknowledge-blocking-message", kM292},
};
static_assert(strictly_sorted(kDocs));

}  // namespace

std::span<const CommandDoc> m_codes_low() { return kDocs; }

}  // namespace rrflint::docs
