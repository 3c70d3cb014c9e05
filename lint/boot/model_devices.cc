// The machine model's reading of the device commands beyond creation (docs/firmware-behaviour.md): every heater
// monitor slot (M143), M301 PID values, M570 fault detection, fan thermostats (M106 H/T), the M950 ports that are
// not heaters or fans and the commands that use them (M42, M280, M581, M453), M591 filament monitors and G31.
#include <algorithm>

#include "lint/boot/commands.h"
#include "lint/boot/model.h"
#include "lint/boot/model_commands.h"

namespace rrflint {

bool read_fact(CommandCx& x, char letter, Fact& f) {
  auto v = get_float(x.pf, x.c, letter);
  if (!v.present()) return false;
  f = Fact{v.known() ? v.value : 0, v.known() && !x.maybe, x.id};
  return true;
}

void install_default_monitor(Heater& h, double limit, NodeId id, bool maybe) {
  if (h.slots_set_by_user) return;  // monitorsSetByUser
  MonitorSlot& m = h.monitors[0];
  m = MonitorSlot{};
  m.limit = Fact{limit, !maybe, id};
  m.action = Fact{0, !maybe, id};
  m.condition = Fact{0, !maybe, id};
  m.sensor = Fact{static_cast<double>(h.sensor), h.sensor >= 0 && !maybe, id};
  m.set = id;
  m.maybe = maybe;
  h.default_monitor = id;
  h.default_monitor_maybe = maybe;
}

namespace {

/// The heater an M143 / M301 / M570 names: H, or `fallback` without one (-1: H is required); nullptr when unknown
/// or absent (`Heater n not found`).
Heater* named_heater(CommandCx& x, int fallback) {
  auto H = get_int(x.pf, x.c, 'H');
  const int h = H.known() ? static_cast<int>(H.value) : (H.absent() ? fallback : -1);
  if (h < 0) return nullptr;
  auto it = x.s.heaters.find(h);
  return it == x.s.heaters.end() ? nullptr : &it->second;
}

// Heater::ConfigureMonitor: any of T, S, A, C sets slot P (default 0); the omitted ones take RRF's defaults.
void monitor_slots(CommandCx& x) {
  Heater* h = named_heater(x, 1);
  if (!h) return;
  const bool any = x.pf.find(x.c, 'T') || x.pf.find(x.c, 'S') || x.pf.find(x.c, 'A') || x.pf.find(x.c, 'C');
  if (!any) return;  // a report
  auto P = get_int(x.pf, x.c, 'P');
  if (P.known() && (P.value < 0 || P.value > 2)) return;                         // parameter 'P' too high
  if (auto S = get_float(x.pf, x.c, 'S'); S.known() && S.value >= 2000) return;  // BadErrorTemperature: invalid
  auto set_slot = [&](MonitorSlot& m, bool unsure) {
    CommandCx y{x.s, x.pf, x.c, x.id, x.maybe || unsure};
    const auto fixed = [&](double v) { return Fact{v, !y.maybe, x.id}; };
    if (!read_fact(y, 'T', m.sensor)) m.sensor = Fact{static_cast<double>(h->sensor), h->sensor >= 0 && !y.maybe, x.id};
    if (!read_fact(y, 'A', m.action)) m.action = fixed(0);
    if (!read_fact(y, 'C', m.condition)) m.condition = fixed(0);
    if (!read_fact(y, 'S', m.limit)) m.limit = Fact{m.limit.value, m.limit.known && !y.maybe, x.id};
    m.set = x.id;
    m.maybe = x.maybe;
  };
  if (!x.maybe) h->slots_set_by_user = true;  // (inside an `if`, a later default may or may not be installed)
  if (P.known() || P.absent()) set_slot(h->monitors[static_cast<size_t>(P.known() ? P.value : 0)], false);
  else
    for (MonitorSlot& m : h->monitors) set_slot(m, true);  // P from an expression: any slot may have changed
}

void pid(CommandCx& x) {
  Heater* h = named_heater(x, 1);  // M301 without H: heater 1 (GCodes2.cpp)
  if (!h) return;
  bool any = read_fact(x, 'P', h->pid.p);
  any = read_fact(x, 'I', h->pid.i) || any;
  any = read_fact(x, 'D', h->pid.d) || any;
  if (any) h->pid.set = x.id;
}

void fault_detection(CommandCx& x) {
  Heater* h = named_heater(x, -1);  // M570 must see H
  if (!h) return;
  FaultDetection& f = h->fault;
  bool any = read_fact(x, 'P', f.time);
  any = read_fact(x, 'T', f.excursion) || any;
  any = read_fact(x, 'R', f.bad_readings) || any;
  any = read_fact(x, 'S', f.timeout) || any;
  if (any) f.set = x.id;
}

// M106 P<fan> H<sensors> T<threshold[:high]>: H-1 (or any negative number) turns the thermostat off.
void fan_thermostat(CommandCx& x) {
  auto P = get_int(x.pf, x.c, 'P');
  if (!P.known()) return;  // without P: the current tool's print cooling fan, no thermostat
  auto it = x.s.fans.find(static_cast<int>(P.value));
  if (it == x.s.fans.end()) return;  // Fan number n not found
  Fan& f = it->second;
  auto H = get_int_list(x.pf, x.c, 'H');
  auto T = get_float_list(x.pf, x.c, 'T');
  if (!H.present() && !T.present()) return;
  if (H.present()) {
    f.sensors.clear();
    if (H.known())
      for (int64_t sn : H.value)
        if (sn >= 0) f.sensors.push_back(sn);
    f.thermostatic = !f.sensors.empty();
    if (!H.known() || x.maybe) f.thermostat_known = false;
  }
  if (T.present()) {
    if (T.known()) f.thresholds = T.value;
    if (!T.known() || x.maybe) f.thermostat_known = false;
  }
  f.thermostat_set = x.id;
}

std::string pin_text(const Val<std::string>& pin) { return pin.known() ? pin.value : std::string("?"); }

// M950 with exactly one device letter (Platform::ConfigurePort): J, P, S or R (3.3+) here; H and F elsewhere.
void m950_port(CommandCx& x) {
  const char which = m950_device(x.pf, x.c, x.s.firmware, x.s.board);
  if (!which || std::string_view("JPSR").find(which) == std::string_view::npos) return;
  const PortKind kind = which == 'J'   ? PortKind::GpioIn
                        : which == 'P' ? PortKind::GpioOut
                        : which == 'S' ? PortKind::Servo
                                       : PortKind::Spindle;
  auto n = get_int(x.pf, x.c, which);
  if (!n.known()) {
    x.s.ports_known = false;
    return;
  }
  auto pin = get_string(x.pf, x.c, 'C');
  if (!pin.present()) return;  // reconfiguring or reporting an existing port
  auto& ports = x.s.ports[static_cast<size_t>(kind)];
  const int port = static_cast<int>(n.value);
  if (pin.known() && to_lower(pin.value) == "nil") {
    if (!x.maybe) ports.erase(port);
    return;
  }
  ports[port] = Port{pin_text(pin), x.id, x.maybe || !pin.known()};
}

void port_use(CommandCx& x, PortKind kind, char letter) {
  auto P = get_int(x.pf, x.c, letter);
  if (!P.present()) return;
  x.s.port_uses.push_back(PortUse{kind, P.known() ? static_cast<int>(P.value) : -1, x.id, x.maybe});
}

void trigger(CommandCx& x) {
  auto T = get_int(x.pf, x.c, 'T');
  if (!T.known() || T.value < 0) return;
  Trigger& t = x.s.triggers[static_cast<int>(T.value)];
  bool seen = read_fact(x, 'R', t.condition);
  auto S = get_int(x.pf, x.c, 'S');
  auto P = get_int_list(x.pf, x.c, 'P');
  if (P.present()) {
    seen = true;
    if (!P.known() || S.unknown()) {
      t.ports_known = false;
    } else if (P.value.size() == 1 && P.value[0] == -1) {
      if (!x.maybe) t.rising.clear(), t.falling.clear();
      else t.ports_known = false;
    } else {
      const int64_t edge = S.known() ? S.value : 1;
      for (int64_t p : P.value) {
        std::erase(t.rising, p);
        std::erase(t.falling, p);
        if (edge >= 1) t.rising.push_back(p);
        else if (edge == 0) t.falling.push_back(p);
        x.s.port_uses.push_back(PortUse{PortKind::GpioIn, static_cast<int>(p), x.id, x.maybe});
      }
      if (x.maybe) t.ports_known = false;
    }
  }
  if (!seen) return;
  t.set = x.id;
  t.maybe = t.maybe || x.maybe;
}

// M591 D<extruder> P<type> C<pin>: P0 removes the monitor; no P configures the one there.
void filament_monitor(CommandCx& x) {
  auto D = get_int(x.pf, x.c, 'D');
  if (!D.present()) return;
  if (!D.known()) {
    x.s.filament_monitors_known = false;
    return;
  }
  auto P = get_int(x.pf, x.c, 'P');
  if (!P.present()) return;
  const int e = static_cast<int>(D.value);
  if (P.known() && P.value == 0) {
    if (!x.maybe) x.s.filament_monitors.erase(e);
    return;
  }
  FilamentMonitor m;
  read_fact(x, 'P', m.type);
  if (auto C = get_string(x.pf, x.c, 'C'); C.present()) m.pin = pin_text(C);
  m.created = x.id;
  m.maybe = x.maybe;
  x.s.filament_monitors[e] = m;
}

// G31 K<probe> Z<trigger height> X Y<offsets>: the probe must exist (`invalid Z probe index`).
void g31(CommandCx& x) {
  auto K = get_int(x.pf, x.c, 'K');
  if (!K.known() && !K.absent()) return;
  auto it = x.s.probes.find(K.known() ? static_cast<int>(K.value) : 0);
  if (it == x.s.probes.end()) return;
  Probe& p = it->second;
  bool any = read_fact(x, 'Z', p.trigger_height);
  any = read_fact(x, 'X', p.x_offset) || any;
  any = read_fact(x, 'Y', p.y_offset) || any;
  if (any) p.g31 = x.id;
}

}  // namespace

void interpret_device_command(CommandCx& x) {
  if (x.c.letter == 'G') return g31(x);
  switch (x.c.number) {
    case 143: monitor_slots(x); break;
    case 301: pid(x); break;
    case 570: fault_detection(x); break;
    case 106: fan_thermostat(x); break;
    case 950: m950_port(x); break;
    case 42: port_use(x, PortKind::GpioOut, 'P'); break;
    case 280: port_use(x, PortKind::Servo, 'P'); break;
    case 581: trigger(x); break;
    case 453:  // 3.3+: spindles are M950 R ports and M453 S fails; before, M453 configured spindle S (default 0)
      if (x.s.firmware < kRrf3_3 && x.pf.find(x.c, 'C')) {
        auto S = get_int(x.pf, x.c, 'S');
        x.s.port_uses.push_back(
            PortUse{PortKind::Spindle, S.known() ? static_cast<int>(S.value) : (S.absent() ? 0 : -1), x.id, x.maybe});
      }
      break;
    case 591: filament_monitor(x); break;
    default: break;
  }
}

}  // namespace rrflint
