// The machine model's facts beyond creation (issue 15 §1): heater monitor slots, PID, fault detection, fan
// thermostats, ports and their users, filament monitors, G31, kinematics and leadscrews, drivers, steps/mm and
// microstepping. Each: known, unknown value, inside `if` (maybe), re-creation. (tests/model_test.cc is near the
// 500-line limit.)
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "lint/boot/commands.h"
#include "lint/engine/linter.h"
#include "lint/render/model_render.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

struct Run {
  SourceManager sources;
  MemoryReader reader;
  MachineResult result;
  const MachineState& end() const { return result.end_of_boot; }
  std::string word(NodeId id) const {
    if (id == kNoNode) return "default";
    const Node& n = result.graph.nodes[id];
    const FileUnit& u = result.machine->unit(n.unit);
    return std::string(u.parsed.text(u.parsed.commands[n.index].span));
  }
};

std::unique_ptr<Run> config(std::string text, std::optional<Version> fw = kLatestVersion) {
  auto r = std::make_unique<Run>();
  r->reader.add("/sys/config.g", std::move(text));
  LintOptions o;
  o.firmware = fw;
  o.select = {"syntax-error"};
  r->result = lint_machine(r->sources, r->reader, builtin_rules(), o);
  return r;
}

const std::string kBed = "M308 S0 Y\"thermistor\" P\"bedtemp\"\nM950 H0 C\"bedheat\" T0\n";
const std::string kUnknownIf = "if move.axes[0].homed\n";

}  // namespace

TEST_CASE("model: heater monitor slots follow Heater::ConfigureMonitor", "[model]") {
  auto r = config(kBed + "M140 H0\nM143 H0 P1 S120 A2\nM143 H0 P2 T0 C1 S10\n");
  const Heater& h = r->end().heaters.at(0);
  CHECK(r->word(h.default_monitor) == "M140 H0");
  CHECK(h.monitors[0].limit.value == 125);
  CHECK(h.monitors[0].sensor.value == 0);
  CHECK(h.monitors[0].condition.value == 0);
  CHECK(h.monitors[1].limit.value == 120);
  CHECK(h.monitors[1].action.value == 2);
  CHECK(h.monitors[1].condition.value == 0);  // C omitted: temperature exceeded
  CHECK(h.monitors[1].sensor.value == 0);     // T omitted: the heater's sensor
  CHECK(r->word(h.monitors[1].set) == "M143 H0 P1 S120 A2");
  CHECK(h.monitors[2].condition.value == 1);
  CHECK(h.monitors[2].limit.value == 10);

  // Unknown values; an expression P may have set any slot.
  auto u = config(kBed + "M143 H0 P1 S{move.axes[0].max}\nM143 H0 P{move.axes[0].max} A1\n");
  const Heater& hu = u->end().heaters.at(0);
  CHECK_FALSE(hu.monitors[1].limit.known);
  CHECK_FALSE(hu.monitors[0].action.known);
  CHECK(hu.default_monitor == kNoNode);
  // Inside an if: maybe, unknown.
  auto m = config(kBed + kUnknownIf + "  M143 H0 P0 S100\nendif\n");
  CHECK(m->end().heaters.at(0).monitors[0].maybe);
  CHECK_FALSE(m->end().heaters.at(0).monitors[0].limit.known);
  // Re-creation resets every slot (disabled).
  auto re = config(kBed + "M143 H0 P1 S120\nM950 H0 C\"bedheat\" T0\n");
  CHECK(re->end().heaters.at(0).monitors[1].condition.value == -1);
  CHECK(re->end().heaters.at(0).monitors[1].set == kNoNode);
  // No P: slot 0 only.
  auto p0 = config(kBed + "M143 H0 S150\n");
  CHECK(p0->end().heaters.at(0).monitors[0].limit.value == 150);
  CHECK(p0->end().heaters.at(0).monitors[1].set == kNoNode);
  // A limit of 2000 or more is invalid: the slot keeps its old values.
  CHECK(config(kBed + "M140 H0\nM143 H0 S2000\n")->end().heaters.at(0).monitors[0].limit.value == 125);
  // An M143 with only A marks the monitors as the user's: a later M140 installs no default.
  auto user = config(kBed + "M143 H0 P1 A2\nM140 H0\n");
  CHECK(user->end().heaters.at(0).monitors[0].condition.value == -1);
  CHECK(user->end().heaters.at(0).default_monitor == kNoNode);
  // A tool heater gets the hot-end default from M563.
  auto tool = config(kBed + "M563 P0 H0\n");
  CHECK(tool->end().heaters.at(0).monitors[0].limit.value == 285);
  CHECK(tool->word(tool->end().heaters.at(0).default_monitor) == "M563 P0 H0");
}

TEST_CASE("model: M301 PID values and M570 fault detection", "[model]") {
  auto r = config(kBed + "M301 H0 P10 I0.5 D40\nM570 H0 P10 T20 R5\n");
  const Heater& h = r->end().heaters.at(0);
  CHECK(h.pid.p.value == 10);
  CHECK(h.pid.i.value == 0.5);
  CHECK(h.pid.d.value == 40);
  CHECK(r->word(h.pid.set) == "M301 H0 P10 I0.5 D40");
  CHECK(h.fault.time.value == 10);
  CHECK(h.fault.excursion.value == 20);
  CHECK(h.fault.bad_readings.value == 5);
  CHECK_FALSE(h.fault.timeout.known);  // S not given
  // Defaults; M570 without H does nothing; M301 without H is heater 1.
  auto d = config(kBed + "M570 P30\nM301 P5\n");
  CHECK(d->end().heaters.at(0).fault.time.value == 5);
  CHECK(d->end().heaters.at(0).fault.excursion.value == 15);
  CHECK_FALSE(d->end().heaters.at(0).pid.p.known);
  // Unknown, maybe, re-created.
  auto u = config(kBed + "M570 H0 P{move.axes[0].max}\n" + kUnknownIf + "  M301 H0 P3\nendif\n");
  CHECK_FALSE(u->end().heaters.at(0).fault.time.known);
  CHECK_FALSE(u->end().heaters.at(0).pid.p.known);
  CHECK(u->end().heaters.at(0).pid.set != kNoNode);
  auto re = config(kBed + "M570 H0 P30\nM950 H0 C\"bedheat\" T0\n");
  CHECK(re->end().heaters.at(0).fault.time.value == 5);
}

TEST_CASE("model: fan thermostats (M106 H sensors, T threshold)", "[model]") {
  const std::string fan = "M950 F1 C\"fan1\"\n";
  auto r = config(fan + "M106 P1 H1:2 T45:60\n");
  const Fan& f = r->end().fans.at(1);
  CHECK(f.thermostatic);
  CHECK(f.sensors == std::vector<int64_t>{1, 2});
  CHECK(f.thresholds == std::vector<double>{45, 60});
  CHECK(r->word(f.thermostat_set) == "M106 P1 H1:2 T45:60");
  CHECK_FALSE(config(fan + "M106 P1 H1 T50\nM106 P1 H-1\n")->end().fans.at(1).thermostatic);
  CHECK_FALSE(config(fan + "M106 P1 H{move.axes[0].max}\n")->end().fans.at(1).thermostat_known);
  CHECK_FALSE(config(fan + kUnknownIf + "  M106 P1 H1\nendif\n")->end().fans.at(1).thermostat_known);
  CHECK_FALSE(config(fan + "M106 P1 H1\n" + fan)->end().fans.at(1).thermostatic);          // re-created
  CHECK(config("M106 P3 H1\n")->end().fans.empty());                                       // Fan number 3 not found
  CHECK_FALSE(config("M950 F0 C\"fan0\"\nM106 H1 T50\n")->end().fans.at(0).thermostatic);  // no P: no fan named
}

TEST_CASE("model: M950 ports and the commands that use them", "[model]") {
  auto r = config(
      "M950 J0 C\"io0.in\"\nM950 P1 C\"out1\"\nM950 S2 C\"servo\"\nM950 R0 C\"spindle\"\nM42 P1 S1\nM280 P2 S90\n"
      "M581 T2 P0 S1 R0\nM581 T3 P0:1 S0\n");
  const MachineState& s = r->end();
  CHECK(s.ports[static_cast<size_t>(PortKind::GpioIn)].at(0).pin == "io0.in");
  CHECK(s.ports[static_cast<size_t>(PortKind::GpioOut)].at(1).pin == "out1");
  CHECK(s.ports[static_cast<size_t>(PortKind::Servo)].at(2).pin == "servo");
  CHECK(r->word(s.ports[static_cast<size_t>(PortKind::Spindle)].at(0).created) == "M950 R0 C\"spindle\"");
  REQUIRE(s.port_uses.size() == 5);
  CHECK(s.port_uses[0].kind == PortKind::GpioOut);
  CHECK(s.port_uses[0].port == 1);
  CHECK(s.port_uses[1].kind == PortKind::Servo);
  CHECK(s.port_uses[2].kind == PortKind::GpioIn);
  CHECK(s.triggers.at(2).rising == std::vector<int64_t>{0});
  CHECK(s.triggers.at(3).falling == std::vector<int64_t>{0, 1});
  // R is no spindle before 3.3; two device letters are an error; C"nil" deletes; unknown numbers.
  CHECK(config("M950 R0 C\"spindle\"\n", Version(3, 2, 2))->end().ports[3].empty());
  CHECK(config("M950 J0 P1 C\"io0.in\"\n")->end().ports[0].empty());
  CHECK(config("M950 J0 C\"io0.in\"\nM950 J0 C\"nil\"\n")->end().ports[0].empty());
  // The heaters and fans count the device letters the same way: two of them create nothing; a letter the version
  // does not read (E before 3.5.0-beta.4, D before 3.4, R before 3.3) is no device letter.
  CHECK(config("M950 H1 F1 C\"out1\" T1\n")->end().heaters.empty());
  CHECK(config("M950 F1 E0 C\"out1\"\n")->end().fans.empty());
  CHECK(config("M950 F1 E0 C\"out1\"\n", Version(3, 4, 6))->end().fans.count(1) == 1);
  CHECK(config("M950 H1 D0 C\"out1\" T1\n", Version(3, 3, 0))->end().heaters.count(1) == 1);
  CHECK(config("M950 E0 C\"led\"\n", Version(3, 4, 6))->end().pins.empty());
  CHECK_FALSE(config("M950 J{move.axes[0].max} C\"io0.in\"\n")->end().ports_known);
  auto m = config(kUnknownIf + "  M950 J0 C\"io0.in\"\n  M42 P{move.axes[0].max} S1\nendif\n");
  CHECK(m->end().ports[0].at(0).maybe);
  CHECK(m->end().port_uses.at(0).port == -1);
  CHECK(m->end().port_uses.at(0).maybe);
  // Re-created: the new pin. M581 P-1 clears the trigger, S-1 removes ports.
  CHECK(config("M950 J0 C\"a\"\nM950 J0 C\"b\"\n")->end().ports[0].at(0).pin == "b");
  CHECK(config("M581 T2 P0:1\nM581 T2 P-1\n")->end().triggers.at(2).rising.empty());
  CHECK(config("M581 T2 P0:1\nM581 T2 P0 S-1\n")->end().triggers.at(2).rising == std::vector<int64_t>{1});
  // M453 configured a spindle before 3.3.
  CHECK(config("M453 C\"exp.heater3\" R20000\n", Version(3, 2, 2))->end().port_uses.at(0).kind == PortKind::Spindle);
  CHECK(config("M453\n")->end().port_uses.empty());
}

TEST_CASE("model: M591 filament monitors", "[model]") {
  auto r = config("M591 D0 P1 C\"e0stop\" S1\nM591 D1 P3 C{global.pin}\n");
  CHECK(r->end().filament_monitors.at(0).type.value == 1);
  CHECK(r->end().filament_monitors.at(0).pin == "e0stop");
  CHECK(r->end().filament_monitors.at(1).pin == "?");
  CHECK(config("M591 D0 P1 C\"e0stop\"\nM591 D0 P0\n")->end().filament_monitors.empty());
  CHECK(config("M591 D0 P1 C\"e0stop\"\nM591 D0 S0\n")->end().filament_monitors.at(0).type.value == 1);
  CHECK_FALSE(config("M591 D{move.axes[0].max} P1 C\"e0stop\"\n")->end().filament_monitors_known);
  CHECK_FALSE(config("M591 D0 P{move.axes[0].max} C\"x\"\n")->end().filament_monitors.at(0).type.known);
  CHECK(config(kUnknownIf + "  M591 D0 P2 C\"x\"\nendif\n")->end().filament_monitors.at(0).maybe);
  CHECK(config("M591 D0 P1 C\"a\"\nM591 D0 P2 C\"b\"\n")->end().filament_monitors.at(0).type.value == 2);
}

TEST_CASE("model: G31 trigger height and offsets", "[model]") {
  const std::string probe = "M558 P5 C\"^zprobe.in\" H5 F120 T6000\n";
  auto r = config(probe + "G31 P500 X-10 Y5 Z2.5\n");
  const Probe& p = r->end().probes.at(0);
  CHECK(p.trigger_height.value == 2.5);
  CHECK(p.x_offset.value == -10);
  CHECK(p.y_offset.value == 5);
  CHECK(r->word(p.g31) == "G31 P500 X-10 Y5 Z2.5");
  CHECK(config(probe)->end().probes.at(0).trigger_height.value == 0.7);                       // ZProbe default
  CHECK(config(probe + "G31 Z2\n" + probe)->end().probes.at(0).trigger_height.value == 0.7);  // re-created
  CHECK_FALSE(config(probe + "G31 Z{move.axes[0].max}\n")->end().probes.at(0).trigger_height.known);
  CHECK_FALSE(config(probe + kUnknownIf + "  G31 Z2\nendif\n")->end().probes.at(0).trigger_height.known);
  CHECK(config(probe + "G31 K1 Z3\n")->end().probes.at(0).g31 == kNoNode);  // no probe 1
}

TEST_CASE("model: kinematics parameters and leadscrews dropped by a type change", "[model]") {
  auto r = config("M669 K1\nM671 X-10:110 Y50:50 S3\nM669 K1 S200\n");
  const MachineState& s = r->end();
  CHECK(s.leadscrews.x == std::vector<double>{-10, 110});
  CHECK(s.leadscrews.known);
  CHECK(s.leadscrews.dropped == kNoNode);  // same type: kept
  CHECK(s.kinematics_params.at("M669 S").value == 200);
  auto d = config("M671 X-10:110 Y50:50\nM669 K1\n");
  CHECK(d->word(d->end().leadscrews.dropped) == "M669 K1");
  CHECK_FALSE(d->end().leadscrews.dropped_maybe);
  auto delta = config("M665 R105.6 L215 H250 B85\n");
  CHECK(delta->end().kinematics == 3);
  CHECK(delta->end().kinematics_params.at("M665 L").value == 215);
  CHECK(config("M665 R105 L215\nM669 K0\n")->end().kinematics_params.empty());
  // A refused M671 (lists of different lengths, one list alone, more than 4) keeps the leadscrews as they were.
  auto k = config("M671 X-10:110 Y50:50\nM671 X0:1:2 Y0:1\nM671 X5:6\nM671 X0:1:2:3:4 Y0:1:2:3:4\n");
  CHECK(k->end().leadscrews.x == std::vector<double>{-10, 110});
  CHECK(k->word(k->end().leadscrews.set) == "M671 X-10:110 Y50:50");
  CHECK(config("M671 X0:1:2 Y0:1\n")->end().leadscrews.set == kNoNode);
  CHECK_FALSE(config("M671 X{global.a} Y0:1\n")->end().leadscrews.known);
  auto u = config("M671 X0:1 Y0:1\nM669 K{move.axes[0].max}\n");
  CHECK(u->end().leadscrews.dropped_maybe);
  auto m = config("M671 X0:1 Y0:1\n" + kUnknownIf + "  M669 K1\nendif\n");
  CHECK(m->end().leadscrews.dropped_maybe);
  CHECK_FALSE(config(kUnknownIf + "  M671 X0:1 Y0:1\nendif\n")->end().leadscrews.known);
  CHECK(config("M671 X0:1 Y0:1\nM669 K1\nM671 X2:3 Y0:1\n")->end().leadscrews.dropped == kNoNode);  // set again
}

TEST_CASE("model: drivers per axis and extruder, local or CAN, shared", "[model]") {
  auto r = config("M584 X0.0 Y0.1 Z0.2:0.3 U1.0 E0.4:0.1 P3\n");
  const MachineState& s = r->end();
  const std::vector<DriverUse> uses = s.driver_uses();
  REQUIRE(uses.size() == 7);
  CHECK(uses[4].driver.board == 1);
  CHECK_FALSE(uses[4].local());
  CHECK(uses[5].extruder);
  CHECK(s.driver_shared(DriverId{0, 1}));
  CHECK_FALSE(s.driver_shared(DriverId{0, 2}));
  CHECK(s.visible_axes == 3);  // U hidden
  CHECK(config("M584 X{move.axes[0].max}\n")->end().axes[0].drivers.empty());
}

TEST_CASE("model: steps/mm and microstepping, with M350's rescaling", "[model]") {
  auto r = config("M92 X80 Y80 Z400\nM350 X32 Y16 I1\nM92 S16 Z400\n");
  const MachineState& s = r->end();
  CHECK(s.axes[0].drive.steps.value == 160);  // 80 at x16, now x32
  CHECK(r->word(s.axes[0].drive.steps_rescaled) == "M350 X32 Y16 I1");
  CHECK(r->word(s.axes[0].drive.steps.origin) == "M92 X80 Y80 Z400");
  CHECK(s.axes[1].drive.steps.value == 80);
  CHECK(s.axes[1].drive.steps_rescaled == kNoNode);
  CHECK(s.axes[0].drive.microsteps.value == 32);
  CHECK(s.axes[0].drive.interpolation);
  CHECK(s.axes[2].drive.steps.value == 400);  // Z x16: S16 keeps it
  auto s2 = config("M350 Z32\nM92 Z400 S16\n");
  CHECK(s2->end().axes[2].drive.steps.value == 800);   // S16 converted to x32
  CHECK_FALSE(s2->end().axes[2].drive.interpolation);  // I omitted: off
  // Defaults: 80, Z 800 on 3.5 (4000 before), E 420, x16.
  CHECK(config("")->end().axes[2].drive.steps.value == 800);
  CHECK(config("", Version(3, 4, 6))->end().axes[2].drive.steps.value == 4000);
  CHECK(config("")->end().extruder_drive[0].steps.value == 420);
  // E lists: one value fills every extruder; too long sets none.
  auto e = config("M584 E0.3:0.4\nM92 E400\nM350 E32:-1\n");
  CHECK(e->end().extruder_drive[1].steps.value == 400);
  CHECK(e->end().extruder_drive[0].steps.value == 800);
  CHECK(e->end().extruder_drive[1].microsteps.value == 16);
  CHECK(config("M584 E0.3\nM92 E400:500\n")->end().extruder_drive[0].steps.value == 420);
  // Unknown, maybe, invalid microstepping.
  CHECK_FALSE(config("M92 X{move.axes[0].max}\n")->end().axes[0].drive.steps.known);
  auto u = config("M92 X80\nM350 X{move.axes[0].max}\n");
  CHECK_FALSE(u->end().axes[0].drive.steps.known);
  CHECK_FALSE(u->end().axes[0].drive.microsteps.known);
  CHECK_FALSE(config(kUnknownIf + "  M350 X32\nendif\n")->end().axes[0].drive.steps.known);
  CHECK(config("M350 X12\n")->end().axes[0].drive.microsteps.value == 16);
  // An axis created later starts from the defaults.
  CHECK(config("M92 X100\nM584 U3\n")->end().axes[3].drive.steps.value == 80);
}

TEST_CASE("model: rrflint model prints the new facts, text and JSON", "[model]") {
  auto r = config("M584 X0.0 Y0.1 E0.1\nM350 X32 I1\nM671 X0:1 Y0:1\nM669 K1\n" + kBed +
                  "M140 H0\nM301 H0 P10 I1 D2\nM950 J0 C\"io0.in\"\nM581 T2 P0\nM591 D0 P1 C\"e0stop\"\n");
  std::ostringstream text;
  render_model_text(text, r->sources, r->result, "m");
  for (const char* part : {"Drivers", "SHARED", "rescaled sys/config.g:2", "Heater monitors (M143)", "P10 I1 D2",
                           "J0    GPIO in", "sys/trigger2.g", "\"e0stop\"", "DROPPED by the kinematics change"})
    CHECK(text.str().find(part) != std::string::npos);
  std::ostringstream js;
  render_model_json(js, r->sources, r->result, "m");
  const auto j = nlohmann::json::parse(js.str());
  CHECK(j["axes"][0]["steps_per_mm"] == 160.0);
  CHECK(j["axes"][0]["letter"] == "X");  // the fields that were there stay
  CHECK(j["heaters"][0]["monitors"][0]["limit"] == 125.0);
  CHECK(j["heaters"][0]["limit"] == 125.0);
  CHECK(j["drivers"][1]["shared"] == true);
  CHECK(j["ports"][0]["used_at"][0] == "sys/config.g:10");  // the M581
  CHECK(j["kinematics"]["leadscrews"]["dropped_at"] == "sys/config.g:4");
  CHECK(j["filament_monitors"][0]["pin"] == "e0stop");
  CHECK(j["extruders"]["drives"][0]["steps_per_mm"] == 420.0);
}

TEST_CASE("model: M574 endstops per axis", "[model]") {
  auto r = config("M574 X1 S1 P\"xstop\"\nM574 Y2 P\"ystop\"\nM574 Y1\nM574 Z1 S2\n");
  const MachineState& s = r->end();
  CHECK(s.axes[0].endstop.pins == "xstop");
  CHECK(s.axes[1].endstop.position.value == 1);  // a switch without P keeps its pins
  CHECK(s.axes[1].endstop.pins == "ystop");
  CHECK(s.axes[2].endstop.type.value == 2);  // the Z probe
  CHECK(s.axes[2].endstop.pins.empty());
  CHECK(r->word(s.axes[1].endstop.set) == "M574 Y1");
  CHECK(config("M574 X1 P\"xstop\"\nM574 X0\n")->end().axes[0].endstop.pins.empty());
  CHECK(config("M574 X1 P{global.pin}\n")->end().axes[0].endstop.pins == "?");
  CHECK_FALSE(config("M574 X{move.axes[0].max} P\"x\"\n")->end().axes[0].endstop.position.known);
  CHECK(config(kUnknownIf + "  M574 X1 P\"x\"\nendif\n")->end().axes[0].endstop.maybe);
}

TEST_CASE("model: the pins devices hold", "[model]") {
  // Names as RRF looks them up: no case, '_', '-', flags or main-board prefix; '+' lists; "nil" is no pin.
  CHECK(pin_name("!^OUT_1").key == "0.out1");
  CHECK(pin_name("0.out-1").key == "0.out1");
  CHECK(pin_name("!121.temp0").key == "121.temp0");
  CHECK(pin_name("007.io0.in").key == "7.io0.in");
  CHECK(pin_name("nil").key.empty());
  auto r = config(
      "M308 S1 P\"temp1\" Y\"thermistor\"\nM950 H1 C\"out1\" T1\nM950 F0 C\"1.out2+out2.tach\"\n"
      "M574 X1 S1 P\"io0.in\"\nM558 P5 C\"^io1.in\" H5\nM591 D0 P1 C\"io2.in\"\nM950 J0 C\"io3.in\"\n");
  const MachineState& s = r->end();
  REQUIRE(s.pins.size() == 8);
  CHECK(s.pins.at("0.temp1").device.name() == "sensor 1");
  CHECK(s.pins.at("0.out1").device.name() == "heater 1");
  CHECK(s.pins.at("1.out2.tach").device.name() == "fan 0");  // on the first pin's board
  CHECK(s.pins.at("0.io0.in").device.name() == "the X endstop");
  CHECK(s.pins.at("0.io1.in").written == "^io1.in");
  CHECK(s.pins.at("0.io2.in").device.name() == "filament monitor 0");
  CHECK(r->word(s.pins.at("0.io3.in").at) == "M950 J0 C\"io3.in\"");
  // Given back: re-created elsewhere, deleted, another endstop type; a refused device takes no pin at all.
  CHECK(config("M950 H1 C\"out1\" T1\nM950 H1 C\"out2\" T1\n")->end().pins.count("0.out1") == 0);
  CHECK(config("M950 H1 C\"out1\" T1\nM950 H1 C\"nil\"\n")->end().pins.empty());
  CHECK(config("M574 X1 S1 P\"io0.in\"\nM574 X1 S3\n")->end().pins.empty());
  CHECK(config("M574 X1 S1 P\"io0.in\"\nM574 X1 S1\n")->end().pins.size() == 1);
  CHECK(config("M950 F0 C\"out1\"\nM950 F1 C\"out2+out1\"\n")->end().pins.count("0.out2") == 0);
  // Unknown: a device number from an expression; a holder inside an `if`; RRF 2 has no pin names.
  CHECK_FALSE(config("M950 F{global.n} C\"out1\"\n")->end().pins_known);
  CHECK(config(kUnknownIf + "  M950 F0 C\"out1\"\nendif\n")->end().pins.at("0.out1").maybe);
  // A pin a maybe-holder may hold is taken (maybe) by the next device; the first one giving its pins back later
  // does not free it.
  auto mh = config(kUnknownIf + "  M950 F0 C\"out1\"\nendif\nM950 F1 C\"out1\"\nM950 F0 C\"nil\"\n");
  CHECK(mh->end().pins.at("0.out1").device.name() == "fan 1");
  CHECK(mh->end().pins.at("0.out1").maybe);
  CHECK(config("M558 P5 C\"zprobe.in\"\n", Version(2, 5, 0))->end().pins.empty());
  // rrflint model shows them.
  std::ostringstream text;
  render_model_text(text, r->sources, r->result, "m");
  for (const char* part : {"\nPins\n", "0.io1.in", "Z probe 0", "\"^io1.in\"", "sys/config.g:5"})
    CHECK(text.str().find(part) != std::string::npos);
  std::ostringstream js;
  render_model_json(js, r->sources, r->result, "m");
  const auto j = nlohmann::json::parse(js.str());
  CHECK(j["pins"][0]["pin"] == "0.io0.in");  // by name
  CHECK(j["pins"][0]["device"] == "the X endstop");
  CHECK(j["pins_known"] == true);
}
