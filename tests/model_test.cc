// The machine model after boot (docs/firmware-behaviour.md, "Axes and M584" to "Board limits") and firmware inference.
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <catch2/catch.hpp>

#include "lint/engine/linter.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

struct Run {
  SourceManager sources;
  MemoryReader reader;
  MachineResult result;
  const MachineState& end() const { return result.end_of_boot; }
  const Tool& tool(int n) const { return result.end_of_boot.tools.at(n); }
  /// The word of the command a node runs ("M563"), for origins.
  std::string word(NodeId id) const {
    if (id == kNoNode) return "default";
    const Node& n = result.graph.nodes[id];
    const FileUnit& u = result.machine->unit(n.unit);
    return std::string(u.parsed.text(u.parsed.commands[n.index].span));
  }
};

std::unique_ptr<Run> boot(const std::map<std::string, std::string>& files, std::optional<Version> fw = kLatestVersion,
                          std::optional<Board> board = std::nullopt) {
  auto r = std::make_unique<Run>();
  for (const auto& [path, text] : files) r->reader.add(path, text);
  LintOptions o;
  o.firmware = fw;
  o.board = board;
  o.select = {"syntax-error"};
  r->result = lint_machine(r->sources, r->reader, builtin_rules(), o);
  return r;
}

std::unique_ptr<Run> config(std::string text, std::optional<Version> fw = kLatestVersion,
                            std::optional<Board> board = std::nullopt) {
  return boot({{"/sys/config.g", std::move(text)}}, fw, board);
}

std::string letters(const MachineState& s) {
  std::string out;
  for (const Axis& a : s.axes) out += a.letter;
  return out;
}

}  // namespace

TEST_CASE("model: axes are created in RRF's letter order, not parameter order", "[model]") {
  auto one = config("M584 X0.0 Y0.1 Z0.2 C0.5 U0.6\n");
  CHECK(letters(one->end()) == "XYZUC");
  CHECK(one->end().visible_axes == 5);
  CHECK(one->end().axis_index('C') == 4);
  CHECK(one->word(one->end().axes[3].created) == "M584 X0.0 Y0.1 Z0.2 C0.5 U0.6");
  CHECK(one->end().axes[4].rotational);
  CHECK_FALSE(one->end().axes[3].rotational);
  CHECK(one->end().axes[0].created == kNoNode);  // X, Y, Z exist from power-on
  CHECK(one->end().axes[0].drivers == std::vector<DriverId>{{0, 0}});

  auto two = config("M584 C5\nM584 U6\n");
  CHECK(letters(two->end()) == "XYZCU");
  CHECK(two->end().axis_index('U') == 4);

  // Lowercase letters from 3.3; none before.
  CHECK(letters(config("M584 'a7 'b8\n")->end()) == "XYZab");
  CHECK(letters(config("M584 'a7\n", Version(3, 2, 2))->end()) == "XYZ");
  // Letters beyond the board's MaxAxes are not created.
  auto duet2 = config("M584 U3 V4 W5 A6 B7 C8 D9 'a10\n", Version(3, 5, 0), Board::Duet2);
  CHECK(letters(duet2->end()) == "XYZUVWABCD");
  CHECK(duet2->end().failed_axes.count('a'));
}

TEST_CASE("model: M584 P hides the last axes until another axis is created", "[model]") {
  auto r = config("M584 X0 Y1 Z2 U3 V4 P3\n");
  CHECK(r->end().axes.size() == 5);
  CHECK(r->end().visible_axes == 3);
  CHECK_FALSE(r->end().axis_visible(3));
  CHECK(r->end().axes_known);
  auto later = config("M584 X0 Y1 Z2 U3 P3\nM584 W5\n");
  CHECK(later->end().visible_axes == 5);
  auto unknown = config("M584 X0 Y1 Z2 U3 P{global.p}\n");
  CHECK_FALSE(unknown->end().axes_known);
}

TEST_CASE("model: extruders come from M584 E", "[model]") {
  CHECK(config("M584 E0.3:0.4\n")->end().extruders == 2);
  CHECK(config("M83\n")->end().extruders == 0);                    // none by default from 3.3
  CHECK(config("M83\n", Version(3, 2, 2))->end().extruders == 1);  // one by default in 3.0-3.2
  CHECK_FALSE(config("M584 E{global.e}\n")->end().extruders_known);
  CHECK_FALSE(config("if move.axes[0].homed\n  M584 E0.3\n")->end().extruders_known);
  // An E swallowed as an exponent creates no extruder.
  CHECK(config("M584 X0 Y1 Z2E3\n")->end().extruders == 0);
}

TEST_CASE("model: M563 axis maps are axis indices ANDed with the visible axes", "[model]") {
  auto r = config(
      "M584 X0 Y1 Z2 U3\n"
      "M563 P0 S\"left\" X0:3\n"
      "M563 P1 S\"right\" X3\n"
      "M584 V4 P4\n"
      "M563 P2 S\"hidden\" X0:4\n"
      "M563 P3 S\"plain\"\n");
  CHECK(r->tool(0).xmap.bits == 0b1001);
  CHECK(r->end().axis_letters(r->tool(0).xmap.bits) == "X+U");
  CHECK(r->tool(1).xmap.bits == 0b1000);
  CHECK(r->word(r->tool(1).xmap.origin) == "M563 P1 S\"right\" X3");
  CHECK(r->tool(2).xmap.bits == 0b0001);  // V (index 4) is hidden by P4
  CHECK(r->tool(3).xmap.bits == 0b0001);  // defaults: X->X, Y->Y, Z->Z
  CHECK(r->tool(3).ymap.bits == 0b0010);
  CHECK(r->tool(3).zmap.bits == 0b0100);
  CHECK(r->tool(3).xmap.origin == kNoNode);

  // Before U exists, index 3 is dropped: an empty X map.
  auto early = config("M563 P1 S\"right\" X3\nM584 U3\n");
  CHECK(early->tool(1).xmap.bits == 0);
  CHECK(early->tool(1).xmap.known);
  // `M584 C5` then `M584 U6`: index 3 is C.
  auto order = config("M584 C5\nM584 U6\nM563 P1 S\"t\" X3\n");
  CHECK(order->end().axis_letters(order->tool(1).xmap.bits) == "C");
  auto expr = config("M584 U3\nM563 P1 S\"t\" X{global.map}\n");
  CHECK_FALSE(expr->tool(1).xmap.known);
}

TEST_CASE("model: an overlapping map fails before the old tool is deleted", "[model]") {
  auto r = config("M563 P0 S\"old\"\nM563 P0 S\"new\" X1\n");  // X->Y overlaps the default Y->Y
  CHECK(r->tool(0).name == "old");
  auto swap = config("M563 P0 S\"old\"\nM563 P0 S\"swapped\" X1 Y0\n");
  CHECK(swap->tool(0).name == "swapped");
  // The Z map exists from 3.5; before, Z in M563 is ignored.
  CHECK(config("M563 P0 S\"old\"\nM563 P0 S\"new\" Z0\n")->tool(0).name == "old");
  CHECK(config("M563 P0 S\"old\"\nM563 P0 S\"new\" Z0\n", Version(3, 4, 6))->tool(0).name == "new");
  // Too many entries for the visible axes: an exception, the old tool survives.
  CHECK(config("M563 P0 S\"old\"\nM563 P0 S\"new\" X0:1:2:0\n")->tool(0).name == "old");
}

TEST_CASE("model: M563 D without an extruder deletes the old tool and creates none", "[model]") {
  auto r = config("M563 P0 S\"old\"\nM563 P0 S\"new\" D0 H1\n");
  CHECK(r->end().tools.count(0) == 0);
  REQUIRE(r->end().failed_tools.count(0));
  CHECK(r->word(r->end().failed_tools.at(0)) == "M563 P0 S\"new\" D0 H1");
  // 3.0-3.2 have one extruder by default; with M584 E the drive exists.
  CHECK(config("M563 P0 S\"t\" D0 H1\n", Version(3, 2, 2))->end().tools.count(0) == 1);
  CHECK(config("M584 E0.3\nM563 P0 S\"t\" D0 H1\n")->end().tools.count(0) == 1);
  CHECK(config("M584 E0.3\nM563 P0 S\"t\" D1 H1\n")->end().failed_tools.count(0) == 1);
  // A negative heater also fails (unless D-1 H-1, which deletes the tool).
  CHECK(config("M563 P0 S\"t\" H-1\n")->end().failed_tools.count(0) == 1);
  CHECK(config("M563 P0 S\"t\"\nM563 P0 D-1 H-1\n")->end().tools.empty());
  CHECK(config("M563 P0 S\"t\"\nM563 P0 D-1 H-1\n")->end().failed_tools.empty());
  // A later good definition clears the failure.
  CHECK(config("M563 P0 D0\nM584 E0.3\nM563 P0 D0\n")->end().failed_tools.empty());
  // `M563 P0` alone only reports; P out of range creates nothing.
  CHECK(config("M563 P0\n")->end().tools.empty());
  CHECK(config("M563 P50 S\"t\"\n")->end().tools.empty());
}

TEST_CASE("model: redefining a tool resets its offsets and deselects it", "[model]") {
  auto r = config("M563 P0 S\"a\"\nG10 P0 X5 Y6\nT0 P0\nM563 P0 S\"b\"\n");
  const Tool& t = r->tool(0);
  CHECK(t.name == "b");
  CHECK(t.offsets[0].value == 0);
  CHECK(t.offsets[0].origin == kNoNode);
  CHECK(t.offsets[1].known);
  CHECK(r->end().current_tool == -1);
  CHECK(r->word(t.created) == "M563 P0 S\"b\"");
  auto before = config("M563 P0 S\"a\"\nG10 P0 X5 Y6\n");
  CHECK(before->tool(0).offsets[0].value == 5);
  CHECK(before->tool(0).offsets[1].value == 6);
  CHECK(before->word(before->tool(0).offsets[1].origin) == "G10 P0 X5 Y6");
  CHECK(before->word(before->tool(0).last_configured) == "G10 P0 X5 Y6");
}

TEST_CASE("model: G10 sets offsets per physical axis, visible axes only", "[model]") {
  auto r = config("M584 X0 Y1 Z2 U3\nM563 P1 S\"r\" X3\nG10 P1 U7 X1 Z-0.5\n");
  const Tool& t = r->tool(1);
  CHECK(t.offsets[3].value == 7);
  CHECK(t.offsets[0].value == 1);
  CHECK(t.offsets[2].value == -0.5);
  CHECK(t.offsets[1].origin == kNoNode);  // Y not named: unchanged
  // A hidden axis is not visible to G10.
  auto hidden = config("M584 X0 Y1 Z2 U3 P3\nM563 P1 S\"r\"\nG10 P1 U7\n");
  CHECK(hidden->tool(1).offsets[3].origin == kNoNode);
  // G10 for a tool that does not exist sets nothing; without P it uses the current tool.
  auto current = config("M563 P2 S\"c\"\nT2 P0\nG10 X3\n");
  CHECK(current->tool(2).offsets[0].value == 3);
  CHECK(config("G10 P4 X3\n")->end().tools.empty());
}

TEST_CASE("model: expressions and if-branches make facts unknown", "[model]") {
  auto r = config(
      "M563 P0 S\"a\"\n"
      "G10 P0 X{global.x} Y2\n"
      "if exists(global.z)\n"
      "  G10 P0 Z3\n"
      "  M563 P1 S\"maybe\"\n");
  CHECK_FALSE(r->tool(0).offsets[0].known);
  CHECK(r->tool(0).offsets[1].known);
  CHECK_FALSE(r->tool(0).offsets[2].known);
  CHECK(r->word(r->tool(0).offsets[2].origin) == "G10 P0 Z3");
  CHECK(r->tool(1).maybe);
  CHECK_FALSE(r->tool(0).maybe);

  // A tool number from a macro parameter: any tool may exist afterwards.
  auto p = boot({{"/sys/config.g", "M98 P\"mk.g\" T3\n"}, {"/sys/mk.g", "M563 P{param.T} S\"t\"\n"}});
  CHECK_FALSE(p->end().tools_known);
  CHECK_FALSE(p->end().tool_certainly_absent(3));
  // A macro whose name is an expression may do anything.
  auto m = config("M98 P{move.axes[0].letter ^ \".g\"}\n");
  CHECK_FALSE(m->end().tools_known);
  CHECK_FALSE(m->end().axes_known);
  // A T{expr} leaves the current tool unknown.
  auto t = config("M563 P0 S\"a\"\nT{0} P0\n");
  CHECK_FALSE(t->end().current_tool_known);
}

TEST_CASE("model: T selects, T-1 deselects, a missing tool selects none", "[model]") {
  auto r = config("M563 P0 S\"a\"\nM563 P1 S\"b\"\nT1 P0\n");
  CHECK(r->end().current_tool == 1);
  CHECK(r->end().current_tool_known);
  auto d = config("M563 P0 S\"a\"\nT0 P0\nT-1 P0\n");
  CHECK(d->end().current_tool == -1);
  CHECK(d->end().current_tool_known);
  auto none = config("M563 P0 S\"a\"\nT0 P0\nT5 P0\n");
  CHECK(none->end().current_tool == -1);
  CHECK(none->end().current_tool_known);
  auto maybe = config("M563 P0 S\"a\"\nif move.axes[0].homed\n  T0\n");
  CHECK_FALSE(maybe->end().current_tool_known);
}

TEST_CASE("model: M501 flags the offsets it loads as probed", "[model]") {
  auto r = boot({
      {"/sys/config.g", "M563 P0 S\"a\"\nM501\nG10 P0 Y9\n"},
      {"/sys/config-override.g", "G10 P0 X1.5 Y0.5 Z-0.2\n"},
  });
  const Tool& t = r->tool(0);
  CHECK(t.probed[0]);
  CHECK(t.probed[2]);
  CHECK_FALSE(t.probed[1]);  // set again after M501 by config.g
  CHECK(t.offsets[0].value == 1.5);
  CHECK(t.offsets[1].value == 9);
  CHECK(r->word(r->end().m501) == "M501");
  CHECK_FALSE(r->end().running_m501);
  // Loading the file with M98 does not flag anything.
  auto m98 = boot({
      {"/sys/config.g", "M563 P0 S\"a\"\nM98 P\"config-override.g\"\n"},
      {"/sys/config-override.g", "G10 P0 X1.5\n"},
  });
  CHECK_FALSE(m98->tool(0).probed[0]);
  CHECK(m98->end().m501 == kNoNode);
}

TEST_CASE("model: tool heaters get a monitor only if they exist when M563 names them", "[model]") {
  const std::string heater = "M308 S1 P\"temp1\" Y\"thermistor\"\nM950 H1 C\"out1\" T1\n";
  auto after = config(heater + "M563 P0 S\"t\" H1\n");
  const Heater& h = after->end().heaters.at(1);
  CHECK(h.monitor_installed);
  CHECK(h.limit == 285);
  CHECK(after->word(h.monitor_origin) == "M563 P0 S\"t\" H1");
  CHECK(after->end().sensors.at(1).type == "thermistor");
  CHECK(after->end().heaters.at(1).sensor == 1);

  auto before = config("M563 P0 S\"t\" H1\n" + heater);
  CHECK_FALSE(before->end().heaters.at(1).monitor_installed);
  CHECK(before->end().heaters.at(1).limit == 2000);

  // 3.0 used 290 °C; the bed gets 125 °C from M140; a user M143 wins.
  CHECK(config(heater + "M563 P0 S\"t\" H1\n", Version(3, 0, 0))->end().heaters.at(1).limit == 290);
  auto bed = config("M308 S0 P\"temp0\" Y\"thermistor\"\nM950 H0 C\"out0\" T0\nM140 H0\n");
  CHECK(bed->end().heaters.at(0).limit == 125);
  CHECK(bed->end().bed_heater == 0);
  auto user = config(heater + "M143 H1 S300\nM563 P0 S\"t\" H1\n");
  CHECK(user->end().heaters.at(1).user_monitor);
  CHECK(user->end().heaters.at(1).limit == 300);
  // M950 with pin "nil" removes the heater.
  CHECK(config(heater + "M950 H1 C\"nil\"\n")->end().heaters.count(1) == 0);
}

TEST_CASE("model: fans, probes and machine mode", "[model]") {
  auto r = config(
      "M950 F2 C\"out4\"\nM558 P8 C\"io3.in\" H5 F120\nM558 K1 P5 C\"io4.in\"\nM558 K3 C\"io5.in\"\nM453\nM669 K1\n");
  CHECK(r->end().fans.count(2) == 1);
  CHECK(r->end().probes.at(0).type == 8);
  CHECK(r->end().probes.at(1).type == 5);
  CHECK(r->end().probes.count(3) == 0);  // C without P: "Missing Z probe type number"
  CHECK(r->end().mode == MachineMode::CNC);
  CHECK(r->end().kinematics == 1);
}

TEST_CASE("model: kinematics type from M669 K, M667 S (up to 3.4) and M665 L/D", "[model]") {
  CHECK(config("M669 K1\nM667 S2\n", Version(3, 4, 6))->end().kinematics == 2);
  CHECK(config("M669 K1\nM667 S2\n", Version(3, 5, 0))->end().kinematics == 1);  // M667 is no longer supported
  CHECK(config("M669 K1\nM669 S40\nM665 R100\n")->end().kinematics == 1);        // no K, no L/D: no change
  CHECK(config("M665 L360 R180 H400\n")->end().kinematics == 3);
  CHECK(!config("M669 K{global.k}\n")->end().kinematics_known);
  CHECK(!config("if exists(global.k)\n  M669 K1\n")->end().kinematics_known);
}

// Firmware inference (issue: core §4): the newest version consistent with the evidence.
TEST_CASE("infer: the version comes from the header, the syntax, or the newest release", "[model][infer]") {
  auto target = [](std::string text) { return config(std::move(text), std::nullopt)->result.target; };
  CHECK(target("; Configuration file for Duet 3 (firmware version 3.4)\nM83\n").version == Version(3, 4, 6));
  CHECK(target("; generated by RepRapFirmware Configuration Tool v3.3.16\nM83\n").version == Version(3, 3, 0));
  CHECK(target("M305 P0 T100000\n").version == Version(2, 5, 1));
  CHECK(target("M308 S0 P\"temp0\" Y\"thermistor\"\n").version == kLatestVersion);
  CHECK(target("var x = 1\n").version == kLatestVersion);
  CHECK(target("M83\n").version == kLatestVersion);
  // A mistake a rule reports is not evidence: E values with no M584 E are RRF202's finding on 3.3+, not a sign
  // of 3.2 or older.
  Target e = target("M92 X80 Y80 Z400 E420\n");
  CHECK(e.version == kLatestVersion);
  CHECK(e.source == Target::Source::Newest);
  CHECK(target("M563 P0 D0 F0\nvar x = 1\n").version == kLatestVersion);
  // Era hints: the Configuration Tool's version names the series, RRF 2 idioms name RRF 2.
  Target tool = target(
      "; Configuration file (firmware version 3)\n; generated by RepRapFirmware Configuration "
      "Tool v3.1.4 on Sat Jan 01\nM83\n");
  CHECK(tool.version == Version(3, 1, 1));
  CHECK(tool.source == Target::Source::Hint);
  CHECK(tool.floor == Version(3, 0, 0));
  CHECK(target("; generated by RepRapFirmware Configuration Tool v2.1.8\nM83\n").version == Version(2, 5, 1));
  CHECK(target("; firmware version 2\nM83\n").version == Version(2, 5, 1));
  Target rrf2 = target("M307 H0 A90 C700 D10\nM143 H1 S280\nM563 P0 D0 H1\n");
  CHECK(rrf2.version == Version(2, 5, 1));
  CHECK(rrf2.reason.find("no M950 creates one") != std::string::npos);
  CHECK(target("M950 H1 C\"out1\" T1\nM143 H1 S280\n").version == kLatestVersion);
  CHECK(target("M563 P0 D0 H1\n").version == kLatestVersion);
  // A hint that a floor above its series contradicts is stale: the newest release, with both named.
  Target both = target("M305 P0 T100000\nvar x = 1\n");
  CHECK(both.version == kLatestVersion);
  CHECK(both.floor == Version(3, 3, 0));
  CHECK(both.reason.find("but 'var' variables need RRF 3.3") != std::string::npos);
  Target stale = target("; firmware version 1.21\nM308 S0 P\"temp0\" Y\"thermistor\"\n");
  CHECK(stale.version == kLatestVersion);
  CHECK(stale.reason.find("header states version 1.21, but M308") != std::string::npos);
  // Codes in the files the firmware writes are floors; a user's file may hold a typo (M596 for M569).
  auto written =
      boot({{"/sys/config.g", "; firmware version 3.2\nM83\n"}, {"/sys/resurrect.g", "M596 P0\n"}}, std::nullopt);
  CHECK(written->result.target.version == kLatestVersion);
  CHECK(written->result.target.floor == kRrf3_5);
  CHECK(target("; firmware version 3.2\nM596 P0.2 S0\n").version == Version(3, 2, 2));
  // A header consistent with the syntax wins over "newest".
  CHECK(target("; firmware version 3.4\nvar x = 1\n").version == Version(3, 4, 6));
  CHECK(target("; firmware version 3.4\nglobal a = {1, 2}\n").version == kLatestVersion);
  // A header above the newest known release (found by the fuzzer: a null dereference) gives the newest.
  CHECK(target("; firmware version 4\nM83\n").version == kLatestVersion);
  CHECK(target("; firmware version 4\nM92 E420\n").version == kLatestVersion);
  // Hazards: at the target, at another version the files allow (floor to newest), or nowhere.
  auto before_3_6 = [](Version v) { return v < Version::first_of(3, 6); };
  CHECK(hazard_at(target("M83\n"), before_3_6) == HazardAt::Possible);
  CHECK(hazard_at(target("; firmware version 3.4\nM83\n"), before_3_6) == HazardAt::Target);
  CHECK(hazard_at(target("global a = {1, 2}\nM83\n"), before_3_6) == HazardAt::Possible);
  CHECK(hazard_at(target("global a = {1, 2}\nM83\n"), [](Version v) { return v < kRrf3_5; }) == HazardAt::Nowhere);
  CHECK(hazard_at(config("M83\n", Version(3, 6, 0))->result.target, before_3_6) == HazardAt::Nowhere);
  // Evidence is collected from every file, not only config.g.
  auto macro = boot({{"/sys/config.g", "M83\n"}, {"/macros/m.g", "var v = {1, 2}\n"}}, std::nullopt);
  CHECK(macro->result.target.version == kLatestVersion);
  bool floor35 = false;
  for (const Evidence& ev : macro->result.target.evidence)
    floor35 = floor35 || (ev.kind == Evidence::Kind::Floor && ev.version == kRrf3_5);
  CHECK(floor35);
}

TEST_CASE("infer: a given version and board win", "[model][infer]") {
  auto r = config("; Configuration file for Duet WiFi (firmware version 2.05)\nM305 P0\n", Version(3, 5, 1),
                  Board::Duet3_6HC);
  CHECK(r->result.target.version == Version(3, 5, 1));
  CHECK(r->result.target.version_given);
  CHECK(r->result.target.board == Board::Duet3_6HC);
  auto header = config("; Configuration file for Duet 3 MB 6HC (firmware version 3.5)\nM83\n", std::nullopt);
  CHECK(header->result.target.board == Board::Duet3_6HC);
  CHECK(header->result.target.version == Version(3, 5, 4));
  CHECK(config("; Duet 2 WiFi\nM83\n", std::nullopt)->result.target.board == Board::Duet2);
}

TEST_CASE("model: a G10 whose form is unknown sets nothing certain, and no rule fires on it", "[model][commands]") {
  // After a macro whose name is an expression the axes are unknown: 'G10 X1' may set a tool offset, or X may be
  // hidden and it is a retraction.
  auto r = config(
      "M563 P0 S\"a\"\n"
      "T0 P0\n"
      "M98 P{move.axes[0].letter ^ \".g\"}\n"
      "G10 X1 Z0\n"
      "G10 L{global.l} Z2\n");
  CHECK_FALSE(r->end().axes_known);
  const Tool& t = r->tool(0);
  CHECK_FALSE(t.offsets[0].known);  // it may have set X
  CHECK_FALSE(t.offsets[2].known);
  CHECK(r->word(t.offsets[2].origin) == "G10 L{global.l} Z2");

  // The same lines lint silently: no G10 rule fires on a G10 of unknown form.
  SourceManager sources;
  MemoryReader reader;
  reader.add("/sys/config.g", "M563 P0 S\"a\"\nT0 P0\nM98 P{move.axes[0].letter ^ \".g\"}\nG10 X1 U3\nG10 U3\n");
  LintOptions o;
  o.select = {"ALL"};
  const MachineResult res = lint_machine(sources, reader, builtin_rules(), o);
  for (const Diagnostic& d : res.diagnostics) {
    INFO(d.message);
    CHECK(std::string(d.name).rfind("g10-", 0) != 0);
  }
}

TEST_CASE("model: an M98 whose path is known at boot is followed, and what it creates is known", "[model]") {
  auto r = boot({{"/sys/config.g", "M584 X0 Y1 Z2 E3\nM98 P{directories.system^\"/tools.g\"}\n"},
                 {"/sys/tools.g", "M563 P0 D0\n"}});
  CHECK(r->end().tools_known);
  CHECK(r->end().tools.count(0) == 1);
  // An object model value is not known at boot: anything may exist afterwards.
  auto u = boot({{"/sys/config.g", "M584 X0 Y1 Z2 E3\nM98 P{move.axes[0].letter^\".g\"}\n"}});
  CHECK_FALSE(u->end().tools_known);
}
