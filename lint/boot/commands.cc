#include "lint/boot/commands.h"

#include <string>

#include "lint/base/strings.h"

namespace rrflint {

namespace {

/// Only P and L among the parameters (L being 1, checked by the caller): the tool form that only reports.
bool only_p_and_l(const ParsedFile& pf, const Command& c) {
  for (const Param& p : pf.params(c))
    if (p.letter != 'P' && p.letter != 'L') return false;
  return true;
}

/// A G10 with no L, P, R or S: the visible axes decide between the tool form and retraction.
G10Form by_axes(const ParsedFile& pf, const Command& c, const MachineState* s) {
  if (!s || !s->axes_known || s->unknown_baseline) return G10Form::Unknown;
  bool maybe = false;
  for (int i = 0; i < s->visible_axes && i < static_cast<int>(s->axes.size()); ++i) {
    const Axis& a = s->axes[static_cast<size_t>(i)];
    if (!pf.find(c, a.letter)) continue;
    if (!a.maybe) return G10Form::Tool;
    maybe = true;  // an axis created inside an `if`: it may not exist
  }
  return maybe ? G10Form::Unknown : G10Form::Retraction;
}

}  // namespace

G10Form g10_form(const ParsedFile& pf, const Command& c, const MachineState* s, Version fw) {
  auto L = get_int(pf, c, 'L');
  if (L.present()) {
    if (!L.known()) return G10Form::Unknown;
    if (L.value == 2 || L.value == 20) return G10Form::Workplace;
    if (L.value != 1) return G10Form::BadL;
    return only_p_and_l(pf, c) ? G10Form::Report : G10Form::Tool;
  }
  if (pf.find(c, 'P') || pf.find(c, 'R') || pf.find(c, 'S'))
    return only_p_and_l(pf, c) ? G10Form::Report : G10Form::Tool;
  if (fw >= kRrf3_3 && fw < kRrf3_5 && pf.find(c, 'F')) return G10Form::Tool;  // 3.3–3.4.x count F as well
  return by_axes(pf, c, s);
}

bool m563_defines(const ParsedFile& pf, const Command& c) {
  for (char L : {'S', 'D', 'H', 'X', 'Y', 'Z', 'F', 'R'})
    if (pf.find(c, L)) return true;
  return false;
}

M671Read m671_read(const ParsedFile& pf, const Command& c) {
  M671Read r;
  auto X = get_float_list(pf, c, 'X');
  auto Y = get_float_list(pf, c, 'Y');
  r.has_x = X.present(), r.has_y = Y.present();
  if (!r.has_x && !r.has_y) return r;
  if (X.known()) r.x = std::move(X.value);
  if (Y.known()) r.y = std::move(Y.value);
  if (r.x.size() > kMaxLeadscrews || r.y.size() > kMaxLeadscrews) r.form = M671Form::TooLong;
  else if (!r.has_x || !r.has_y) r.form = M671Form::Mismatch;
  else if (!X.known() || !Y.known()) r.form = M671Form::Unknown;
  else r.form = r.x.size() == r.y.size() ? M671Form::Set : M671Form::Mismatch;
  return r;
}

bool has_leadscrews(int kinematics) {
  switch (kinematics) {
    case 0:
    case 1:
    case 4:
    case 5:
    case 8:
    case 9:
    case 11: return true;
    default: return false;
  }
}

char m950_device(const ParsedFile& pf, const Command& c, Version fw, Board board) {
  const Version every_board = Version::beta(3, 5, 0, 4);
  const bool reads_d = fw >= every_board || (fw >= kRrf3_4 && (board == Board::Duet3_6HC || board == Board::Unknown));
  char which = 0;
  for (char L : {'D', 'E', 'R', 'J', 'F', 'H', 'P', 'S'}) {
    if (!pf.find(c, L) || (L == 'R' && fw < kRrf3_3) || (L == 'D' && !reads_d) || (L == 'E' && fw < every_board))
      continue;
    if (which) return 0;
    which = L;
  }
  return which;
}

M563Map m563_map(const ParsedFile& pf, const Command& c, const MachineState& s, char letter) {
  M563Map m;
  m.letter = letter;
  auto v = get_int_list(pf, c, letter);
  if (v.absent()) {
    m.bits = 1u << (letter - 'X');
    return m;
  }
  m.given = true;
  m.param = v.param;
  if (!v.known()) {
    m.known = false;
    return m;
  }
  m.indices = v.value;
  for (int64_t i : v.value)
    if (i >= 0 && i < 32) m.bits |= 1u << i;
  m.bits &= visible_mask(s);
  return m;
}

ToolRef addressed_tool(const ParsedFile& pf, const Command& c, const MachineState& s) {
  auto P = get_int(pf, c, 'P');
  if (P.known()) return {static_cast<int>(P.value), true, true};
  if (P.present()) return {-1, false, true};
  // A lone macro starts with any tool selected, until a T in it selects one.
  const bool baseline = s.unknown_baseline && s.current_tool_set == kNoNode;
  return {s.current_tool, s.current_tool_known && !baseline, false};
}

int m585_axis(const ParsedFile& pf, const Command& c, const MachineState& s) {
  for (int i = 0; i < s.visible_axes && i < static_cast<int>(s.axes.size()); ++i)
    if (pf.find(c, s.axes[static_cast<size_t>(i)].letter)) return i;
  return -1;
}

namespace {

/// "tpost12.g" with prefix "tpost": 12; "tpost.g": -1; anything else: -2.
int numbered(std::string_view name, std::string_view prefix) {
  if (!name.starts_with(prefix) || !name.ends_with(".g")) return -2;
  const std::string_view digits = name.substr(prefix.size(), name.size() - prefix.size() - 2);
  if (digits.empty()) return -1;
  if (digits.size() > 6) return -2;
  int n = 0;
  for (char ch : digits) {
    if (ch < '0' || ch > '9') return -2;
    n = n * 10 + (ch - '0');
  }
  return n;
}

bool homing_name(std::string_view name) {
  if (name == "homeall.g" || name == "homedelta.g") return true;
  if (!name.starts_with("home") || !name.ends_with(".g")) return false;
  std::string_view axis = name.substr(4, name.size() - 6);
  if (axis.starts_with('\'')) axis.remove_prefix(1);
  return axis.size() == 1 && axis[0] >= 'a' && axis[0] <= 'z';
}

}  // namespace

bool drops_rest_of_line(const ParsedFile& pf, const Command& c) {
  if (c.fraction >= 0) return false;
  if (c.letter == 'M') return c.number == 98;
  if (c.letter != 'G') return false;
  return c.number == 28 || c.number == 32 || (c.number == 29 && pf.find(c, 'S') == nullptr);
}

FileRole file_role(std::string_view sd_path, int* tool) {
  const size_t slash = sd_path.rfind('/');
  const std::string name = to_lower(sd_path.substr(slash == std::string_view::npos ? 0 : slash + 1));
  if (name == "config.g" || name == "config.g.bak") return FileRole::Config;
  if (name == "config-override.g") return FileRole::ConfigOverride;
  if (name == "resurrect.g") return FileRole::Resurrect;
  if (name == "resurrect-prologue.g") return FileRole::ResurrectPrologue;
  if (name == "daemon.g") return FileRole::Daemon;
  if (name == "runonce.g") return FileRole::RunOnce;
  if (homing_name(name)) return FileRole::Homing;
  static constexpr struct {
    std::string_view prefix;
    FileRole role;
  } kToolMacros[] = {{"tfree", FileRole::ToolFree}, {"tpre", FileRole::ToolPre}, {"tpost", FileRole::ToolPost}};
  for (const auto& m : kToolMacros) {
    const int n = numbered(name, m.prefix);
    if (n < -1) continue;
    if (tool) *tool = n;
    return m.role;
  }
  return FileRole::Other;
}

std::optional<int> kinematics_set_by(const ParsedFile& pf, const Command& c, Version fw) {
  if (c.number == 665) {
    if (pf.find(c, 'L') || pf.find(c, 'D')) return 3;
    return std::nullopt;
  }
  const char letter = c.number == 669 ? 'K' : 'S';
  if (c.number == 667 && fw >= kRrf3_5) return std::nullopt;  // "M667 is no longer supported"
  auto v = get_int(pf, c, letter);
  if (v.absent()) return std::nullopt;
  if (!v.known() || v.value < 0) return -1;
  if (c.number == 667) return v.value == 1 || v.value == 2 ? static_cast<int>(v.value) : 0;
  return static_cast<int>(v.value);
}

}  // namespace rrflint
