// `rrflint model`, the machine beyond the first tables: heater monitor slots, PID and fault detection; drivers,
// steps/mm, microstepping and endstops; ports, their users, triggers, filament monitors and the pins devices hold;
// kinematics and leadscrews.
#include "lint/render/model_tables.h"

#include <fmt/format.h>

#include <algorithm>

#include "lint/render/render.h"

namespace rrflint::model_text {

std::string where(const MachineResult& r, const SourceManager& sm, NodeId id) {
  if (id == kNoNode) return "default";
  const Graph& g = r.graph;
  Node node = g.nodes[id];
  while (node.kind != NodeKind::Command && node.call_site != kNoNode) node = g.nodes[node.call_site];
  const Node* n = &node;
  const FileUnit& u = r.machine->unit(n->unit);
  uint32_t off = n->kind == NodeKind::Command ? u.parsed.commands[n->index].span.begin : 0;
  LineCol lc = sm.get(u.source->id()).position(off);
  return fmt::format("{}:{}", sanitize(u.source->display_path()), lc.line);
}

std::string num(double v) {
  std::string s = fmt::format("{:.3f}", v);
  while (s.size() > 1 && s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::string fact(const Fact& f) { return f.known ? num(f.value) : "unknown"; }

void table(std::ostream& os, const std::vector<std::vector<std::string>>& rows) {
  if (rows.empty()) return;
  std::vector<size_t> w(rows[0].size(), 0);
  for (const auto& r : rows)
    for (size_t i = 0; i < r.size(); ++i) w[i] = std::max<size_t>(w[i], count_code_points(r[i]));
  for (const auto& r : rows) {
    std::string line = "  ";
    for (size_t i = 0; i < r.size(); ++i) {
      line += r[i];
      if (i + 1 < r.size()) line += std::string(w[i] - count_code_points(r[i]) + 2, ' ');
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    os << line << "\n";
  }
}

nlohmann::json fact_json(const Fact& f) { return f.known ? nlohmann::json(f.value) : nlohmann::json("unknown"); }

nlohmann::json at_json(const MachineResult& r, const SourceManager& sm, NodeId id) {
  return id == kNoNode ? nlohmann::json(nullptr) : nlohmann::json(where(r, sm, id));
}

namespace {

using nlohmann::json;

void table_or_none(std::ostream& os, const std::vector<std::vector<std::string>>& rows, const char* none = "none") {
  if (rows.size() > 1) table(os, rows);
  else os << "  " << none << "\n";
}

/// The pin table (kept in no order on the forward pass) by pin name.
std::vector<std::pair<const std::string*, const PinOwner*>> pins_by_name(const MachineState& s) {
  std::vector<std::pair<const std::string*, const PinOwner*>> v;
  v.reserve(s.pins.size());
  for (const auto& [key, o] : s.pins) v.emplace_back(&key, &o);
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return *a.first < *b.first; });
  return v;
}

std::string axis_name(const Axis& a) {
  return a.letter >= 'a' ? fmt::format("'{}", a.letter) : std::string(1, a.letter);
}

std::string list(const std::vector<int64_t>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ":" : "") + std::to_string(v[i]);
  return s.empty() ? "-" : s;
}

std::string list(const std::vector<double>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ":" : "") + num(v[i]);
  return s.empty() ? "-" : s;
}

std::string condition_name(const Fact& c) {
  if (!c.known) return "unknown";
  return c.value < 0 ? "disabled" : c.value == 0 ? "exceeded" : c.value == 1 ? "too low" : num(c.value);
}

std::string action_name(const Fact& a) {
  if (!a.known) return "unknown";
  static const char* kNames[] = {"fault", "switch off", "switch off (temporary)", "shut down"};
  return a.value >= 0 && a.value <= 3 ? kNames[static_cast<int>(a.value)] : num(a.value);
}

std::string maybe(bool m) { return m ? " (maybe)" : ""; }

constexpr const char* kPortLetters = "JPSR";  // by PortKind
constexpr const char* kPortKinds[] = {"GPIO in", "GPIO out", "servo", "spindle"};

std::string drive_name(const DriverUse& u, const MachineState& s) {
  return u.extruder ? fmt::format("E{}", u.index) : axis_name(s.axes[static_cast<size_t>(u.index)]);
}

/// The extruders to list: those that exist, or with their count unknown, those some command set.
int listed_extruders(const MachineState& s) {
  if (s.extruders_known) return std::min(s.extruders, kMaxAxisSlots);
  int n = 0;
  for (int e = 0; e < kMaxAxisSlots; ++e) {
    const DriveSettings& d = s.extruder_drive[static_cast<size_t>(e)];
    if (d.steps.origin != kNoNode || d.microsteps.origin != kNoNode) n = e + 1;
  }
  return n;
}

std::string trigger_action(int n) {
  return n == 0 ? "emergency stop" : n == 1 ? "pause" : fmt::format("sys/trigger{}.g", n);
}

}  // namespace

void render_heater_settings(std::ostream& os, const SourceManager& sm, const MachineResult& r) {
  const MachineState& s = r.end_of_boot;
  os << "\nHeater monitors (M143)\n";
  std::vector<std::vector<std::string>> rows = {{"heater", "slot", "condition", "limit", "action", "sensor", "set at"}};
  for (const auto& [n, h] : s.heaters)
    for (size_t i = 0; i < h.monitors.size(); ++i) {
      const MonitorSlot& m = h.monitors[i];
      if (m.set == kNoNode) continue;
      const char* how = m.set == h.default_monitor ? " (default)" : "";
      rows.push_back({std::to_string(n), std::to_string(i), condition_name(m.condition), fact(m.limit) + " °C",
                      action_name(m.action), fact(m.sensor), where(r, sm, m.set) + how + maybe(m.maybe)});
    }
  table_or_none(os, rows, "none set (every slot disabled)");
  os << "\nHeater control (M301, M570)\n";
  rows = {{"heater", "PID", "fault time", "excursion", "bad readings", "set at"}};
  for (const auto& [n, h] : s.heaters) {
    const Pid& p = h.pid;
    const FaultDetection& f = h.fault;
    std::string pid = p.set == kNoNode ? "-" : fmt::format("P{} I{} D{}", fact(p.p), fact(p.i), fact(p.d));
    std::string at = p.set == kNoNode ? "" : "M301 " + where(r, sm, p.set);
    if (f.set != kNoNode) at += (at.empty() ? "M570 " : ", M570 ") + where(r, sm, f.set);
    rows.push_back({std::to_string(n), pid, fact(f.time) + " s", fact(f.excursion) + " °C", fact(f.bad_readings),
                    at.empty() ? "default" : at});
  }
  table_or_none(os, rows);
}

void render_drives(std::ostream& os, const SourceManager& sm, const MachineResult& r) {
  const MachineState& s = r.end_of_boot;
  os << "\nDrivers\n";
  std::vector<std::vector<std::string>> rows = {{"driver", "board", "drives", "shared"}};
  std::vector<DriverUse> uses = s.driver_uses();
  std::vector<DriverId> seen;
  for (const DriverUse& u : uses) {
    if (std::find(seen.begin(), seen.end(), u.driver) != seen.end()) continue;
    seen.push_back(u.driver);
    std::string drives;
    for (const DriverUse& v : uses)
      if (v.driver == u.driver) drives += (drives.empty() ? "" : ", ") + drive_name(v, s);
    rows.push_back({u.driver.str(), u.local() ? "local" : fmt::format("CAN {}", u.driver.board), drives,
                    s.driver_shared(u.driver) ? "SHARED" : "-"});
  }
  table_or_none(os, rows);
  os << "\nDrives (M92, M350)\n";
  rows = {{"drive", "steps/mm", "microstepping", "steps set at", "microstepping set at"}};
  auto add = [&](const std::string& name, const DriveSettings& d) {
    std::string steps = where(r, sm, d.steps.origin);
    if (d.steps_rescaled != kNoNode) steps += ", rescaled " + where(r, sm, d.steps_rescaled);
    std::string interp = d.interpolation_known ? (d.interpolation ? " I1" : " I0") : " I?";
    rows.push_back({name, fact(d.steps), (d.microsteps.known ? "x" + num(d.microsteps.value) : "unknown") + interp,
                    steps, where(r, sm, d.microsteps.origin)});
  };
  for (const Axis& a : s.axes) add(axis_name(a), a.drive);
  for (int e = 0; e < listed_extruders(s); ++e) add(fmt::format("E{}", e), s.extruder_drive[static_cast<size_t>(e)]);
  table(os, rows);
  os << "\nEndstops (M574)\n";
  rows = {{"axis", "position", "type", "pins", "set at"}};
  for (const Axis& a : s.axes) {
    const Axis::Endstop& e = a.endstop;
    if (e.set == kNoNode) continue;
    const std::string pos = !e.position.known       ? "unknown"
                            : e.position.value == 1 ? "low end"
                            : e.position.value == 2 ? "high end"
                                                    : "none";
    rows.push_back({axis_name(a), pos, "S" + fact(e.type), e.pins.empty() ? "-" : "\"" + sanitize(e.pins) + "\"",
                    where(r, sm, e.set) + maybe(e.maybe)});
  }
  table_or_none(os, rows);
}

void render_ports(std::ostream& os, const SourceManager& sm, const MachineResult& r) {
  const MachineState& s = r.end_of_boot;
  os << fmt::format("\nPorts (M950 J/P/S/R){}\n", s.ports_known ? "" : " (some created with unknown numbers)");
  std::vector<std::vector<std::string>> rows = {{"port", "kind", "pin", "used at", "created at"}};
  for (size_t k = 0; k < 4; ++k)
    for (const auto& [n, p] : s.ports[k]) {
      std::string used;
      for (const PortUse& u : s.port_uses)
        if (static_cast<size_t>(u.kind) == k && u.port == n) used += (used.empty() ? "" : ", ") + where(r, sm, u.at);
      rows.push_back({fmt::format("{}{}", kPortLetters[k], n), kPortKinds[k], "\"" + sanitize(p.pin) + "\"",
                      used.empty() ? "-" : used, where(r, sm, p.created) + maybe(p.maybe)});
    }
  for (const PortUse& u : s.port_uses)  // uses of a port no M950 created (or of an unknown one)
    if (u.port < 0 || !s.ports[static_cast<size_t>(u.kind)].count(u.port))
      rows.push_back({u.port < 0 ? fmt::format("{}?", kPortLetters[static_cast<size_t>(u.kind)])
                                 : fmt::format("{}{}", kPortLetters[static_cast<size_t>(u.kind)], u.port),
                      kPortKinds[static_cast<size_t>(u.kind)], "-", where(r, sm, u.at) + maybe(u.maybe),
                      "not created"});
  table_or_none(os, rows);
  os << "\nTriggers (M581)\n";
  rows = {{"trigger", "rising", "falling", "condition", "runs", "set at"}};
  for (const auto& [n, t] : s.triggers)
    rows.push_back({std::to_string(n), t.ports_known ? list(t.rising) : "unknown",
                    t.ports_known ? list(t.falling) : "unknown", "R" + fact(t.condition), trigger_action(n),
                    where(r, sm, t.set) + maybe(t.maybe)});
  table_or_none(os, rows);
  os << fmt::format("\nFilament monitors (M591){}\n", s.filament_monitors_known ? "" : " (partly unknown)");
  rows = {{"extruder", "type", "pin", "created at"}};
  for (const auto& [e, m] : s.filament_monitors)
    rows.push_back({std::to_string(e), "P" + fact(m.type), m.pin.empty() ? "-" : "\"" + sanitize(m.pin) + "\"",
                    where(r, sm, m.created) + maybe(m.maybe)});
  table_or_none(os, rows);
  os << fmt::format("\nPins{}\n", s.pins_known ? "" : " (partly unknown: a device or a macro path from an expression)");
  rows = {{"pin", "held by", "as written", "taken at"}};
  for (const auto& [key, o] : pins_by_name(s))
    rows.push_back(
        {sanitize(*key), o->device.name(), "\"" + sanitize(o->written) + "\"", where(r, sm, o->at) + maybe(o->maybe)});
  table_or_none(os, rows);
}

void render_kinematics(std::ostream& os, const SourceManager& sm, const MachineResult& r) {
  const MachineState& s = r.end_of_boot;
  os << "\nKinematics: " << (s.kinematics_known ? fmt::format("K{}", s.kinematics) : std::string("unknown"))
     << (s.kinematics_set != kNoNode ? " (" + where(r, sm, s.kinematics_set) + ")" : " (default)") << "\n";
  for (const auto& [name, f] : s.kinematics_params)
    os << fmt::format("  {}{} ({})\n", name, fact(f), where(r, sm, f.origin));
  const Leadscrews& l = s.leadscrews;
  os << "Leadscrews (M671): ";
  if (l.set == kNoNode) {
    os << "none\n";
    return;
  }
  os << (l.known ? fmt::format("X{} Y{}", list(l.x), list(l.y)) : std::string("unknown")) << " (" << where(r, sm, l.set)
     << ")";
  if (l.dropped != kNoNode)
    os << fmt::format(", {} by the kinematics change at {}", l.dropped_maybe ? "perhaps dropped" : "DROPPED",
                      where(r, sm, l.dropped));
  os << "\n";
}

void heater_json(json& j, const SourceManager& sm, const MachineResult& r, const Heater& h) {
  json slots = json::array();
  for (size_t i = 0; i < h.monitors.size(); ++i) {
    const MonitorSlot& m = h.monitors[i];
    slots.push_back({{"slot", i},
                     {"condition", fact_json(m.condition)},
                     {"limit", fact_json(m.limit)},
                     {"action", fact_json(m.action)},
                     {"sensor", fact_json(m.sensor)},
                     {"maybe", m.maybe},
                     {"set_at", at_json(r, sm, m.set)}});
  }
  j["monitors"] = slots;
  j["default_monitor_at"] = at_json(r, sm, h.default_monitor);
  j["pid"] = {{"p", fact_json(h.pid.p)},
              {"i", fact_json(h.pid.i)},
              {"d", fact_json(h.pid.d)},
              {"set_at", at_json(r, sm, h.pid.set)}};
  j["fault_detection"] = {{"time", fact_json(h.fault.time)},
                          {"excursion", fact_json(h.fault.excursion)},
                          {"bad_readings", fact_json(h.fault.bad_readings)},
                          {"timeout", fact_json(h.fault.timeout)},
                          {"set_at", at_json(r, sm, h.fault.set)}};
}

void fan_json(json& j, const SourceManager& sm, const MachineResult& r, const Fan& f) {
  j["thermostatic"] = f.thermostat_known ? json(f.thermostatic) : json("unknown");
  j["sensors"] = f.sensors;
  j["thresholds"] = f.thresholds;
  j["thermostat_set_at"] = at_json(r, sm, f.thermostat_set);
}

void probe_json(json& j, const SourceManager& sm, const MachineResult& r, const Probe& p) {
  j["trigger_height"] = fact_json(p.trigger_height);
  j["offsets"] = {{"X", fact_json(p.x_offset)}, {"Y", fact_json(p.y_offset)}};
  j["g31_at"] = at_json(r, sm, p.g31);
}

namespace {

json drive_json(const SourceManager& sm, const MachineResult& r, const DriveSettings& d) {
  return {{"steps_per_mm", fact_json(d.steps)},
          {"steps_set_at", at_json(r, sm, d.steps.origin)},
          {"steps_rescaled_at", at_json(r, sm, d.steps_rescaled)},
          {"microstepping", fact_json(d.microsteps)},
          {"interpolation", d.interpolation_known ? json(d.interpolation) : json("unknown")},
          {"microstepping_set_at", at_json(r, sm, d.microsteps.origin)}};
}

json ports_json(const SourceManager& sm, const MachineResult& r) {
  const MachineState& s = r.end_of_boot;
  json ports = json::array();
  for (size_t k = 0; k < 4; ++k)
    for (const auto& [n, p] : s.ports[k]) {
      json used = json::array();
      for (const PortUse& u : s.port_uses)
        if (static_cast<size_t>(u.kind) == k && u.port == n) used.push_back(where(r, sm, u.at));
      ports.push_back({{"kind", kPortKinds[k]},
                       {"port", n},
                       {"pin", sanitize(p.pin)},
                       {"maybe", p.maybe},
                       {"created_at", at_json(r, sm, p.created)},
                       {"used_at", used}});
    }
  return ports;
}

}  // namespace

void axis_json(json& j, const SourceManager& sm, const MachineResult& r, const Axis& a) {
  j.update(drive_json(sm, r, a.drive));
  const Axis::Endstop& e = a.endstop;
  j["endstop"] = {{"position", fact_json(e.position)},
                  {"type", fact_json(e.type)},
                  {"pins", sanitize(e.pins)},
                  {"maybe", e.maybe},
                  {"set_at", at_json(r, sm, e.set)}};
}

void machine_json(json& j, const SourceManager& sm, const MachineResult& r) {
  const MachineState& s = r.end_of_boot;
  auto at = [&](NodeId id) { return at_json(r, sm, id); };
  json drives = json::array();
  for (int e = 0; e < listed_extruders(s); ++e) {
    drives.push_back(drive_json(sm, r, s.extruder_drive[static_cast<size_t>(e)]));
    drives.back()["extruder"] = e;
  }
  j["extruders"]["drives"] = drives;
  json drivers = json::array();
  for (const DriverUse& u : s.driver_uses())
    drivers.push_back({{"driver", u.driver.str()},
                       {"board", u.driver.board},
                       {"local", u.local()},
                       {"drive", drive_name(u, s)},
                       {"shared", s.driver_shared(u.driver)}});
  j["drivers"] = drivers;
  j["ports"] = ports_json(sm, r);
  j["ports_known"] = s.ports_known;
  json uses = json::array();
  for (const PortUse& u : s.port_uses)
    uses.push_back({{"kind", kPortKinds[static_cast<size_t>(u.kind)]},
                    {"port", u.port < 0 ? json("unknown") : json(u.port)},
                    {"maybe", u.maybe},
                    {"at", at(u.at)}});
  j["port_uses"] = uses;
  json triggers = json::array();
  for (const auto& [n, t] : s.triggers)
    triggers.push_back({{"trigger", n},
                        {"rising", t.rising},
                        {"falling", t.falling},
                        {"ports_known", t.ports_known},
                        {"condition", fact_json(t.condition)},
                        {"runs", trigger_action(n)},
                        {"maybe", t.maybe},
                        {"set_at", at(t.set)}});
  j["triggers"] = triggers;
  json fms = json::array();
  for (const auto& [e, m] : s.filament_monitors)
    fms.push_back({{"extruder", e},
                   {"type", fact_json(m.type)},
                   {"pin", sanitize(m.pin)},
                   {"maybe", m.maybe},
                   {"created_at", at(m.created)}});
  j["filament_monitors"] = fms;
  json pins = json::array();
  for (const auto& [key, o] : pins_by_name(s))
    pins.push_back({{"pin", sanitize(*key)},
                    {"device", o->device.name()},
                    {"written", sanitize(o->written)},
                    {"maybe", o->maybe},
                    {"at", at(o->at)}});
  j["pins"] = pins;
  j["pins_known"] = s.pins_known;
  json params = json::object();
  for (const auto& [name, f] : s.kinematics_params) params[name] = fact_json(f);
  const Leadscrews& l = s.leadscrews;
  j["kinematics"] = {{"type", s.kinematics_known ? json(s.kinematics) : json("unknown")},
                     {"set_at", at(s.kinematics_set)},
                     {"parameters", params},
                     {"leadscrews",
                      {{"x", l.x},
                       {"y", l.y},
                       {"known", l.known},
                       {"set_at", at(l.set)},
                       {"dropped_at", at(l.dropped)},
                       {"dropped_maybe", l.dropped_maybe}}}};
}

}  // namespace rrflint::model_text
