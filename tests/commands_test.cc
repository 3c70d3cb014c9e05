// lint/boot/commands: what RRF makes of a command (docs/firmware-behaviour.md: M563 tools, G10 forms, System files),
// decided once for the model and every rule. Where the answer depends on facts the model does not know, it is Unknown.
#include <memory>
#include <string>

#include <catch2/catch.hpp>

#include "lint/boot/commands.h"
#include "lint/boot/const_eval.h"
#include "lint/engine/linter.h"
#include "rules/registry.h"

using namespace rrflint;

namespace {

/// One parsed command line.
struct One {
  std::unique_ptr<SourceFile> source;
  ParsedFile pf;
  Command c() const { return pf.commands[0]; }
};

std::unique_ptr<One> cmd(std::string text) {
  auto o = std::make_unique<One>();
  o->source = std::make_unique<SourceFile>(0, "t.g", "/sys/t.g", std::move(text) + "\n");
  o->pf = parse(*o->source);
  return o;
}

/// The state after boot: X Y Z, plus U when asked.
MachineState axes(bool with_u = false) {
  MachineState s;
  s.firmware = kLatestVersion;
  for (char L : std::string(with_u ? "XYZU" : "XYZ")) {
    Axis a;
    a.letter = L;
    s.axes.push_back(a);
  }
  s.visible_axes = static_cast<int>(s.axes.size());
  return s;
}

G10Form form(const std::string& text, const MachineState* s, Version fw = kLatestVersion) {
  auto o = cmd(text);
  return g10_form(o->pf, o->c(), s, fw);
}

}  // namespace

TEST_CASE("commands: G10's form, on each form", "[commands]") {
  const MachineState s = axes();
  CHECK(form("G10 P0 X1 Y2 Z0", &s) == G10Form::Tool);
  CHECK(form("G10 L1 P0 X1", &s) == G10Form::Tool);
  CHECK(form("G10 P0 R150 S210", &s) == G10Form::Tool);
  CHECK(form("G10 S210", &s) == G10Form::Tool);
  CHECK(form("G10 X5", &s) == G10Form::Tool);  // a visible axis letter alone
  CHECK(form("G10 P0", &s) == G10Form::Report);
  CHECK(form("G10 L1 P3", &s) == G10Form::Report);
  CHECK(form("G10 L1", &s) == G10Form::Report);  // reports the current tool
  CHECK(form("G10 L2 P1 X0 Y0", &s) == G10Form::Workplace);
  CHECK(form("G10 L20 P1 X0", &s) == G10Form::Workplace);
  CHECK(form("G10", &s) == G10Form::Retraction);
  CHECK(form("G10 U5", &s) == G10Form::Retraction);  // U is no axis here
  CHECK(form("G10 L3 P1", &s) == G10Form::BadL);
  CHECK(form("G10 L{global.l} P0 X1", &s) == G10Form::Unknown);
  CHECK(is_tool_form(G10Form::Tool));
  CHECK(is_tool_form(G10Form::Report));
  CHECK_FALSE(is_tool_form(G10Form::Retraction));
}

TEST_CASE("commands: F counts towards the tool form on 3.3 and 3.4 only", "[commands]") {
  const MachineState s = axes();
  CHECK(form("G10 F1200", &s, Version(3, 4, 0, 0, 0)) == G10Form::Tool);
  CHECK(form("G10 F1200", &s, Version(3, 5, 0, 0, 0)) == G10Form::Retraction);
  CHECK(form("G10 F1200", &s, Version(3, 2, 0, 0, 0)) == G10Form::Retraction);
}

TEST_CASE("commands: a G10 whose axes or baseline are unknown has an unknown form", "[commands]") {
  MachineState unknown_axes = axes();
  unknown_axes.axes_known = false;
  CHECK(form("G10 X5", &unknown_axes) == G10Form::Unknown);
  CHECK(form("G10 U5", &unknown_axes) == G10Form::Unknown);
  CHECK(form("G10", &unknown_axes) == G10Form::Unknown);
  CHECK(form("G10 P0 X5", &unknown_axes) == G10Form::Tool);  // P decides without the axes

  MachineState baseline = axes();
  baseline.unknown_baseline = true;
  CHECK(form("G10 X5", &baseline) == G10Form::Unknown);
  CHECK(form("G10 U5", &baseline) == G10Form::Unknown);

  MachineState maybe_u = axes(true);
  maybe_u.axes[3].maybe = true;  // created inside an `if`
  CHECK(form("G10 U5", &maybe_u) == G10Form::Unknown);
  CHECK(form("G10 X1 U5", &maybe_u) == G10Form::Tool);

  // Without a state (file rules, look-ahead) only L, P, R and S decide.
  CHECK(form("G10 X5", nullptr) == G10Form::Unknown);
  CHECK(form("G10 P1 X5", nullptr) == G10Form::Tool);
}

TEST_CASE("commands: M563 defines a tool with any of S D H X Y Z F R", "[commands]") {
  for (const char* t : {"M563 P0 S\"a\"", "M563 P0 D0", "M563 P0 H1", "M563 P0 X3", "M563 P0 Y3", "M563 P0 Z3",
                        "M563 P0 F0", "M563 P0 R0"}) {
    auto o = cmd(t);
    CHECK(m563_defines(o->pf, o->c()));
  }
  auto report = cmd("M563 P0");
  CHECK_FALSE(m563_defines(report->pf, report->c()));
}

TEST_CASE("commands: the tool a command addresses", "[commands]") {
  MachineState s = axes();
  s.current_tool = 2;
  auto p = cmd("G10 P1 X0");
  CHECK(addressed_tool(p->pf, p->c(), s).number == 1);
  CHECK(addressed_tool(p->pf, p->c(), s).explicit_p);
  auto e = cmd("G10 P{global.t} X0");
  CHECK_FALSE(addressed_tool(e->pf, e->c(), s).known);
  auto current = cmd("G10 X0");
  CHECK(addressed_tool(current->pf, current->c(), s).number == 2);
  CHECK(addressed_tool(current->pf, current->c(), s).known);
  s.current_tool = -1;
  CHECK(addressed_tool(current->pf, current->c(), s).none());
  s.unknown_baseline = true;  // a lone macro: any tool may be selected
  CHECK_FALSE(addressed_tool(current->pf, current->c(), s).known);
  s.current_tool_set = 7;  // until a T in it selects one
  CHECK(addressed_tool(current->pf, current->c(), s).known);
}

TEST_CASE("commands: file roles by name", "[commands]") {
  int n = -5;
  CHECK(file_role("/sys/config.g") == FileRole::Config);
  CHECK(file_role("/sys/Config-Override.g") == FileRole::ConfigOverride);
  CHECK(file_role("/sys/tpost12.g", &n) == FileRole::ToolPost);
  CHECK(n == 12);
  CHECK(file_role("/sys/tpre.g", &n) == FileRole::ToolPre);
  CHECK(n == -1);
  CHECK(file_role("/sys/tfree0.g", &n) == FileRole::ToolFree);
  CHECK(n == 0);
  CHECK(file_role("/sys/tpostx.g") == FileRole::Other);
  CHECK(file_role("/sys/homeall.g") == FileRole::Homing);
  CHECK(file_role("/sys/homex.g") == FileRole::Homing);
  CHECK(file_role("/sys/homedelta.g") == FileRole::Homing);
  CHECK(file_role("/sys/homing.g") == FileRole::Other);
  CHECK(file_role("/sys/resurrect.g") == FileRole::Resurrect);
  CHECK(file_role("/sys/resurrect-prologue.g") == FileRole::ResurrectPrologue);
  CHECK(file_role("/sys/daemon.g") == FileRole::Daemon);
  CHECK(file_role("/sys/runonce.g") == FileRole::RunOnce);
  CHECK(file_role("/macros/print.g") == FileRole::Other);
  CHECK(is_tool_change_role(FileRole::ToolFree));
  CHECK_FALSE(is_tool_change_role(FileRole::Homing));
}

TEST_CASE("commands: an M563 axis map is the given indices ANDed with the visible axes", "[commands]") {
  MachineState s = axes(true);
  s.visible_axes = 3;  // U hidden (M584 P3)
  auto o = cmd("M563 P0 D0 X0:3 Y{global.y}");
  const M563Map x = m563_map(o->pf, o->c(), s, 'X');
  CHECK(x.given);
  CHECK(x.known);
  CHECK(x.bits == 1u);  // index 3 is not visible
  CHECK(x.indices.size() == 2);
  const M563Map y = m563_map(o->pf, o->c(), s, 'Y');
  CHECK_FALSE(y.known);
  const M563Map z = m563_map(o->pf, o->c(), s, 'Z');
  CHECK_FALSE(z.given);
  CHECK(z.bits == 4u);  // the default: Z -> Z
  CHECK_FALSE(has_z_map(Version(3, 4, 0, 0, 0)));
  CHECK(has_z_map(Version(3, 5, 0, 0, 0)));
}

TEST_CASE("commands: M585 probes the first visible axis it names", "[commands]") {
  MachineState s = axes(true);
  s.visible_axes = 3;
  auto u = cmd("M585 U0 Y5 X3");
  CHECK(m585_axis(u->pf, u->c(), s) == 0);  // X: creation order, not parameter order; U is hidden
  auto none = cmd("M585 U0 S1");
  CHECK(m585_axis(none->pf, none->c(), s) == -1);
}

TEST_CASE("const_eval: values known at boot", "[commands]") {
  std::map<std::string, ConstValue> globals{{"dir", ConstValue::string("0:/macros/")},
                                            {"on", ConstValue::boolean(true)}};
  const ConstEnv env{"0:/sys/", &globals, nullptr};
  auto str = [&](std::string_view e) {
    const ConstValue v = const_eval(e, env);
    return v.kind == ConstValue::Kind::String ? v.str : std::string("?");
  };
  CHECK(str("directories.system^\"/tool_params.g\"") == "0:/sys//tool_params.g");
  CHECK(str("global.dir ^ \"park.g\"") == "0:/macros/park.g");
  CHECK(str("\"a\"\"b\"") == "a\"b");
  CHECK(str("(\"a\" ^ \"b\") ^ \"c\"") == "abc");
  auto truth = [&](std::string_view e) {
    const ConstValue v = const_eval(e, env);
    return v.kind == ConstValue::Kind::Bool ? (v.b ? 1 : 0) : -1;
  };
  CHECK(truth("directories.system == \"0:/sys/\"") == 1);
  CHECK(truth("global.on && !false") == 1);
  CHECK(truth("1 != 1 || global.on") == 1);
  CHECK(truth("\"a\" == 1") == -1);  // different kinds: not a constant here
  // Unknown: other names, object model fields, functions, arrays, other operators.
  CHECK(str("global.missing ^ \"x\"") == "?");
  CHECK(str("move.axes[0].letter") == "?");
  CHECK(str("exists(global.dir)") == "?");
  CHECK(truth("1 < 2") == -1);
  CHECK(str("\"unterminated") == "?");
  CHECK(str("var.x") == "?");
}
