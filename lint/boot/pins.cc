// The pins a command takes and gives back (docs/firmware-behaviour.md#pins), as RRF 3 allocates them: every
// device that uses a pin asks IoPort::AssignPorts for it, which first gives back the pins that device held, then
// takes the new ones, all or none. A pin another device holds is refused ("Pin 'x' is not free"). Pins are looked
// up by name after GCodeBuffer::GetReducedString (lower case, no '_' or '-') with the '!', '^' and '*' flags and the
// "<board>." prefix taken off (IoPort::RemoveBoardAddress, IoPort::Allocate). A pin has aliases on some boards
// ("out9" is also "laser" on a 6HC); only the names are compared here, so two aliases of one pin are not seen.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "lint/boot/commands.h"

namespace rrflint {

namespace {

/// pin_name(), and the board as written ("" without a "<board>." prefix).
PinName parse_pin(std::string_view written, std::string_view& board) {
  std::string_view s = written;
  auto skip_flags = [&] {
    while (!s.empty() && (s.front() == '!' || s.front() == '^' || s.front() == '*')) s.remove_prefix(1);
  };
  skip_flags();
  board = {};
  size_t digits = 0;
  while (digits < s.size() && std::isdigit(static_cast<unsigned char>(s[digits]))) ++digits;
  if (digits > 0 && digits < s.size() && s[digits] == '.') {
    const size_t zeros = std::min(s.find_first_not_of('0'), digits - 1);  // "00." is board 0
    board = s.substr(zeros, digits - zeros);
    s.remove_prefix(digits + 1);
    skip_flags();
  }
  PinName p;
  p.written = std::string(written);
  p.key.reserve((board.empty() ? 1 : board.size()) + 1 + s.size());
  p.key += board.empty() ? std::string_view("0") : board;
  p.key += '.';
  const size_t name_at = p.key.size();
  for (char ch : s)
    if (ch != '_' && ch != '-') p.key += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const std::string_view name = std::string_view(p.key).substr(name_at);
  if (name.empty() || name == "nil") p.key.clear();
  return p;
}

/// The pins of a "+"-separated list; a pin without a board prefix after the first is on the first one's board.
std::vector<PinName> pin_list(std::string_view text) {
  std::vector<PinName> out;
  std::string_view first_board, board;
  for (size_t start = 0; start <= text.size();) {
    const size_t plus = std::min(text.find('+', start), text.size());
    PinName p = parse_pin(text.substr(start, plus - start), board);
    if (!p.key.empty()) {
      if (out.empty()) first_board = board;
      else if (board.empty() && !first_board.empty()) p.key = std::string(first_board) + p.key.substr(p.key.find('.'));
      out.push_back(std::move(p));
    }
    start = plus + 1;
  }
  return out;
}

/// A change for `device` from the string parameter `letter` (nullopt when the command has no such parameter).
std::optional<PinChange> pins_from(const ParsedFile& pf, const Command& c, char letter, PinDevice device) {
  auto v = get_string(pf, c, letter);
  if (!v.present()) return std::nullopt;
  PinChange ch;
  ch.device = device;
  ch.param = v.param;
  if (v.known()) ch.pins = pin_list(v.value);
  else ch.pins_known = false;
  return ch;
}

/// A change by which `device` only gives its pins back (deleted or re-created without pins).
PinChange release_only(PinDevice device) {
  PinChange ch;
  ch.device = device;
  return ch;
}

/// M950 <letter><n> C"pins": exactly one device letter (Platform::ConfigurePort); without C it changes no pin.
void m950(const ParsedFile& pf, const Command& c, const MachineState& s, std::vector<PinChange>& out) {
  using K = PinDevice::Kind;
  static constexpr std::pair<char, K> kDevices[] = {{'D', K::SdCard},  {'E', K::LedStrip}, {'R', K::Spindle},
                                                    {'J', K::GpioIn},  {'F', K::Fan},      {'H', K::Heater},
                                                    {'P', K::GpioOut}, {'S', K::Servo}};
  const char which = m950_device(pf, c, s.firmware, s.board);
  K kind = K::Unknown;
  for (const auto& [L, k] : kDevices)
    if (L == which) kind = k;
  if (kind == K::Unknown || !pf.find(c, 'C')) return;
  auto n = get_int(pf, c, which);
  if (n.known() && n.value < 0) return;
  auto ch = pins_from(pf, c, 'C', n.known() ? PinDevice{kind, n.value} : PinDevice{});
  if (ch) out.push_back(std::move(*ch));
}

/// M308 S<n>: P"nil" deletes the sensor, Y creates a new one (deleting the old), P alone gives an existing one a new
/// pin. P"S<n>.<m>" is another sensor's additional output (a DHT's humidity), not a pin.
void m308(const ParsedFile& pf, const Command& c, const MachineState& s, std::vector<PinChange>& out) {
  auto S = get_int(pf, c, 'S');
  if (!S.present() || (S.known() && S.value < 0)) return;
  const bool create = static_cast<bool>(pf.find(c, 'Y'));
  if (!create && S.known() && s.sensors_known && !s.unknown_baseline && !s.sensors.count(static_cast<int>(S.value)))
    return;  // "Sensor n does not exist"
  const PinDevice device = S.known() ? PinDevice{PinDevice::Kind::Sensor, S.value} : PinDevice{};
  auto P = get_string(pf, c, 'P');
  const bool output_of = P.known() && P.value.size() > 1 &&
                         std::tolower(static_cast<unsigned char>(P.value[0])) == 's' &&
                         std::isdigit(static_cast<unsigned char>(P.value[1]));  // an additional output
  auto ch = output_of ? std::nullopt : pins_from(pf, c, 'P', device);
  if (!ch && create) ch = release_only(device);
  if (ch) out.push_back(std::move(*ch));
}

/// M558 K<n> P<type> C"pins": P deletes the probe and makes a new one on C (EndstopsManager::HandleM558); RRF 3
/// rejects the types 4, 6 and 7 first. C without P is an error.
void m558(const ParsedFile& pf, const Command& c, std::vector<PinChange>& out) {
  auto P = get_int(pf, c, 'P');
  if (!P.present() || (P.known() && (P.value == 4 || P.value == 6 || P.value == 7))) return;
  auto K = get_int(pf, c, 'K');
  if (K.known() && K.value < 0) return;
  const PinDevice device = K.unknown() ? PinDevice{} : PinDevice{PinDevice::Kind::ZProbe, K.known() ? K.value : 0};
  // Types 0 (no probe) and 10 (motor stall) read no pins.
  const bool no_pins = P.known() && (P.value == 0 || P.value == 10);
  auto ch = no_pins ? std::nullopt : pins_from(pf, c, 'C', device);
  if (!ch) ch = release_only(device);
  out.push_back(std::move(*ch));
}

/// M574 <axis><pos> S<type> P"pins" (EndstopsManager::HandleM574): P makes a new switch endstop for the one axis
/// named; without P, position 0 or a type other than 1 deletes the axis's switch endstop, and S1 keeps it.
void m574(const ParsedFile& pf, const Command& c, const MachineState& s, std::vector<PinChange>& out) {
  auto S = get_int(pf, c, 'S');
  if (S.known() && S.value == 0) return;  // RRF 3: "endstop type 0 is no longer supported"
  std::vector<const Axis*> named;
  for (const Axis& a : s.axes)
    if (pf.find(c, a.letter)) named.push_back(&a);
  if (named.empty()) return;
  auto device = [](const Axis& a) { return PinDevice{PinDevice::Kind::Endstop, static_cast<unsigned char>(a.letter)}; };
  if (pf.find(c, 'P')) {
    if (named.size() > 1 || (S.known() && S.value != 1)) return;  // "Invalid use of P parameter"
    if (auto ch = pins_from(pf, c, 'P', device(*named[0]))) out.push_back(std::move(*ch));
    return;
  }
  for (const Axis* a : named) {
    auto pos = get_int(pf, c, a->letter);
    if ((pos.known() && pos.value != 0) && (S.absent() || (S.known() && S.value == 1))) continue;  // keeps its pins
    PinChange ch;
    ch.device = device(*a);
    out.push_back(std::move(ch));
  }
}

/// M591 D<extruder> P<type> C"pin": P deletes the monitor and makes a new one on C; P0 makes none
/// (FilamentMonitor::Configure).
void m591(const ParsedFile& pf, const Command& c, std::vector<PinChange>& out) {
  auto D = get_int(pf, c, 'D');
  if (!D.present() || !pf.find(c, 'P')) return;
  const PinDevice device = D.known() ? PinDevice{PinDevice::Kind::FilamentMonitor, D.value} : PinDevice{};
  auto P = get_int(pf, c, 'P');
  auto ch = P.known() && P.value == 0 ? std::nullopt : pins_from(pf, c, 'C', device);  // P0 only deletes
  if (!ch) ch = release_only(device);
  out.push_back(std::move(*ch));
}

}  // namespace

std::string PinDevice::name() const {
  using K = Kind;
  switch (kind) {
    case K::Unknown: return "a device";
    case K::SdCard: return fmt::format("SD card {}", number);
    case K::LedStrip: return fmt::format("LED strip {}", number);
    case K::Spindle: return fmt::format("spindle {}", number);
    case K::GpioIn: return fmt::format("GPIO input {}", number);
    case K::Fan: return fmt::format("fan {}", number);
    case K::Heater: return fmt::format("heater {}", number);
    case K::GpioOut: return fmt::format("GPIO output {}", number);
    case K::Servo: return fmt::format("servo {}", number);
    case K::Sensor: return fmt::format("sensor {}", number);
    case K::ZProbe: return fmt::format("Z probe {}", number);
    case K::Endstop: return fmt::format("the {} endstop", static_cast<char>(number));
    case K::FilamentMonitor: return fmt::format("filament monitor {}", number);
    case K::Laser: return "the laser";
  }
  return "a device";
}

std::optional<PinClash> pin_clash(const MachineState& s, const PinChange& ch) {
  for (size_t i = 0; i < ch.pins.size(); ++i) {
    for (size_t j = 0; j < i; ++j)
      if (ch.pins[j].key == ch.pins[i].key) return PinClash{i, nullptr};
    auto it = s.pins.find(ch.pins[i].key);
    if (it != s.pins.end() && it->second.device != ch.device) return PinClash{i, &it->second};
  }
  return std::nullopt;
}

void apply_pin_changes(MachineState& s, const std::vector<PinChange>& changes, NodeId id, bool maybe) {
  for (const PinChange& ch : changes) {
    if (!ch.device.known()) {  // any device's pins may have changed
      s.pins_known = false;
      continue;
    }
    // Given back even inside an `if`: a pin that may be free is not reported as taken. (Through the device's own
    // list: a long file names many pins, and most commands that name one give some back. The list is emptied, not
    // erased, so that a device given pins again and again reuses it.)
    std::vector<std::string>* held = nullptr;
    if (auto it = s.pins_held.find(ch.device); it != s.pins_held.end()) {
      held = &it->second;
      for (const std::string& key : *held) s.pins.erase(key);
      held->clear();
    }
    if (!ch.pins_known || ch.pins.empty()) continue;
    const auto clash = pin_clash(s, ch);
    if (clash && (!clash->holder || !clash->holder->maybe)) continue;  // refused: the device holds no pin
    for (const PinName& p : ch.pins) {
      PinOwner& o = s.pins[p.key];
      if (o.device.known() && o.device != ch.device) std::erase(s.pins_held[o.device], p.key);  // a maybe holder
      o = PinOwner{ch.device, p.written, id, maybe || clash.has_value()};
      if (!held) held = &s.pins_held[ch.device];  // (an insertion into an unordered_map moves no element)
      held->push_back(p.key);
    }
  }
}

PinName pin_name(std::string_view written) {
  std::string_view board;
  return parse_pin(written, board);
}

std::vector<PinChange> pin_changes(const ParsedFile& pf, const Command& c, const MachineState& s) {
  std::vector<PinChange> out;
  if (c.letter != 'M' || c.fraction >= 0 || s.firmware < kRrf3_0) return out;
  switch (c.number) {
    case 950: m950(pf, c, s, out); break;
    case 308: m308(pf, c, s, out); break;
    case 558: m558(pf, c, out); break;
    case 574: m574(pf, c, s, out); break;
    case 591: m591(pf, c, out); break;
    case 452:
      if (auto ch = pins_from(pf, c, 'C', PinDevice{PinDevice::Kind::Laser, 0})) out.push_back(std::move(*ch));
      break;
    default: break;
  }
  return out;
}

}  // namespace rrflint
