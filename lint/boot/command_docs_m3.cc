// M570 and above, then T, of the command documentation table (command_docs_parts.h; sources and anchors:
// command_docs.cc).
#include "lint/boot/command_docs_parts.h"

namespace rrflint::docs {
namespace {

constexpr std::span<const ParamDoc> kNone;  // a command without parameters
constexpr ParamDoc kM570[] = {{'H', "heater number"},
                              {'P', "how long an anomaly may last (s, default 5)"},
                              {'T', "allowed excursion from the target (C, default 15)"},
                              {'R', "bad readings in a row allowed (3.5+)"},
                              {'S', "print pause timeout (up to 3.3)"}};
constexpr ParamDoc kM572[] = {{'D', "extruders"}, {'S', "pressure advance (seconds)"}};
constexpr ParamDoc kM574[] = {{'X', "X endstop: 0 none, 1 low end, 2 high end"},
                              {'Y', "Y endstop"},
                              {'Z', "Z endstop"},
                              {'S', "type: 1 switch, 2 probe, 3 stall (one motor), 4 stall (each motor)"},
                              {'P', "input pins, one per motor"},
                              {'K', "probe number for S2 (3.5+)"}};
constexpr ParamDoc kM575[] = {{'P', "serial channel"},
                              {'B', "baud rate"},
                              {'S', "mode: PanelDue with or without checksums, raw G-code, or a device (3.5+)"},
                              {'C', "RS485 transmit enable pin"}};
constexpr ParamDoc kM577[] = {{'X', "wait for the X endstop"},
                              {'Y', "wait for the Y endstop"},
                              {'Z', "wait for the Z endstop"},
                              {'P', "input ports to wait for"},
                              {'S', "level: 1 triggered (default), 0 not triggered"}};
constexpr ParamDoc kM579[] = {{'X', "X scale factor"}, {'Y', "Y scale factor"}, {'Z', "Z scale factor"}};
constexpr ParamDoc kM581[] = {{'T', "trigger number: 0 emergency stop, 1 pause, n runs trigger<n>.g"},
                              {'P', "input ports (M950 J), -1 to clear"},
                              {'S', "1 rising edge (default), 0 falling edge, -1 remove the inputs"},
                              {'R', "when: 0 always, 1 only while printing, 2 only when not printing"},
                              {'X', "axis endstops (before 3.0)"}};
constexpr ParamDoc kM582[] = {{'T', "trigger number"}, {'S', "S1: only when an input is active (3.5+)"}};
constexpr ParamDoc kM584[] = {{'X', "X drivers"},
                              {'Y', "Y drivers"},
                              {'Z', "Z drivers"},
                              {'U', "U drivers; any new axis letter creates that axis"},
                              {'E', "extruder drivers; their count is the number of extruders"},
                              {'P', "number of visible axes"},
                              {'R', "R1: new axes are rotational (3.2+)"},
                              {'S', "S1: new axes are fed as rotational (3.2+)"}};
constexpr ParamDoc kM585[] = {{'X', "probe in X, this far"},
                              {'Y', "probe in Y, this far"},
                              {'Z', "probe in Z, this far"},
                              {'F', "probing speed"},
                              {'S', "direction: 0 towards the low end"},
                              {'P', "probe number"},
                              {'E', "endstop to use (older versions)"},
                              {'R', "probing radius"}};
constexpr ParamDoc kM586[] = {{'P', "protocol: 0 HTTP, 1 FTP, 2 Telnet, 4 MQTT (3.5+)"},
                              {'S', "S1 enable, S0 disable"},
                              {'R', "TCP port"},
                              {'T', "T1: use TLS"},
                              {'C', "allowed cross-origin site (3.2+)"},
                              {'I', "network interface number"}};
constexpr ParamDoc kM587[] = {
    {'S', "network SSID"}, {'P', "network password"}, {'I', "fixed IP address"}, {'J', "gateway"}, {'K', "netmask"}};
constexpr ParamDoc kM591[] = {{'D', "extruder number"},
                              {'P', "monitor type; P0 removes the monitor"},
                              {'C', "input pin"},
                              {'S', "S1 enable, S0 disable checking"},
                              {'R', "allowed range of measured/commanded (percent)"},
                              {'E', "extrusion length per check (mm)"},
                              {'L', "filament per rotation or per pulse (mm)"},
                              {'A', "A1: check every extrusion, not only printing moves"}};
constexpr ParamDoc kM592[] = {{'D', "extruder number"},
                              {'A', "first coefficient"},
                              {'B', "second coefficient"},
                              {'L', "upper limit of the correction"}};
constexpr ParamDoc kM593[] = {{'P', "shaper type, e.g. \"mzv\" or \"none\""},
                              {'F', "frequency to cancel (Hz)"},
                              {'S', "damping factor"},
                              {'L', "lowest acceleration (ignored from 3.6)"},
                              {'H', "custom shaper amplitudes"},
                              {'T', "custom shaper durations"}};
constexpr ParamDoc kM665[] = {{'L', "diagonal rod length(s)"},   {'R', "delta radius"},
                              {'B', "printable radius"},         {'H', "homed nozzle height"},
                              {'X', "X tower angle correction"}, {'Y', "Y tower angle correction"},
                              {'Z', "Z tower angle correction"}};
constexpr ParamDoc kM666[] = {{'X', "X endstop correction"},
                              {'Y', "Y endstop correction"},
                              {'Z', "Z endstop correction"},
                              {'A', "X tilt (percent)"},
                              {'B', "Y tilt (percent)"}};
constexpr ParamDoc kM667[] = {{'S', "S1 CoreXY, S0 Cartesian"}};
constexpr ParamDoc kM669[] = {{'K', "kinematics type number or name"},
                              {'X', "motor coefficients of X (matrix kinematics)"},
                              {'Y', "motor coefficients of Y"},
                              {'Z', "motor coefficients of Z"},
                              {'S', "segments per second"},
                              {'T', "shortest segment (mm)"}};
constexpr ParamDoc kM671[] = {{'X', "X positions of the leadscrews or screws"},
                              {'Y', "Y positions of the leadscrews or screws"},
                              {'S', "largest correction allowed (mm)"},
                              {'P', "screw pitch (manual levelling)"},
                              {'F', "correction factor"}};
constexpr ParamDoc kM672[] = {{'S', "bytes to send to the probe"}, {'K', "probe number (3.1+)"}};
constexpr ParamDoc kM673[] = {{'U', "rotary axis the plane turns on"}, {'P', "factor for the correction"}};
constexpr ParamDoc kM851[] = {{'Z', "trigger height, with the sign Marlin uses"}};
constexpr ParamDoc kM905[] = {{'P', "date YYYY-MM-DD"}, {'S', "time HH:MM:SS"}, {'T', "time zone (SBC)"}};
constexpr ParamDoc kM906[] = {{'X', "X motor current (mA)"},   {'Y', "Y motor current (mA)"},
                              {'Z', "Z motor current (mA)"},   {'E', "extruder currents (mA)"},
                              {'I', "idle current (percent)"}, {'T', "idle timeout (s, 3.6+)"}};
constexpr ParamDoc kM911[] = {{'S', "voltage below which to save and stop"},
                              {'R', "voltage above which to resume"},
                              {'P', "commands to run at power failure"}};
constexpr ParamDoc kPercent[] = {
    {'X', "X percent"}, {'Y', "Y percent"}, {'Z', "Z percent"}, {'E', "extruder percents"}};
constexpr ParamDoc kM915[] = {{'P', "drivers"},
                              {'X', "the drivers of X"},
                              {'Y', "the drivers of Y"},
                              {'Z', "the drivers of Z"},
                              {'S', "stall threshold"},
                              {'F', "F1: filtered"},
                              {'H', "lowest full steps/s it works at"},
                              {'T', "coolStep setting"},
                              {'R', "action: 0 none, 1 report, 2 pause / event, 3 event"}};
constexpr ParamDoc kM929[] = {{'P', "log file name"}, {'S', "S0 stop; S1 warnings, S2 info, S3 debug (3.2+)"}};
constexpr ParamDoc kM950[] = {{'H', "heater number"},
                              {'F', "fan number"},
                              {'J', "GPIO input port number"},
                              {'P', "GPIO output port number"},
                              {'S', "servo port number"},
                              {'R', "spindle number (3.3+)"},
                              {'E', "LED strip number (3.5+)"},
                              {'D', "SD slot (Duet 3 6HC)"},
                              {'C', "pin name(s); \"nil\" frees the pin and deletes the device"},
                              {'Q', "PWM frequency (Hz)"},
                              {'T', "sensor of a heater; LED type; spindle type"},
                              {'L', "spindle RPM range"},
                              {'K', "fan tacho pulses per turn, spindle PWM values (3.5+)"}};
constexpr ParamDoc kM955[] = {{'P', "accelerometer (board.device)"},
                              {'I', "orientation"},
                              {'S', "sample rate (Hz)"},
                              {'R', "resolution (bits)"},
                              {'C', "CS and INT pins"},
                              {'Q', "SPI clock (3.3+)"}};
constexpr ParamDoc kM956[] = {{'P', "accelerometer (board.device)"},
                              {'S', "number of samples"},
                              {'A', "start: 0 now, 1 just before the next move"},
                              {'X', "record X"},
                              {'Y', "record Y"},
                              {'Z', "record Z"},
                              {'F', "file to write"}};
constexpr ParamDoc kM957[] = {{'E', "event type"},
                              {'D', "device number"},
                              {'B', "CAN address of the board"},
                              {'P', "extra data"},
                              {'S', "text of the event"}};
constexpr ParamDoc kM999[] = {{'B', "CAN address of the board to restart"}, {'P', "reset flags"}};
constexpr ParamDoc kT[] = {{'P', "macros to run: 1 tfree, 2 tpre, 4 tpost (default 7; P0 none)"},
                           {'R', "R1: the tool active at the last pause"},
                           {'T', "tool number as a parameter (3.4+)"}};

constexpr CommandDoc kDocs[] = {
    {'M', 570, -1, "Heater fault detection",
     "Sets how long and how far heater H, which must exist, may stray before it faults; re-creating the heater resets "
     "it.",
     "m570-configure-heater-fault-detection", kM570},
    {'M', 572, -1, "Pressure advance", "Sets pressure advance of extruders D, which must exist; without S it reports.",
     "m572-set-or-report-extruder-pressure-advance", kM572},
    {'M', 574, -1, "Endstops",
     "Says where each axis endstop is and of which type, and which pins it reads; for an axis that does not exist it "
     "only reports.",
     "m574-set-endstop-configuration", kM574},
    {'M', 575, -1, "Serial port", "Sets the baud rate and mode of a serial channel (PanelDue, raw G-code, devices).",
     "m575-set-serial-comms-parameters", kM575},
    {'M', 577, -1, "Wait for an input", "Waits until the endstops or input ports named reach the level S.",
     "m577-wait-until-endstop-is-triggered", kM577},
    {'M', 579, -1, "Scale axes",
     "Scales the coordinates of the axes named, to correct a machine that prints too large or small.",
     "m579-scale-cartesian-axes", kM579},
    {'M', 581, -1, "External trigger",
     "Makes input ports P (M950 J) fire trigger T on an edge: T0 stops, T1 pauses, others run trigger<T>.g.",
     "m581-configure-external-trigger-on-inputs-andor-endstops", kM581},
    {'M', 582, -1, "Check a trigger", "Fires trigger T now if one of its inputs is already active.",
     "m582-check-external-trigger", kM582},
    {'M', 584, -1, "Drive mapping",
     "Maps axes and extruders to drivers; a new letter creates that axis (in XYZUVWABCD order) and E sets the extruder "
     "count. Axes are never deleted.",
     "m584-set-drive-mapping", kM584},
    {'M', 585, -1, "Probe a tool offset",
     "Measures the current tool's offset on one axis against a probe and stores it; needs a homed axis, so not in "
     "config.g.",
     "m585-probe-tool", kM585},
    {'M', 586, -1, "Network protocols", "Enables or disables HTTP, FTP, Telnet and (3.5+) MQTT, and their ports.",
     "m586-configure-network-protocols", kM586},
    {'M', 587, -1, "Remember a WiFi network", "Stores an SSID and password in the WiFi module; without S lists them.",
     "m587-add-wifi-host-network-to-remembered-list-or-list-remembered-networks", kM587},
    {'M', 591, -1, "Filament monitor",
     "With P configures the filament monitor of extruder D (P0 removes it); without P changes the existing one.",
     "m591-configure-filament-sensing", kM591},
    {'M', 592, -1, "Nonlinear extrusion",
     "Adds extrusion at high flow rates for extruder D, by the A and B coefficients.",
     "m592-configure-nonlinear-extrusion", kM592},
    {'M', 593, -1, "Input shaping", "Chooses the input shaper and the ringing frequency it cancels.",
     "m593-configure-input-shaping", kM593},
    {'M', 600, -1, "Filament change", "Pauses the print and runs filament-change.g (or pause.g).",
     "m600-filament-change-pause", kNone},
    {'M', 665, -1, "Delta geometry",
     "Sets the rods, radius and homed height of a linear delta (and selects delta kinematics, which drops the M671 "
     "data).",
     "m665-set-delta-configuration", kM665},
    {'M', 666, -1, "Delta endstop corrections", "Sets the endstop corrections and bed tilt of a linear delta.",
     "m666-set-delta-endstop-adjustment", kM666},
    {'M', 667, -1, "CoreXY mode (old)",
     "Selects CoreXY (S1) or Cartesian kinematics; RRF 3.5 and later refuse it in favour of M669.",
     "m667-select-corexy-or-related-mode", kM667},
    {'M', 669, -1, "Kinematics",
     "Selects the kinematics K and its parameters; a change of type drops the parameters and the M671 leadscrews set "
     "before.",
     "m669-set-kinematics-type-and-kinematics-parameters", kM669},
    {'M', 671, -1, "Leadscrew positions",
     "Gives the positions of the Z leadscrews (or levelling screws) that G32 corrects; a later kinematics change "
     "discards them.",
     "m671-define-positions-of-z-pivot-points-or-bed-levelling-screws", kM671},
    {'M', 672, -1, "Program a probe", "Sends programming bytes to a probe that takes them, such as the Smart Effector.",
     "m672-program-z-probe", kM672},
    {'M', 673, -1, "Align a rotary plane",
     "Turns a rotary axis to level a plane it carries, from two probed points (3.0+).",
     "m673-align-plane-on-rotary-axis", kM673},
    {'M', 703, -1, "Apply filament settings", "Runs config.g of the filament loaded in the current tool.",
     "m703-configure-filament", kNone},
    {'M', 851, -1, "Probe Z offset (Marlin)",
     "Sets the probe trigger height with Marlin's sign convention; G31 is the RRF form.",
     "m851-set-z-probe-offset-marlin-compatibility", kM851},
    {'M', 905, -1, "Date and time", "Sets the clock of the board.", "m905-set-local-date-and-time", kM905},
    {'M', 906, -1, "Motor currents", "Sets the motor currents of existing axes and extruders, and the idle current.",
     "m906-set-motor-currents", kM906},
    {'M', 911, -1, "Power-fail resume",
     "Saves the print state and runs P when the supply voltage drops below S, so that M916 can resume with "
     "resurrect.g.",
     "m911-configure-auto-save-on-loss-of-power", kM911},
    {'M', 913, -1, "Motor current percent", "Scales the motor currents of the axes named, in percent of M906.",
     "m913-set-motor-percentage-of-normal-current", kPercent},
    {'M', 915, -1, "Stall detection",
     "Sets stall detection sensitivity and the action on a stall for the drivers or axes named.",
     "m915-configure-motor-stall-detection", kM915},
    {'M', 917, -1, "Standstill current", "Sets the current of motors at rest, in percent of M906.",
     "m917-set-motor-standstill-current-reduction", kPercent},
    {'M', 929, -1, "Event log", "Starts or stops writing the event log to a file on the SD card.",
     "m929-startstop-event-logging-to-sd-card", kM929},
    {'M', 950, -1, "Create a device",
     "With C creates (or re-creates, losing its settings) a heater, fan, port or spindle on that pin; without C only "
     "changes or reports it (3.0+).",
     "m950-create-heater-fan-spindle-led-strip-or-gpioservo-pin", kM950},
    {'M', 955, -1, "Accelerometer", "Configures an accelerometer on the main board or a CAN board (3.3+).",
     "m955-configure-accelerometer", kM955},
    {'M', 956, -1, "Record acceleration", "Records accelerometer samples into a CSV file (3.3+).",
     "m956-collect-accelerometer-data-and-write-to-file", kM956},
    {'M', 957, -1, "Raise an event", "Raises an event as if a device had reported it, to test event macros (3.4+).",
     "m957-raise-event", kM957},
    {'M', 999, -1, "Restart", "Restarts the board (or CAN board B).", "m999-restart", kM999},
    {'T', -1, -1, "Select a tool",
     "Tn selects tool n, running tfree, tpre and tpost macros unless P says otherwise; T-1 deselects; T alone reports. "
     "An unknown tool is silently none.",
     "t-select-tool", kT},
};
static_assert(strictly_sorted(kDocs));

}  // namespace

std::span<const CommandDoc> m_codes_high() { return kDocs; }

}  // namespace rrflint::docs
