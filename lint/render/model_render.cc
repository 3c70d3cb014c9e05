// `rrflint model`: the machine model the boot sequence builds, as aligned tables or JSON.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "lint/engine/linter.h"
#include "lint/render/model_render.h"
#include "lint/render/model_tables.h"
#include "lint/render/render.h"

namespace rrflint {
namespace {

using namespace model_text;

std::string ints(const std::vector<int64_t>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ":" : "") + std::to_string(v[i]);
  return s.empty() ? "-" : s;
}

std::string temps(const std::vector<double>& v) {
  if (v.empty()) return "off";
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ":" : "") + num(v[i]);
  return s;
}

std::string map_str(const MachineState& s, const AxisMap& m) { return m.known ? s.axis_letters(m.bits) : "unknown"; }

std::string axis_name(const Axis& a) {
  return a.letter >= 'a' ? fmt::format("'{}", a.letter) : std::string(1, a.letter);
}

// The target, its evidence and the board.
void render_target(std::ostream& os, const SourceManager& sm, const MachineResult& r) {
  os << "Firmware: " << r.target.reason << "\n";
  for (const Evidence& e : r.target.evidence) {
    LineCol lc = sm.get(e.loc.file).position(e.loc.span.begin);
    os << fmt::format("  evidence: {} ({}:{})\n", e.what, sanitize(sm.get(e.loc.file).display_path()), lc.line);
  }
  os << "Board: " << r.target.board_reason << "\n";
  if (!r.has_boot) os << "No config.g: the model below is the power-on state.\n";
}

// The axes and the extruders.
void render_axes(std::ostream& os, const SourceManager& sm, const MachineResult& r, const MachineState& s) {
  os << fmt::format("\nAxes ({} total, {} visible){}\n", s.axes.size(), s.visible_axes,
                    s.axes_known ? "" : " (partly unknown)");
  std::vector<std::vector<std::string>> rows{{"index", "axis", "drivers", "kind", "visible", "set at"}};
  for (size_t i = 0; i < s.axes.size(); ++i) {
    const Axis& a = s.axes[i];
    std::string drv;
    for (const auto& d : a.drivers) drv += (drv.empty() ? "" : ":") + d.str();
    rows.push_back({std::to_string(i), axis_name(a), drv.empty() ? "unknown" : drv,
                    a.rotational ? "rotational" : "linear", static_cast<int>(i) < s.visible_axes ? "yes" : "hidden",
                    where(r, sm, a.drivers_set != kNoNode ? a.drivers_set : a.created) + (a.maybe ? " (maybe)" : "")});
  }
  table(os, rows);
  os << fmt::format("\nExtruders: {}", s.extruders_known ? std::to_string(s.extruders) : "unknown");
  if (!s.extruder_drivers.empty()) {
    std::string drv;
    for (size_t i = 0; i < s.extruder_drivers.size(); ++i)
      drv += fmt::format("{}E{}={}", i ? " " : "", i, s.extruder_drivers[i].str());
    os << " (" << drv << ", " << where(r, sm, s.extruders_set) << ")";
  }
  os << "\n";
}

// Sensors, heaters, fans and probes.
void render_devices(std::ostream& os, const SourceManager& sm, const MachineResult& r, const MachineState& s) {
  os << "\nSensors\n";
  std::vector<std::vector<std::string>> rows = {{"sensor", "type", "created at"}};
  for (const auto& [n, sn] : s.sensors)
    rows.push_back({std::to_string(n), sn.type, where(r, sm, sn.created) + (sn.maybe ? " (maybe)" : "")});
  if (rows.size() > 1) table(os, rows);
  else os << "  none\n";
  os << "\nHeaters\n";
  rows = {{"heater", "sensor", "over-temperature monitor", "model", "created at"}};
  for (const auto& [n, h] : s.heaters) {
    std::string mon = h.monitor_installed
                          ? fmt::format("{} °C ({}, {})", num(h.limit), h.user_monitor ? "M143" : "default",
                                        where(r, sm, h.monitor_origin))
                          : "NONE (limit 2000 °C)";
    rows.push_back({std::to_string(n) + (n == s.bed_heater ? " (bed)" : ""),
                    h.sensor >= 0 ? std::to_string(h.sensor) : "-", mon, h.model_set ? "M307" : "default",
                    where(r, sm, h.created) + (h.maybe ? " (maybe)" : "")});
  }
  if (rows.size() > 1) table(os, rows);
  else os << "  none\n";
  os << "\nFans\n";
  rows = {{"fan", "thermostatic", "created at"}};
  for (const auto& [n, f] : s.fans) {
    std::string th = !f.thermostat_known ? "unknown" : f.thermostatic ? "sensors " + ints(f.sensors) : "no";
    if (f.thermostat_known && f.thermostatic) th += " at " + temps(f.thresholds) + " °C";
    if (f.thermostat_set != kNoNode) th += " (" + where(r, sm, f.thermostat_set) + ")";
    rows.push_back({std::to_string(n), th, where(r, sm, f.created) + (f.maybe ? " (maybe)" : "")});
  }
  if (rows.size() > 1) table(os, rows);
  else os << "  none\n";
  os << "\nProbes\n";
  rows = {{"probe", "type", "trigger height", "offsets", "created at"}};
  for (const auto& [n, p] : s.probes)
    rows.push_back({std::to_string(n), std::to_string(p.type),
                    fact(p.trigger_height) + (p.g31 != kNoNode ? " (" + where(r, sm, p.g31) + ")" : " (default)"),
                    "X" + fact(p.x_offset) + " Y" + fact(p.y_offset), where(r, sm, p.created)});
  if (rows.size() > 1) table(os, rows);
  else os << "  none\n";
}

// The tools, those whose M563 failed, and the current tool.
void render_tools(std::ostream& os, const SourceManager& sm, const MachineResult& r, const MachineState& s) {
  os << fmt::format("\nTools{}\n", s.tools_known ? "" : " (some created with unknown numbers)");
  std::vector<std::vector<std::string>> rows = {
      {"tool", "name", "D", "H", "F", "X/Y/Z map", "offsets", "active/standby", "created at"}};
  for (const auto& [n, t] : s.tools) {
    std::string offs;
    for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i) {
      const Fact& f = t.offsets[static_cast<size_t>(i)];
      offs += fmt::format("{}{}{}", offs.empty() ? "" : " ", axis_name(s.axes[static_cast<size_t>(i)]), fact(f));
    }
    NodeId last = t.last_configured;
    rows.push_back({std::to_string(n) + (t.maybe ? " (maybe)" : ""),
                    t.name.empty() ? "-" : "\"" + sanitize(t.name) + "\"", t.drives_known ? ints(t.drives) : "?",
                    t.heaters_known ? ints(t.heaters) : "?", ints(t.fans),
                    fmt::format("X→{} Y→{} Z→{}", map_str(s, t.xmap), map_str(s, t.ymap), map_str(s, t.zmap)),
                    offs + (last != kNoNode ? fmt::format(" ({})", where(r, sm, last)) : ""),
                    t.temps_known ? temps(t.active) + "/" + temps(t.standby) : "unknown", where(r, sm, t.created)});
  }
  if (rows.size() > 1) table(os, rows);
  else os << "  none\n";
  for (const auto& [n, id] : s.failed_tools)
    os << fmt::format("  tool {}: not created, its M563 failed ({})\n", n, where(r, sm, id));
  os << "\nCurrent tool: "
     << (s.current_tool_known ? (s.current_tool >= 0 ? std::to_string(s.current_tool) : std::string("none"))
                              : std::string("unknown"))
     << "\n";
}

// The workplaces, the mode and the kinematics.
void render_workplaces(std::ostream& os, const SourceManager& sm, const MachineResult& r, const MachineState& s) {
  os << "\nWorkplaces\n";
  std::vector<std::vector<std::string>> rows = {{"slot", "code", "origin"}};
  static const char* kCodes[] = {"", "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"};
  for (int w = 1; w <= 9; ++w) {
    std::string o;
    NodeId last = kNoNode;
    for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i) {
      const Fact& f = s.workplaces[static_cast<size_t>(w)].origin[static_cast<size_t>(i)];
      if (f.origin != kNoNode) last = f.origin;
      o += fmt::format("{}{}{}", o.empty() ? "" : " ", axis_name(s.axes[static_cast<size_t>(i)]), fact(f));
    }
    if (last == kNoNode) continue;
    rows.push_back({std::to_string(w), kCodes[w], o + " (" + where(r, sm, last) + ")"});
  }
  if (rows.size() > 1) table(os, rows);
  else os << "  all at 0 (default)\n";
  os << "\nMode: "
     << (s.mode == MachineMode::CNC     ? "CNC"
         : s.mode == MachineMode::Laser ? "laser"
                                        : "FFF")
     << fmt::format(", kinematics K{}", s.kinematics)
     << (s.m501 != kNoNode ? fmt::format(", M501 at {}", where(r, sm, s.m501)) : ", no M501") << "\n";
}

}  // namespace

void render_model_text(std::ostream& os, const SourceManager& sm, const MachineResult& r, const std::string& title) {
  const MachineState& s = r.end_of_boot;
  os << "Machine: " << title << "\n";
  render_target(os, sm, r);
  render_axes(os, sm, r, s);
  render_drives(os, sm, r);
  render_devices(os, sm, r, s);
  render_heater_settings(os, sm, r);
  render_ports(os, sm, r);
  render_tools(os, sm, r, s);
  render_workplaces(os, sm, r, s);
  render_kinematics(os, sm, r);
}

namespace {

using namespace model_text;

nlohmann::json tools_json(const MachineResult& r, const SourceManager& sm) {
  using nlohmann::json;
  const MachineState& s = r.end_of_boot;
  auto at = [&](NodeId id) { return at_json(r, sm, id); };
  auto fj = fact_json;
  json tools = json::array();
  for (const auto& [n, t] : s.tools) {
    json offs = json::object();
    for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i)
      offs[axis_name(s.axes[static_cast<size_t>(i)])] = fj(t.offsets[static_cast<size_t>(i)]);
    tools.push_back({{"tool", n},
                     {"name", sanitize(t.name)},
                     {"drives", t.drives},
                     {"heaters", t.heaters},
                     {"fans", t.fans},
                     {"x_map", map_str(s, t.xmap)},
                     {"y_map", map_str(s, t.ymap)},
                     {"z_map", map_str(s, t.zmap)},
                     {"offsets", offs},
                     {"active", t.active},
                     {"standby", t.standby},
                     {"temperatures_known", t.temps_known},
                     {"maybe", t.maybe},
                     {"created_at", at(t.created)},
                     {"last_configured_at", at(t.last_configured)}});
  }
  return tools;
}

nlohmann::json workplaces_json(const MachineState& s) {
  using nlohmann::json;
  auto fj = fact_json;
  json wps = json::array();
  for (int w = 1; w <= 9; ++w) {
    json o = json::object();
    for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i)
      o[axis_name(s.axes[static_cast<size_t>(i)])] =
          fj(s.workplaces[static_cast<size_t>(w)].origin[static_cast<size_t>(i)]);
    wps.push_back({{"slot", w}, {"origin", o}});
  }
  return wps;
}

}  // namespace

void render_model_json(std::ostream& os, const SourceManager& sm, const MachineResult& r, const std::string& title) {
  using nlohmann::json;
  const MachineState& s = r.end_of_boot;
  auto at = [&](NodeId id) { return at_json(r, sm, id); };
  json j;
  j["version"] = 1;
  j["machine"] = sanitize(title);
  j["firmware"] = {{"version", r.target.version.str()}, {"given", r.target.version_given}, {"reason", r.target.reason}};
  json ev = json::array();
  for (const Evidence& e : r.target.evidence)
    ev.push_back({{"what", e.what},
                  {"file", sanitize(sm.get(e.loc.file).display_path())},
                  {"line", sm.get(e.loc.file).position(e.loc.span.begin).line}});
  j["firmware"]["evidence"] = ev;
  j["board"] = board_name(r.target.board);
  json axes = json::array();
  for (size_t i = 0; i < s.axes.size(); ++i) {
    const Axis& a = s.axes[i];
    json drv = json::array();
    for (auto& d : a.drivers) drv.push_back(d.str());
    axes.push_back({{"index", i},
                    {"letter", axis_name(a)},
                    {"drivers", drv},
                    {"visible", static_cast<int>(i) < s.visible_axes},
                    {"rotational", a.rotational},
                    {"maybe", a.maybe},
                    {"set_at", at(a.drivers_set != kNoNode ? a.drivers_set : a.created)}});
    axis_json(axes.back(), sm, r, a);
  }
  j["axes"] = axes;
  json ex = json::array();
  for (auto& d : s.extruder_drivers) ex.push_back(d.str());
  j["extruders"] = {{"count", s.extruders_known ? json(s.extruders) : json("unknown")},
                    {"drivers", ex},
                    {"set_at", at(s.extruders_set)}};
  json heaters = json::array();
  for (const auto& [n, h] : s.heaters)
    heaters.push_back({{"heater", n},
                       {"sensor", h.sensor},
                       {"monitor", h.monitor_installed},
                       {"limit", h.limit},
                       {"user_monitor", h.user_monitor},
                       {"bed", n == s.bed_heater},
                       {"created_at", at(h.created)}});
  for (size_t i = 0; const auto& [n, h] : s.heaters) heater_json(heaters[i++], sm, r, h);
  j["heaters"] = heaters;
  json sensors = json::array();
  for (const auto& [n, sn] : s.sensors)
    sensors.push_back({{"sensor", n}, {"type", sanitize(sn.type)}, {"created_at", at(sn.created)}});
  j["sensors"] = sensors;
  json fans = json::array();
  for (const auto& [n, f] : s.fans) {
    fans.push_back({{"fan", n}, {"created_at", at(f.created)}});
    fan_json(fans.back(), sm, r, f);
  }
  j["fans"] = fans;
  json probes = json::array();
  for (const auto& [n, p] : s.probes) {
    probes.push_back({{"probe", n}, {"type", p.type}, {"created_at", at(p.created)}});
    probe_json(probes.back(), sm, r, p);
  }
  j["probes"] = probes;
  j["tools"] = tools_json(r, sm);
  j["current_tool"] = s.current_tool_known ? json(s.current_tool) : json("unknown");
  j["workplaces"] = workplaces_json(s);
  j["m501_at"] = at(s.m501);
  machine_json(j, sm, r);
  os << j.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
}

}  // namespace rrflint
