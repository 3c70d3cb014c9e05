// M300 to M569.x of the command documentation table (command_docs_parts.h; sources and anchors: command_docs.cc).
#include "lint/boot/command_docs_parts.h"

namespace rrflint::docs {
namespace {

constexpr std::span<const ParamDoc> kNone;  // a command without parameters
constexpr ParamDoc kM300[] = {{'P', "duration (ms)"}, {'S', "frequency (Hz)"}};
constexpr ParamDoc kM301[] = {
    {'H', "heater number (default 1)"}, {'P', "proportional term"}, {'I', "integral term"}, {'D', "derivative term"}};
constexpr ParamDoc kM302[] = {{'P', "P1: allow extruding when cold"},
                              {'S', "lowest extrusion temperature"},
                              {'R', "lowest retraction temperature"}};
constexpr ParamDoc kM303[] = {{'H', "heater to tune"},
                              {'T', "tool whose heater to tune (3.2+)"},
                              {'S', "target temperature"},
                              {'P', "PWM to tune at"},
                              {'A', "ambient temperature (3.2+)"},
                              {'Y', "hysteresis of the cycles (3.3+)"},
                              {'F', "fan PWM while tuning (3.3+)"},
                              {'Q', "what to do with the result (3.5+)"}};
constexpr ParamDoc kM305[] = {{'P', "heater number"},   {'T', "thermistor resistance at 25 C"},
                              {'B', "thermistor beta"}, {'C', "Steinhart-Hart C coefficient"},
                              {'R', "series resistor"}, {'X', "sensor channel"}};
constexpr ParamDoc kM307[] = {{'H', "heater number"},
                              {'R', "heating rate (C/s)"},
                              {'K', "cooling rates, fan off:fan on (3.2+)"},
                              {'C', "time constants (s) before 3.2"},
                              {'D', "dead time (s)"},
                              {'S', "highest PWM"},
                              {'V', "supply voltage it was tuned at"},
                              {'B', "B1: bang-bang instead of PID"},
                              {'E', "cooling rate exponent (3.2+)"},
                              {'A', "gain, before 3.2"}};
constexpr ParamDoc kM308[] = {{'S', "sensor number"},
                              {'P', "pin name (or a port of the board's sensor channel)"},
                              {'Y', "sensor type, e.g. \"thermistor\"; given: (re)creates the sensor"},
                              {'A', "sensor name"},
                              {'T', "thermistor resistance at 25 C"},
                              {'B', "thermistor beta"},
                              {'C', "Steinhart-Hart C coefficient"},
                              {'R', "series resistor"},
                              {'L', "ADC low-end correction"},
                              {'H', "ADC high-end correction"}};
constexpr ParamDoc kM350[] = {{'X', "X microstepping"},
                              {'Y', "Y microstepping"},
                              {'Z', "Z microstepping"},
                              {'E', "extruder microstepping, one per extruder"},
                              {'I', "I1: interpolate to x256 (some drivers)"}};
constexpr ParamDoc kM376[] = {{'H', "height over which compensation fades out, 0 for none"}};
constexpr ParamDoc kM409[] = {{'K', "object model key"}, {'F', "flags: v verbose, f frequently changing, d depth"}};
constexpr ParamDoc kM452[] = {{'C', "laser pin"},
                              {'R', "power that S means at full scale"},
                              {'F', "PWM frequency"},
                              {'S', "S1: power follows moves only"}};
constexpr ParamDoc kM453[] = {
    {'C', "spindle pins (before 3.3)"}, {'S', "spindle number (before 3.3)"}, {'R', "highest RPM (before 3.3)"}};
constexpr ParamDoc kM500[] = {{'P', "P10: also save tool offsets; P31: also save G31 values"}};
constexpr ParamDoc kM505[] = {{'P', "folder that becomes the system folder"}};
constexpr ParamDoc kAddress[] = {{'P', "the address or name"}, {'I', "network interface number"}};
constexpr ParamDoc kM552[] = {{'S', "0 off, 1 on (client), 2 access point (WiFi)"},
                              {'P', "IP address (0.0.0.0: DHCP), or the SSID to join"},
                              {'I', "network interface number"},
                              {'R', "HTTP port (older versions)"}};
constexpr ParamDoc kM554[] = {{'P', "gateway address"}, {'S', "DNS server address"}, {'I', "network interface number"}};
constexpr ParamDoc kM555[] = {{'P', "firmware to emulate: 1 RepRap, 2 Marlin, 6 nanoDLP, ..."}};
constexpr ParamDoc kM557[] = {{'X', "min:max X to probe"},
                              {'Y', "min:max Y to probe"},
                              {'S', "spacing between points"},
                              {'P', "number of points in X:Y"},
                              {'R', "radius to probe (round beds)"}};
constexpr ParamDoc kM558[] = {{'K', "probe number (default 0)"},
                              {'P', "probe type; given: creates or re-creates the probe"},
                              {'C', "input pin (needs P)"},
                              {'H', "dive height (mm)"},
                              {'F', "probing speed (mm/min), or fast:slow"},
                              {'T', "travel speed between points (mm/min)"},
                              {'A', "most probes per point"},
                              {'S', "tolerance between probes of one point (mm)"},
                              {'R', "recovery time after probing (s)"},
                              {'B', "B1: heaters off while probing"}};
constexpr ParamDoc kM559[] = {{'P', "file name"}};
constexpr ParamDoc kM563[] = {{'P', "tool number (0-49 from 3.1)"},
                              {'S', "tool name"},
                              {'D', "extruder drives, which M584 E must have created"},
                              {'H', "heaters (not checked to exist)"},
                              {'F', "fans"},
                              {'X', "axes the tool's X maps to"},
                              {'Y', "axes the tool's Y maps to"},
                              {'Z', "axes the tool's Z maps to (3.5+)"},
                              {'R', "spindle (3.3+)"}};
constexpr ParamDoc kM564[] = {{'H', "H1: forbid moving axes that are not homed"},
                              {'S', "S1: keep moves within the M208 limits"}};
constexpr ParamDoc kM566[] = {{'X', "X jerk (mm/min)"},
                              {'Y', "Y jerk (mm/min)"},
                              {'Z', "Z jerk (mm/min)"},
                              {'E', "extruder jerks (mm/min)"},
                              {'P', "P1: apply jerk between all moves"}};
constexpr ParamDoc kM567[] = {{'P', "tool number"}, {'E', "mix ratios, one per extruder of the tool"}};
constexpr ParamDoc kM568[] = {{'P', "tool number (3.3: required; 3.4+: default the current tool)"},
                              {'R', "standby temperatures, one per heater"},
                              {'S', "active temperatures, one per heater"},
                              {'A', "heater state: 0 off, 1 standby, 2 active"},
                              {'F', "spindle speed"}};
constexpr ParamDoc kM569[] = {{'P', "driver number (board.driver on CAN)"},
                              {'S', "direction: S1 forwards, S0 backwards"},
                              {'R', "enable polarity"},
                              {'D', "mode: 2 spreadCycle, 3 stealthChop, 4 closed loop"},
                              {'T', "step pulse timings (us)"},
                              {'V', "stealthChop to spreadCycle threshold"},
                              {'H', "high-speed threshold"},
                              {'Y', "hysteresis start:end"},
                              {'C', "chopper register value"},
                              {'F', "off time"},
                              {'B', "blanking time"}};
constexpr ParamDoc kM569_1[] = {{'P', "driver (board.driver)"},
                                {'T', "encoder type"},
                                {'C', "encoder counts per step"},
                                {'S', "motor full steps per turn (3.5+)"},
                                {'E', "warning:error thresholds"},
                                {'R', "proportional constant"},
                                {'I', "integral constant"},
                                {'D', "derivative constant"},
                                {'V', "velocity feed-forward (3.5+)"},
                                {'A', "acceleration feed-forward (3.5+)"},
                                {'H', "minimum holding current"},
                                {'Q', "motor torque constant (3.5+)"}};
constexpr ParamDoc kM569_2[] = {{'P', "driver number"}, {'R', "register number"}, {'V', "value to write"}};
constexpr ParamDoc kM569_3[] = {{'P', "drivers (board.driver)"}, {'S', "set the encoder reference point"}};
constexpr ParamDoc kM569_4[] = {{'P', "drivers (board.driver)"},
                                {'T', "torque (Nm), 0 back to position mode"},
                                {'V', "speed limit (full steps/s)"}};
constexpr ParamDoc kM569_5[] = {{'P', "driver (board.driver)"},   {'F', "file to write"},
                                {'A', "when to start recording"}, {'R', "sample rate"},
                                {'D', "variables to record"},     {'V', "tuning move to make"},
                                {'S', "number of samples"},       {'T', "step move duration (ms)"}};
constexpr ParamDoc kM569_6[] = {{'P', "driver (board.driver)"}, {'V', "tuning moves to run"}};
constexpr ParamDoc kM569_7[] = {{'P', "driver (board.driver)"},
                                {'C', "brake port"},
                                {'S', "delay between brake and motor (ms, 3.5+)"},
                                {'V', "brake voltage (3.5+)"}};
constexpr ParamDoc kM569_8[] = {{'P', "driver (board.driver)"}};

constexpr CommandDoc kDocs[] = {
    {'M', 300, -1, "Beep", "Sounds a tone on the PanelDue or web interface.", "m300-play-beep-sound", kM300},
    {'M', 301, -1, "PID parameters",
     "Sets the PID terms of heater H (default 1), which must exist: before M950 creates it the answer is 'Heater n not "
     "found'.",
     "m301-set-pid-parameters", kM301},
    {'M', 302, -1, "Cold extrusion", "Allows or forbids extruding below a temperature, and sets those temperatures.",
     "m302-allow-cold-extrudes", kM302},
    {'M', 303, -1, "Tune a heater",
     "Runs heater auto-tuning; the result is an M307 line to save, not something for config.g.",
     "m303-run-heater-tuning", kM303},
    {'M', 305, -1, "Thermistor parameters (RRF 2)",
     "RRF 2 only: set the sensor of heater P. RRF 3 answers that M308 and M950 replace it and sets nothing.",
     "m305-set-temperature-sensor-parameters", kM305},
    {'M', 307, -1, "Heater model",
     "Sets the heating model of heater H, which M950 must have created ('Heater n not found' otherwise); without a "
     "model the heater cannot be switched on.",
     "m307-set-or-report-heating-process-parameters", kM307},
    {'M', 308, -1, "Temperature sensor",
     "With Y creates (or re-creates) sensor S on pin P; without Y changes or reports an existing sensor (3.0+).",
     "m308-set-or-report-sensor-parameters", kM308},
    {'M', 350, -1, "Microstepping",
     "Sets microstepping of the drivers mapped now (later M584 drivers keep x16) and rescales the axis steps per mm by "
     "the change.",
     "m350-set-microstepping-mode", kM350},
    {'M', 376, -1, "Compensation taper", "Fades mesh compensation out over the first H mm of height.",
     "m376-set-bed-compensation-taper", kM376},
    {'M', 400, -1, "Wait for moves", "Waits until all queued moves have finished.",
     "m400-wait-for-current-moves-to-finish", kNone},
    {'M', 409, -1, "Query the object model", "Replies with the part of the object model that key K names (3.1+).",
     "m409-query-object-model", kM409},
    {'M', 451, -1, "FFF mode", "Switches the machine to 3D printing mode (the default).",
     "m451-select-fff-printer-mode", kNone},
    {'M', 452, -1, "Laser mode", "Switches to laser mode: S on moves sets the laser power, which G0 moves never fire.",
     "m452-select-laser-device-mode", kM452},
    {'M', 453, -1, "CNC mode",
     "Switches to CNC mode (parenthesised comments allowed); before 3.3 C configured spindle S, from 3.3 spindles are "
     "M950 R ports.",
     "m453-select-cnc-device-mode", kM453},
    {'M', 500, -1, "Save settings",
     "Writes tuned values (heater models, delta calibration, workplaces, optionally tool offsets and G31) to "
     "config-override.g.",
     "m500-store-parameters", kM500},
    {'M', 501, -1, "Load saved settings",
     "Runs config-override.g at this point, so its values replace the ones set before it; settings after it win over "
     "the saved ones.",
     "m501-read-stored-parameters", kNone},
    {'M', 502, -1, "Revert to config.g", "Runs config.g again without its M501, dropping the saved values.",
     "m502-revert-stored-parameters", kNone},
    {'M', 505, -1, "System folder", "Makes P the folder that relative macro paths and the system files are read from.",
     "m505-set-configuration-file-folder", kM505},
    {'M', 540, -1, "MAC address", "Sets the MAC address of the Ethernet interface.", "m540-set-mac-address", kAddress},
    {'M', 550, -1, "Machine name", "Sets the name the machine shows and announces on the network.", "m550-set-name",
     kAddress},
    {'M', 551, -1, "Password", "Sets the password the web interface and FTP ask for.", "m551-set-password", kAddress},
    {'M', 552, -1, "Network on, off, or IP address",
     "Enables or disables the network interface, or sets its address (0.0.0.0 for DHCP).",
     "m552-set-ip-address-enabledisable-network-interface", kM552},
    {'M', 553, -1, "Netmask", "Sets the netmask of the network interface.", "m553-set-netmask", kAddress},
    {'M', 554, -1, "Gateway and DNS", "Sets the gateway and DNS server of the network interface.",
     "m554-set-gateway-andor-dns-server", kM554},
    {'M', 555, -1, "Compatibility", "Makes replies look like those of another firmware, for hosts that expect it.",
     "m555-set-compatibility", kM555},
    {'M', 557, -1, "Probing grid",
     "Defines the grid G29 probes: the X/Y ranges and spacing or point count, or a radius for round beds.",
     "m557-set-z-probe-point-or-define-probing-grid", kM557},
    {'M', 558, -1, "Create or change a probe",
     "With P creates probe K (re-creating one drops its G31 values); without P only changes or reports the probe, and "
     "C then fails.",
     "m558-create-or-modify-probe", kM558},
    {'M', 559, -1, "Upload a file",
     "The lines after it, up to the end-of-file marker, are written into the file, not run.", "m559-upload-file",
     kM559},
    {'M', 560, -1, "Upload a web file",
     "The lines after it, up to the end-of-file marker, are written into the file, not run.", "m560-upload-file",
     kM559},
    {'M', 561, -1, "Clear bed compensation", "Turns bed levelling off by resetting the bed transform.",
     "m561-set-identity-transform", kNone},
    {'M', 563, -1, "Define or remove a tool",
     "Creates tool P (re-creating it when it exists, which resets its offsets and temperatures) with its extruders, "
     "heaters, fans and axis maps; D-1 H-1 deletes it.",
     "m563-define-or-remove-a-tool", kM563},
    {'M', 564, -1, "Movement limits",
     "Chooses whether moves stay within the M208 limits and whether unhomed axes may move.", "m564-limit-axes", kM564},
    {'M', 566, -1, "Jerk (mm/min)", "Sets the largest instant speed change of existing axes and extruders.",
     "m566-set-allowable-instantaneous-speed-change", kM566},
    {'M', 567, -1, "Mix ratios", "Sets the mixing ratios of the extruders of tool P, which must exist.",
     "m567-set-tool-mix-ratios", kM567},
    {'M', 568, -1, "Tool temperatures and state",
     "3.3+: temperatures, heater state and spindle speed of an existing tool. Up to 3.2 it was the mixing switch and "
     "does nothing.",
     "m568-set-tool-settings", kM568},
    {'M', 569, -1, "Driver settings",
     "Sets direction, enable polarity, mode and timings of driver P (local, or board.driver on CAN).",
     "m569-set-motor-driver-direction-enable-polarity-mode-and-step-pulse-timing", kM569},
    {'M', 569, 1, "Closed-loop settings",
     "Configures the encoder and control loop of a closed-loop driver on a CAN board (3.2+).",
     "m5691-stepper-driver-closed-loop-configuration", kM569_1},
    {'M', 569, 2, "Driver register", "Reads or writes a register of a smart driver (3.3+).",
     "m5692-read-or-write-stepper-driver-register", kM569_2},
    {'M', 569, 3, "Read encoder", "Reads the encoders of drivers on the secondary CAN bus (3.4+).",
     "m5693-read-motor-driver-encoder-via-secondary-can-bus", kM569_3},
    {'M', 569, 4, "Torque mode", "Puts a closed-loop driver into torque mode, or back to position mode (3.4+).",
     "m5694-set-motor-driver-torque-mode", kM569_4},
    {'M', 569, 5, "Closed-loop recording", "Records closed-loop data from a driver into a file (3.4+).",
     "m5695-closed-loop-data-collection", kM569_5},
    {'M', 569, 6, "Closed-loop tuning", "Runs tuning moves on a closed-loop driver (3.4+).",
     "m5696-execute-closed-loop-tuning-move", kM569_6},
    {'M', 569, 7, "Motor brake", "Names the port that releases the brake of a motor when its driver is enabled (3.4+).",
     "m5697-configure-motor-brake-port", kM569_7},
    {'M', 569, 8, "Read motor force", "Reads the force of drivers on the secondary CAN bus (3.5+).",
     "m5698-read-motor-force-via-secondary-can-bus", kM569_8},
};
static_assert(strictly_sorted(kDocs));

}  // namespace

std::span<const CommandDoc> m_codes_mid() { return kDocs; }

}  // namespace rrflint::docs
