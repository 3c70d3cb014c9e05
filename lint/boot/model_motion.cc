// The machine model's reading of the motion commands beyond M584 (docs/firmware-behaviour.md): steps/mm (M92) and
// microstepping (M350, with RRF's rescaling of steps/mm), endstops (M574), leadscrews (M671) and the parameters of
// the kinematics (M665/M667/M669), which a change of kinematics type drops (Move::SetKinematics).
#include <algorithm>
#include <bit>

#include "lint/boot/commands.h"
#include "lint/boot/model.h"
#include "lint/boot/model_commands.h"

namespace rrflint {

std::vector<DriverUse> MachineState::driver_uses() const {
  std::vector<DriverUse> out;
  for (size_t i = 0; i < axes.size(); ++i)
    for (DriverId d : axes[i].drivers) out.push_back(DriverUse{d, false, static_cast<int>(i)});
  for (size_t e = 0; e < extruder_drivers.size(); ++e)
    out.push_back(DriverUse{extruder_drivers[e], true, static_cast<int>(e)});
  return out;
}

bool MachineState::driver_shared(DriverId d) const {
  int users = 0;
  for (const DriverUse& u : driver_uses())
    if (u.driver == d) ++users;
  return users > 1;
}

namespace {

/// Microstepping RRF accepts: a power of two up to 256 (the drivers may accept less; unknown here).
bool valid_microstepping(int64_t u) { return u >= 1 && u <= 256 && std::has_single_bit(static_cast<uint64_t>(u)); }

// Platform::SetDriveStepsPerUnit: a value given for microstepping S is converted to the current microstepping.
void set_steps(CommandCx& x, DriveSettings& d, Val<double> v, Val<int64_t> S) {
  const bool convert = S.present() && (!S.known() || S.value != 0);
  double value = v.known() ? v.value : 0;
  bool known = v.known() && !x.maybe;
  if (convert) {
    known = known && S.known() && d.microsteps.known;
    if (known && S.value != static_cast<int64_t>(d.microsteps.value))
      value *= d.microsteps.value / static_cast<double>(S.value);
  }
  d.steps = Fact{value, known, x.id};
  d.steps_rescaled = kNoNode;
}

void m92(CommandCx& x) {
  MachineState& s = x.s;
  auto S = get_int(x.pf, x.c, 'S');
  for (Axis& a : s.axes)  // every axis, hidden ones too
    if (auto v = get_float(x.pf, x.c, a.letter); v.present()) set_steps(x, a.drive, v, S);
  auto E = get_float_list(x.pf, x.c, 'E');
  if (!E.present()) return;
  const size_t count = s.extruders_known ? static_cast<size_t>(std::max(s.extruders, 0)) : kMaxAxisSlots;
  if (E.known() && s.extruders_known && E.value.size() > count) return;  // array too long: no E value is set
  for (size_t e = 0; e < count && e < kMaxAxisSlots; ++e) {
    if (E.known() && E.value.size() > 1 && e >= E.value.size()) break;
    Val<double> v{E.state, E.known() ? E.value[std::min(e, E.value.size() - 1)] : 0, {}};
    if (!s.extruders_known) v.state = VState::Unknown;  // a list longer than the extruders fails
    set_steps(x, s.extruder_drive[e], v, S);
  }
}

// GCodes::ChangeMicrostepping: a valid new value that differs from the old one rescales steps/mm by new/old.
void set_microstepping(CommandCx& x, DriveSettings& d, Val<int64_t> u, Val<int64_t> I) {
  if (u.known() && !valid_microstepping(u.value)) return;  // rejected: nothing changes
  const bool sure = u.known() && !x.maybe;
  if (!sure || !d.microsteps.known) {
    d.microsteps = Fact{u.known() ? static_cast<double>(u.value) : 0, false, x.id};
    d.steps.known = false;
    d.steps_rescaled = x.id;
  } else {
    const double old = d.microsteps.value, now = static_cast<double>(u.value);
    if (now != old) {
      d.steps.value *= now / old;
      d.steps_rescaled = x.id;
    }
    d.microsteps = Fact{now, true, x.id};
  }
  d.interpolation = I.known() && I.value > 0;  // I omitted: no interpolation
  d.interpolation_known = !I.unknown() && !x.maybe;
  d.interpolation_set = x.id;
}

void m350(CommandCx& x) {
  MachineState& s = x.s;
  auto I = get_int(x.pf, x.c, 'I');
  for (Axis& a : s.axes)
    if (auto u = get_int(x.pf, x.c, a.letter); u.present()) set_microstepping(x, a.drive, u, I);
  auto E = get_int_list(x.pf, x.c, 'E');
  if (!E.present()) return;
  const size_t count = s.extruders_known ? static_cast<size_t>(std::max(s.extruders, 0)) : kMaxAxisSlots;
  if (E.known() && s.extruders_known && E.value.size() > count) return;
  for (size_t e = 0; e < count && e < kMaxAxisSlots; ++e) {
    if (E.known() && E.value.size() > 1 && e >= E.value.size()) break;
    Val<int64_t> u{E.state, E.known() ? E.value[std::min(e, E.value.size() - 1)] : 0, {}};
    if (u.known() && u.value < 0) continue;  // negative values are ignored
    if (!s.extruders_known) u.state = VState::Unknown;
    set_microstepping(x, s.extruder_drive[e], u, I);
  }
}

// M574 X1 S1 P"xstop" (EndstopsManager::HandleM574): the axes named get an endstop position and type (S omitted:
// 1, a switch); P gives the pins, a switch without P keeps the old ones, position 0 or another type drops them.
// S0 on RRF 3 is an error and sets nothing.
void m574(CommandCx& x) {
  // RRF 3 rejects type 0 (RRF 2's active-low switch) before it changes anything (RRF121 replaced-command).
  if (auto S = get_int(x.pf, x.c, 'S'); x.s.firmware >= kRrf3_0 && S.known() && S.value == 0) return;
  auto P = get_string(x.pf, x.c, 'P');
  for (Axis& a : x.s.axes) {
    if (!x.pf.find(x.c, a.letter)) continue;
    Axis::Endstop& e = a.endstop;
    read_fact(x, a.letter, e.position);
    if (!read_fact(x, 'S', e.type)) e.type = Fact{1, !x.maybe, x.id};
    if (P.present()) e.pins = P.known() ? P.value : "?";
    else if ((e.position.known && e.position.value == 0) || (e.type.known && e.type.value != 1)) e.pins.clear();
    e.set = x.id;
    e.maybe = x.maybe;
  }
}

void m671(CommandCx& x) {
  M671Read r = m671_read(x.pf, x.c);
  if (r.form != M671Form::Set && r.form != M671Form::Unknown) return;  // a report, S/P/F alone, or refused
  Leadscrews& l = x.s.leadscrews;
  l = Leadscrews{};
  l.x = std::move(r.x);  // empty when Unknown
  l.y = std::move(r.y);
  l.known = r.form == M671Form::Set && !x.maybe;
  l.set = x.id;
}

// M665/M667/M669: a new kinematics type replaces the kinematics object (its parameters and the M671 leadscrews);
// the same type keeps it. The type itself is the main reading's (kinematics_set_by, in model_commands.cc).
void kinematics(CommandCx& x) {
  MachineState& s = x.s;
  const std::optional<int> k = kinematics_set_by(x.pf, x.c, s.firmware);
  if (k) {
    const bool certain = *k >= 0 && !x.maybe && s.kinematics_known;
    const bool changes = *k < 0 || !s.kinematics_known || *k != s.kinematics;
    if (changes) {
      if (s.leadscrews.set != kNoNode && (s.leadscrews.dropped == kNoNode || s.leadscrews.dropped_maybe)) {
        s.leadscrews.dropped = x.id;
        s.leadscrews.dropped_maybe = !certain;
      }
      if (certain) s.kinematics_params.clear();
    }
  }
  const std::string code = "M" + std::to_string(x.c.number) + " ";
  for (const Param& p : x.pf.params(x.c)) {
    if (p.letter == 0 || (x.c.number == 669 && p.letter == 'K')) continue;
    if (p.kind == ValueKind::String || p.kind == ValueKind::Text || p.kind == ValueKind::List) continue;
    Fact f;
    if (read_fact(x, p.letter, f)) s.kinematics_params[code + p.letter] = f;
  }
}

}  // namespace

void interpret_motion_command(CommandCx& x) {
  switch (x.c.number) {
    case 92: m92(x); break;
    case 350: m350(x); break;
    case 574: m574(x); break;
    case 671: m671(x); break;
    case 665:
    case 667:
    case 669: kinematics(x); break;
    default: break;
  }
}

}  // namespace rrflint
