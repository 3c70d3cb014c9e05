// The numbered objects a command's parameters name, and their descriptions (objects.h).
#include "cli/server/objects.h"

#include <fmt/format.h>

#include "lint/boot/commands.h"
#include "lint/boot/model.h"
#include "lint/render/model_tables.h"

namespace rrflint::server {
namespace {

// Which parameters name which objects (GCodes*.cpp, Heat.cpp, FansManager.cpp); -1 numbers T commands.
constexpr ObjectParam kParams[] = {
    {'G', 10, 'P', ObjKind::Tool, false},    {'M', 106, 'P', ObjKind::Fan, false},
    {'M', 106, 'H', ObjKind::Sensor, false}, {'M', 140, 'H', ObjKind::Heater, false},
    {'M', 141, 'H', ObjKind::Heater, false}, {'M', 143, 'H', ObjKind::Heater, false},
    {'M', 143, 'T', ObjKind::Sensor, false}, {'M', 301, 'H', ObjKind::Heater, false},
    {'M', 303, 'H', ObjKind::Heater, false}, {'M', 303, 'T', ObjKind::Tool, false},
    {'M', 307, 'H', ObjKind::Heater, false}, {'M', 308, 'S', ObjKind::Sensor, true},
    {'M', 563, 'P', ObjKind::Tool, true},    {'M', 563, 'H', ObjKind::Heater, false},
    {'M', 563, 'F', ObjKind::Fan, false},    {'M', 567, 'P', ObjKind::Tool, false},
    {'M', 568, 'P', ObjKind::Tool, false},   {'M', 570, 'H', ObjKind::Heater, false},
    {'M', 950, 'H', ObjKind::Heater, true},  {'M', 950, 'F', ObjKind::Fan, true},
    {'M', 950, 'T', ObjKind::Sensor, false}, {'T', -1, 'T', ObjKind::Tool, false},
};

// " (created at X)" or " (created at X, maybe)".
std::string created(const DocAt& d, NodeId at, bool maybe, bool code) {
  return fmt::format(" (created at {}{})", d.where(at, code), maybe ? "; maybe: inside an if/while" : "");
}

std::string axis_name(const MachineState& s, int i) {
  if (i >= static_cast<int>(s.axes.size())) return "#" + std::to_string(i);
  const char l = s.axes[static_cast<size_t>(i)].letter;
  return l >= 'a' ? fmt::format("'{}", l) : std::string(1, l);
}

}  // namespace

std::string code_span(std::string_view s, bool code) {
  if (!code) return std::string(s);
  std::string t(s);
  for (char& c : t)
    if (c == '`' || c == '\n' || c == '\r') c = '\'';
  return fmt::format("`{}`", t);
}

std::string_view obj_kind_name(ObjKind k) {
  switch (k) {
    case ObjKind::Tool: return "tool";
    case ObjKind::Heater: return "heater";
    case ObjKind::Fan: return "fan";
    case ObjKind::Sensor: return "sensor";
  }
  return "object";
}

const ObjectParam* object_param(const ParsedFile& pf, const Command& c, char param) {
  const int number = c.letter == 'T' ? -1 : c.number;
  if (c.fraction >= 0) return nullptr;
  for (const ObjectParam& p : kParams)
    if (p.letter == c.letter && p.number == number && p.param == param) {
      if (c.is('G', 10)) {  // the tool form only: L1, or no L
        const Val<int64_t> L = get_int(pf, c, 'L');
        if (L.present() && !(L.known() && L.value == 1)) return nullptr;
      }
      return &p;
    }
  return nullptr;
}

std::vector<const ObjectParam*> object_params(const ParsedFile& pf, const Command& c) {
  std::vector<const ObjectParam*> out;
  if (c.letter == 'T') {
    if (const ObjectParam* p = object_param(pf, c, 'T')) out.push_back(p);
    return out;
  }
  for (const Param& p : pf.params(c))
    if (const ObjectParam* op = object_param(pf, c, p.letter)) out.push_back(op);
  return out;
}

std::vector<int> object_numbers(const MachineState& s, ObjKind k) {
  std::vector<int> out;
  auto keys = [&](const auto& map) {
    for (const auto& [n, v] : map) out.push_back(n);
  };
  switch (k) {
    case ObjKind::Tool: keys(s.tools); break;
    case ObjKind::Heater: keys(s.heaters); break;
    case ObjKind::Fan: keys(s.fans); break;
    case ObjKind::Sensor: keys(s.sensors); break;
  }
  return out;
}

bool objects_known(const MachineState& s, ObjKind k) {
  if (s.unknown_baseline) return false;
  switch (k) {
    case ObjKind::Tool: return s.tools_known;
    case ObjKind::Heater: return s.heaters_known;
    case ObjKind::Fan: return s.fans_known;
    case ObjKind::Sensor: return s.sensors_known;
  }
  return false;
}

std::optional<std::string> describe(const DocAt& d, const MachineState& s, ObjKind k, int n, bool code) {
  switch (k) {
    case ObjKind::Tool: {
      const Tool* t = s.tool(n);
      if (!t) return std::nullopt;
      return fmt::format("tool {}{}{}", n, t->name.empty() ? "" : " " + code_span("\"" + t->name + "\"", code),
                         created(d, t->created, t->maybe, code));
    }
    case ObjKind::Heater: {
      auto h = s.heaters.find(n);
      if (h == s.heaters.end()) return std::nullopt;
      return fmt::format("heater {}{}{}{}", n, n == s.bed_heater ? " (bed)" : "",
                         h->second.sensor >= 0 ? fmt::format(", sensor {}", h->second.sensor) : "",
                         created(d, h->second.created, h->second.maybe, code));
    }
    case ObjKind::Fan: {
      auto f = s.fans.find(n);
      if (f == s.fans.end()) return std::nullopt;
      return fmt::format("fan {}{}", n, created(d, f->second.created, f->second.maybe, code));
    }
    case ObjKind::Sensor: {
      auto t = s.sensors.find(n);
      if (t == s.sensors.end()) return std::nullopt;
      return fmt::format("sensor {}{}{}", n, t->second.type.empty() ? "" : " " + code_span(t->second.type, code),
                         created(d, t->second.created, t->second.maybe, code));
    }
  }
  return std::nullopt;
}

std::vector<std::string> tool_details(const DocAt& d, const MachineState& s, int n, bool code) {
  const Tool* t = s.tool(n);
  if (!t) return {};
  auto map = [&](char axis, const AxisMap& m) {
    return fmt::format("{}→{}", axis, m.known ? s.axis_letters(m.bits) : "unknown");
  };
  std::vector<std::string> out{
      fmt::format("axis map: {} {} {}", map('X', t->xmap), map('Y', t->ymap), map('Z', t->zmap))};
  std::string offs;
  for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i)
    offs += fmt::format("{}{}{}", offs.empty() ? "" : " ", axis_name(s, i),
                        model_text::fact(t->offsets[static_cast<size_t>(i)]));
  if (t->last_configured != kNoNode) offs += fmt::format(" (last set at {})", d.where(t->last_configured, code));
  out.push_back("offsets: " + offs);
  return out;
}

std::vector<std::string> drive_facts(const DocAt& d, const MachineState& s, const Command& c, bool code) {
  std::vector<std::string> out;
  const ParsedFile& pf = d.parsed();
  auto drivers = [](const std::vector<DriverId>& v) {
    std::string t;
    for (const DriverId& id : v) t += (t.empty() ? "" : ":") + id.str();
    return t.empty() ? std::string("none") : t;
  };
  if (c.is('M', 584)) {
    for (const Param& p : pf.params(c)) {
      if (p.letter == 'E') {
        out.push_back(
            fmt::format("extruders before it: {}", s.extruders_known ? std::to_string(s.extruders) : "unknown"));
        continue;
      }
      if (!p.letter || allowed_axis_letters().find(p.letter) == std::string_view::npos) continue;
      const int i = s.axis_index(p.letter);
      const std::string name = p.letter >= 'a' ? fmt::format("'{}", p.letter) : std::string(1, p.letter);
      if (i < 0) {
        out.push_back(fmt::format("creates axis {}", name));
        continue;
      }
      const Axis& a = s.axes[static_cast<size_t>(i)];
      const NodeId set = a.drivers_set != kNoNode ? a.drivers_set : a.created;
      out.push_back(fmt::format("axis {} exists: drivers {} ({})", name, drivers(a.drivers),
                                set == kNoNode ? "the default" : "set at " + d.where(set, code)));
    }
  } else if (c.is('M', 569)) {
    const Val<std::vector<DriverId>> ids = get_driver_list(pf, c, 'P');
    if (!ids.known()) return out;
    const std::vector<DriverUse> uses = s.driver_uses();
    for (const DriverId& id : ids.value) {
      std::string what;
      for (const DriverUse& u : uses)
        if (u.driver == id)
          what += fmt::format("{}{}", what.empty() ? "" : ", ",
                              u.extruder ? fmt::format("extruder {}", u.index) : "axis " + axis_name(s, u.index));
      out.push_back(
          fmt::format("driver {}: {}", id.str(), what.empty() ? "moves no axis or extruder here" : "moves " + what));
    }
  }
  return out;
}

}  // namespace rrflint::server
