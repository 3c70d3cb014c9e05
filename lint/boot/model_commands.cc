// The machine model's reading of each command that changes it (docs/firmware-behaviour.md): M584 axes, M563 tools, G10
// offsets and workplaces, M568 temperatures, M950/M308 devices, heater monitors, probes, modes.
#include <algorithm>
#include <bit>

#include "lint/boot/commands.h"
#include "lint/boot/model.h"
#include "lint/boot/model_commands.h"

namespace rrflint {
namespace {

constexpr std::string_view kAxisOrder = "XYZUVWABCDabcdefghijklmnopqrstuvwxyz";
constexpr double kToolHeaterLimit = 285.0;  // DefaultHotEndTemperatureLimit (3.1+); 290 in 3.0
constexpr double kBedHeaterLimit = 125.0;

using Cx = CommandCx;

/// limit = the highest over-temperature monitor (Heater::GetHighestTemperatureLimit), 2000 with none.
void update_limit(Heater& h) {
  double hi = -1;
  for (double l : h.monitor_limits) hi = std::max(hi, l);
  h.monitor_installed = hi >= 0;
  h.limit = hi >= 0 ? hi : 2000;
}

void install_tool_heater_defaults(MachineState& s, int h, NodeId id, bool maybe) {
  auto it = s.heaters.find(h);
  if (it == s.heaters.end()) return;
  const double limit = s.firmware < kRrf3_1 ? 290.0 : kToolHeaterLimit;
  install_default_monitor(it->second, limit, id, maybe);
  if (it->second.user_monitor) return;
  it->second.monitor_limits[0] = limit;
  update_limit(it->second);
  it->second.monitor_origin = id;
}

void install_bed_heater_defaults(MachineState& s, int h, NodeId id, bool maybe) {
  auto it = s.heaters.find(h);
  if (it == s.heaters.end()) return;
  install_default_monitor(it->second, kBedHeaterLimit, id, maybe);
  if (it->second.user_monitor) return;
  it->second.monitor_limits[0] = kBedHeaterLimit;
  update_limit(it->second);
  it->second.monitor_origin = id;
}

void do_m584(Cx& x) {
  MachineState& s = x.s;
  const BoardLimits lim = board_limits(s.board, s.firmware);
  const char hi = highest_lowercase_axis(s.board, s.firmware);
  auto r = get_int(x.pf, x.c, 'R');
  for (char L : kAxisOrder) {
    if (L >= 'a' && (hi == 0 || L > hi)) break;
    if (L < 'a' && s.firmware < kRrf3_0 && std::string_view("XYZUVWABC").find(L) == std::string_view::npos) continue;
    ParamRef p = x.pf.find(x.c, L);
    if (!p) continue;
    auto drivers = get_driver_list(x.pf, x.c, L);
    int idx = s.axis_index(L);
    if (idx < 0) {
      if (static_cast<int>(s.axes.size()) >= lim.max_axes) {
        s.failed_axes[L] = x.id;
        continue;
      }
      Axis a;
      a.letter = L;
      a.created = x.id;
      a.maybe = x.maybe;
      a.rotational = (L == 'A' || L == 'B' || L == 'C' || L == 'D');
      if (r.known()) a.rotational = r.value == 1;
      s.axes.push_back(a);
      idx = static_cast<int>(s.axes.size()) - 1;
      s.visible_axes = static_cast<int>(s.axes.size());
      s.visible_set = x.id;
      if (s.axes.size() + static_cast<size_t>(s.extruders) > static_cast<size_t>(lim.max_axes_plus_extruders) &&
          s.extruders > 0)
        --s.extruders;
    }
    Axis& a = s.axes[static_cast<size_t>(idx)];
    if (drivers.known()) a.drivers = drivers.value;
    else a.drivers.clear();
    a.drivers_set = x.id;
  }
  if (x.pf.find(x.c, 'E')) {
    auto e = get_driver_list(x.pf, x.c, 'E');
    if (e.known() && !x.maybe) {
      s.extruders = static_cast<int>(e.value.size());
      s.extruder_drivers = e.value;
      s.extruders_known = true;
    } else {
      s.extruders_known = false;
    }
    s.extruders_set = x.id;
  }
  if (x.pf.find(x.c, 'P')) {
    auto p = get_int(x.pf, x.c, 'P');
    if (p.known() && !x.maybe && p.value >= 2 && p.value <= static_cast<int64_t>(s.axes.size())) {
      s.visible_axes = static_cast<int>(p.value);
      s.visible_set = x.id;
    } else if (!p.known() || x.maybe) {
      s.axes_known = false;
    }
  }
}

AxisMap read_map(Cx& x, char letter, bool& bad) {
  const M563Map given = m563_map(x.pf, x.c, x.s, letter);
  AxisMap m;
  m.bits = given.bits;
  if (!given.given) return m;
  m.origin = x.id;
  if (!given.known || x.maybe) {
    m.known = false;
    m.bits = 0;
    return m;
  }
  if (given.indices.size() > static_cast<size_t>(x.s.visible_axes)) bad = true;  // array too long: exception
  if (!x.s.axes_known) m.known = false;
  return m;
}

// Is the list exactly "-1" (M563 D-1 H-1 deletes a tool)?
bool just_minus_one(const std::vector<int64_t>& v) { return v.size() == 1 && v[0] == -1; }

void do_m563(Cx& x) {
  MachineState& s = x.s;
  auto P = get_int(x.pf, x.c, 'P');
  if (!m563_defines(x.pf, x.c) || P.absent()) return;
  if (!P.known()) {
    s.tools_known = false;
    return;
  }
  const int n = static_cast<int>(P.value);
  if (n < 0 || (s.firmware >= kRrf3_1 && n >= 50)) return;  // parameter 'P' too high
  auto D = get_int_list(x.pf, x.c, 'D');
  auto H = get_int_list(x.pf, x.c, 'H');
  // Deleting: D-1 H-1.
  if (D.known() && H.known() && just_minus_one(D.value) && just_minus_one(H.value) && !x.pf.find(x.c, 'R')) {
    if (x.maybe) {
      if (auto it = s.tools.find(n); it != s.tools.end()) it->second.maybe = true;
    } else {
      s.tools.erase(n);
    }
    return;
  }
  bool bad = false;
  Tool t;
  t.number = n;
  t.created = x.id;
  t.maybe = x.maybe;
  t.xmap = read_map(x, 'X', bad);
  t.ymap = read_map(x, 'Y', bad);
  if (has_z_map(s.firmware)) t.zmap = read_map(x, 'Z', bad);
  else t.zmap.bits = 1u << 2;
  if (t.xmap.known && t.ymap.known && t.zmap.known &&
      ((t.xmap.bits & t.ymap.bits) || (t.xmap.bits & t.zmap.bits) || (t.ymap.bits & t.zmap.bits)))
    bad = true;  // Cannot map two or more of X,Y,Z to the same axis: the old tool survives
  if (bad && !x.maybe) return;
  if (auto nm = get_string(x.pf, x.c, 'S'); nm.known()) t.name = nm.value;
  t.has_d = D.present();
  t.has_h = H.present();
  t.drives_known = !D.present() || D.known();
  t.heaters_known = !H.present() || H.known();
  if (D.known()) t.drives = D.value;
  if (H.known()) t.heaters = H.value;
  if (auto F = get_int_list(x.pf, x.c, 'F'); F.known()) t.fans = F.value;
  t.spindle = x.pf.find(x.c, 'R') != nullptr;
  // Redefinition deletes the old tool first (deselecting it).
  if (!x.maybe) {
    s.tools.erase(n);
    if (s.current_tool == n) s.current_tool = kNoTool;
  }
  // Creation checks after the deletion: bad drive / heater number leaves no tool at all.
  bool failed = false;
  if (D.known())
    for (int64_t d : D.value)
      if (d < 0 || (s.extruders_known && d >= s.extruders)) failed = true;
  if (H.known())
    for (int64_t h : H.value)
      if (h < 0 && !(D.known() && just_minus_one(D.value) && h == -1)) failed = true;
  if (failed && !x.maybe) {
    s.failed_tools[n] = x.id;
    return;
  }
  s.failed_tools.erase(n);
  for (int64_t h : t.heaters) install_tool_heater_defaults(s, static_cast<int>(h), x.id, x.maybe);
  if (x.maybe && s.tools.count(n)) t.maybe = true;
  s.tools[n] = std::move(t);
}

/// The tool a G10 / M568 sets, or nullptr when it is unknown or does not exist (`Invalid tool number`).
Tool* addressed(Cx& x) {
  const ToolRef ref = addressed_tool(x.pf, x.c, x.s);
  if (!ref.known) return nullptr;
  auto it = x.s.tools.find(ref.number);
  return it == x.s.tools.end() ? nullptr : &it->second;
}

void set_temps(Cx& x, Tool& t) {
  for (char L : {'R', 'S'}) {  // RRF sets standby first, then active
    if (!x.pf.find(x.c, L)) continue;
    auto v = get_float_list(x.pf, x.c, L);
    std::vector<double>& dst = L == 'S' ? t.active : t.standby;
    if (!v.known() || x.maybe) {
      t.temps_known = false;
      continue;
    }
    // A value at or above a heater's limit throws `Requested temperature out of range`: nothing more is set.
    for (size_t i = 0; i < t.heaters.size(); ++i) {
      const double value = v.value.size() == 1 ? v.value[0] : (i < v.value.size() ? v.value[i] : -1000);
      auto h = x.s.heaters.find(static_cast<int>(t.heaters[i]));
      if (value > -273 && h != x.s.heaters.end() && h->second.monitor_installed && value >= h->second.limit) return;
    }
    dst = v.value;
    if (dst.size() == 1 && t.heaters.size() > 1) dst.resize(t.heaters.size(), dst[0]);
  }
}

void set_workplace(Cx& x) {
  MachineState& s = x.s;
  auto L = get_int(x.pf, x.c, 'L');
  if (L.value == 20) return;  // relative to the unknown current position
  auto P = get_int(x.pf, x.c, 'P');
  int slot = P.known() ? static_cast<int>(P.value) : (P.absent() ? 1 : -1);
  if (slot == 0) slot = 1;
  if (slot < 1 || slot > 9) return;
  for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i) {
    auto v = get_float(x.pf, x.c, s.axes[static_cast<size_t>(i)].letter);
    if (v.present())
      s.workplaces[static_cast<size_t>(slot)].origin[static_cast<size_t>(i)] =
          Fact{v.known() ? v.value : 0, v.known() && !x.maybe, x.id};
  }
}

void set_tool_offsets(Cx& x, Tool& t) {
  MachineState& s = x.s;
  for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i) {
    auto v = get_float(x.pf, x.c, s.axes[static_cast<size_t>(i)].letter);
    if (!v.present()) continue;
    t.offsets[static_cast<size_t>(i)] = Fact{v.known() ? v.value : 0, v.known() && !x.maybe, x.id};
    t.probed[static_cast<size_t>(i)] = s.running_m501;
  }
}

void do_g10(Cx& x) {
  const G10Form form = g10_form(x.pf, x.c, &x.s, x.s.firmware);
  if (form == G10Form::Workplace) return set_workplace(x);
  if (form == G10Form::Unknown) {
    // It may be the tool form: whatever it names of the addressed tool becomes unknown.
    Cx maybe{x.s, x.pf, x.c, x.id, true};
    if (Tool* t = addressed(maybe)) {
      set_tool_offsets(maybe, *t);
      if (!t->heaters.empty()) set_temps(maybe, *t);
    }
    return;
  }
  if (!is_tool_form(form)) return;  // firmware retraction, or a bad L
  Tool* t = addressed(x);
  if (!t) return;  // Invalid tool number: nothing set
  set_tool_offsets(x, *t);
  if (!t->heaters.empty()) set_temps(x, *t);
  t->last_configured = x.id;
}

void do_m568(Cx& x) {
  if (x.s.firmware < kRrf3_3) return;  // "The M568 command is no longer needed"
  Tool* t = addressed(x);
  if (!t) return;
  if (!t->heaters.empty()) set_temps(x, *t);
  t->last_configured = x.id;
}

void do_tool_touch(Cx& x) {  // M567 / M207 P
  auto P = get_int(x.pf, x.c, 'P');
  if (!P.known()) return;
  auto it = x.s.tools.find(static_cast<int>(P.value));
  if (it != x.s.tools.end()) it->second.last_configured = x.id;
}

void do_m950(Cx& x) {
  MachineState& s = x.s;
  auto pin = get_string(x.pf, x.c, 'C');
  const bool nil = pin.known() && to_lower(pin.value) == "nil";
  auto device = [&](char L, auto& map, bool& known_flag, auto make) {
    auto v = get_int(x.pf, x.c, L);
    if (!v.known()) {
      known_flag = false;
      return;
    }
    int n = static_cast<int>(v.value);
    if (nil && !x.maybe) {
      map.erase(n);
      return;
    }
    if (!pin.present()) return;  // reconfiguring or reporting an existing device
    auto d = make();
    d.created = x.id;
    d.maybe = x.maybe || !pin.known();
    map[n] = d;
  };
  // Exactly one device letter (m950_device); J, P, S, R, D and E are the ports' (model_devices.cc).
  const char letter = m950_device(x.pf, x.c, s.firmware, s.board);
  if (letter == 'H')
    device('H', s.heaters, s.heaters_known, [&] {
      Heater h;
      if (auto t = get_int(x.pf, x.c, 'T'); t.known()) h.sensor = static_cast<int>(t.value);
      return h;
    });
  else if (letter == 'F') device('F', s.fans, s.fans_known, [] { return Fan{}; });
}

void do_m308(Cx& x) {
  auto S = get_int(x.pf, x.c, 'S');
  if (!S.present()) return;
  if (!S.known()) {
    x.s.sensors_known = false;
    return;
  }
  auto Y = get_string(x.pf, x.c, 'Y');
  if (!Y.present()) return;  // configuring an existing sensor
  Sensor sn;
  sn.created = x.id;
  sn.maybe = x.maybe;
  if (Y.known()) sn.type = Y.value;
  x.s.sensors[static_cast<int>(S.value)] = sn;
}

void do_m140(Cx& x, bool bed) {
  auto H = get_int_list(x.pf, x.c, 'H');
  if (!H.known() || H.value.empty()) return;
  for (int64_t h : H.value) {
    if (h < 0) continue;
    if (bed && h == H.value.front()) x.s.bed_heater = static_cast<int>(h);
    install_bed_heater_defaults(x.s, static_cast<int>(h), x.id, x.maybe);
  }
}

void do_m143(Cx& x) {
  auto H = get_int(x.pf, x.c, 'H');
  int h = H.known() ? static_cast<int>(H.value) : (H.absent() ? 1 : -1);
  if (h < 0) return;
  auto it = x.s.heaters.find(h);
  if (it == x.s.heaters.end()) return;  // Heater n does not exist
  auto S = get_float(x.pf, x.c, 'S');
  auto A = get_int(x.pf, x.c, 'A');  // action; A0 = fault; the limit matters for any action
  (void)A;
  auto C = get_int(x.pf, x.c, 'C');  // condition: 0 (default) temperature exceeded, 1 too low, -1 disabled
  auto P = get_int(x.pf, x.c, 'P');  // monitor index 0–2
  if (!S.present() && !C.present()) return;
  Heater& ht = it->second;
  ht.user_monitor = true;
  ht.monitor_origin = x.id;
  if (x.maybe || (S.present() && !S.known()) || (C.present() && !C.known()) || (P.present() && !P.known())) {
    for (double& l : ht.monitor_limits) l = std::max(l, 2000.0);  // unknown: no rule may rely on a limit
  } else if (const int64_t i = P.known() ? P.value : 0; i >= 0 && i < 3) {
    double& l = ht.monitor_limits[static_cast<size_t>(i)];
    if (C.known() && C.value != 0) l = -1;
    else l = S.known() ? S.value : (l >= 0 ? l : 2000.0);
  }
  update_limit(ht);
}

void do_m558(Cx& x) {
  if (!x.pf.find(x.c, 'P')) return;  // C without P: "Missing Z probe type number" (EndstopsManager.cpp)
  auto K = get_int(x.pf, x.c, 'K');
  int k = K.known() ? static_cast<int>(K.value) : (K.absent() ? 0 : -1);
  if (k < 0) {
    x.s.probes_known = false;
    return;
  }
  auto P = get_int(x.pf, x.c, 'P');
  // RRF 3 rejects RRF 2's endstop-input probe types before it creates a probe (RRF121 replaced-command).
  if (x.s.firmware >= kRrf3_0 && P.known() && (P.value == 4 || P.value == 6 || P.value == 7)) return;
  Probe p;
  p.created = x.id;
  p.maybe = x.maybe;
  if (P.known()) p.type = static_cast<int>(P.value);
  x.s.probes[k] = p;
}

void do_kinematics(Cx& x) {
  MachineState& s = x.s;
  const std::optional<int> k = kinematics_set_by(x.pf, x.c, s.firmware);
  if (!k) return;
  if (*k < 0 || x.maybe) s.kinematics_known = false;
  else s.kinematics = *k;
  s.kinematics_set = x.id;
}

// M585 measures the current tool's offset on the first visible axis it names (GCodes6.cpp `ProbeTool()`): the
// value is unknown and flagged probed. With the current tool unknown, any tool may have been measured.
void do_m585(Cx& x) {
  MachineState& s = x.s;
  const int axis = m585_axis(x.pf, x.c, s);
  if (axis < 0 || axis >= kMaxAxisSlots) return;
  auto measure = [&](Tool& t) {
    t.offsets[static_cast<size_t>(axis)] = Fact{0, false, x.id};
    t.probed[static_cast<size_t>(axis)] = true;
  };
  if (s.current_tool_known) {
    if (auto it = s.tools.find(s.current_tool); it != s.tools.end()) measure(it->second);
    return;  // no tool selected: `No tool selected!`
  }
  for (auto& [n, t] : s.tools) measure(t);
}

}  // namespace

std::string_view allowed_axis_letters() { return kAxisOrder; }

void interpret_command(MachineState& s, const ParsedFile& pf, const Command& c, NodeId id, bool maybe) {
  Cx x{s, pf, c, id, maybe};
  if (c.letter == 'G') {
    if (c.number == 31) return interpret_device_command(x);
    return do_g10(x);
  }
  apply_pin_changes(s, pin_changes(pf, c, s), id, maybe);
  interpret_device_command(x);
  interpret_motion_command(x);
  switch (c.number) {
    case 584: do_m584(x); break;
    case 563: do_m563(x); break;
    case 568: do_m568(x); break;
    case 567:
    case 207: do_tool_touch(x); break;
    case 950: do_m950(x); break;
    case 308: do_m308(x); break;
    case 140: do_m140(x, true); break;
    case 141: do_m140(x, false); break;
    case 143: do_m143(x); break;
    case 307: {
      auto H = get_int(x.pf, x.c, 'H');
      if (H.known())
        if (auto it = s.heaters.find(static_cast<int>(H.value)); it != s.heaters.end()) it->second.model_set = true;
      break;
    }
    case 558: do_m558(x); break;
    case 585: do_m585(x); break;
    case 98: {
      // A macro whose path is an expression may do anything: what it could create is unknown from here on.
      // Only a '{' makes the path unknown: most M98 lines have none and need no parameter lexing.
      const bool braces = x.pf.text(x.c.span).find('{') != std::string_view::npos;
      ParamRef P = braces ? x.pf.find(x.c, 'P') : ParamRef();
      if (P && is_unknown_string(*P)) {
        s.tools_known = s.axes_known = s.heaters_known = s.fans_known = s.sensors_known = s.probes_known = false;
        s.extruders_known = false;
        s.ports_known = s.filament_monitors_known = s.pins_known = false;
      }
      break;
    }
    case 451: s.mode = MachineMode::FFF, s.mode_set = id; break;
    case 452: s.mode = MachineMode::Laser, s.mode_set = id; break;
    case 453: s.mode = MachineMode::CNC, s.mode_set = id; break;
    case 669:
    case 667:
    case 665: do_kinematics(x); break;
    default: break;
  }
}

}  // namespace rrflint
