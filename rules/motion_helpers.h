// Helpers shared by the axis and drive-mapping rules (RRF201, RRF203, RRF213): which commands set per-axis values,
// which drivers an M584 adds to an axis or extruder, and which earlier commands lose effect because of an M584
// (docs/firmware-behaviour.md#axes-and-m584). One M584 with two or more such commands is RRF213's single finding;
// RRF201 and RRF203 then leave those commands to it (`summarised`), so that one mistake is reported once.
#pragma once

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint::motion {

/// Commands that take per-axis values and loop over the axes that exist (RRF201's list).
inline constexpr int32_t kAxisMCodes[] = {92, 201, 203, 205, 206, 208, 350, 566, 574, 906, 913, 915, 917};
inline bool is_axis_code(char letter, int32_t number, int fraction) {
  if (fraction >= 0) return false;
  if (letter == 'G') return number == 31;
  return letter == 'M' && std::find(std::begin(kAxisMCodes), std::end(kAxisMCodes), number) != std::end(kAxisMCodes);
}
inline bool is_axis_command(const Command& c) { return is_axis_code(c.letter, c.number, c.fraction); }

/// Letters that are parameters, not axes, of an axis command.
inline bool is_own_parameter(const Command& c, char letter) {
  if (c.letter == 'G') return letter == 'P' || letter == 'S' || letter == 'T' || letter == 'K' || letter == 'H';
  switch (c.number) {
    case 915: return letter == 'S' || letter == 'F' || letter == 'H' || letter == 'T' || letter == 'R' || letter == 'P';
    case 574: return letter == 'S' || letter == 'P';
    default: return false;
  }
}

/// Is parameter p of an axis command an axis value that RRF201 judges (not X/Y/Z/E, not the command's own letter,
/// not a pin string, the first of duplicate letters)?
inline bool is_axis_value(const ParsedFile& pf, const Command& c, const Param& p) {
  const char L = p.letter;
  if (L == 0 || L == 'X' || L == 'Y' || L == 'Z' || L == 'E') return false;
  if (allowed_axis_letters().find(L) == std::string_view::npos || is_own_parameter(c, L)) return false;
  if (p.kind == ValueKind::String || p.kind == ValueKind::Text) return false;
  return pf.find(c, L).is(p);
}

/// Is this node a current command (M906/M913/M917)? Those reach CAN drivers only when sent.
inline bool is_current_code(int number) { return number == 906 || number == 913 || number == 917; }

/// The drive mapping as far as these rules need it: each axis's drivers (empty: unknown) and the extruders'.
struct DriveMap {
  struct Entry {
    char letter;
    std::vector<DriverId> drivers;
    bool maybe;
  };
  std::vector<Entry> axes;
  std::vector<DriverId> extruders;
  bool axes_known = true, extruders_known = true;
  const Entry* axis(char L) const {
    auto it = std::find_if(axes.begin(), axes.end(), [&](const Entry& e) { return e.letter == L; });
    return it == axes.end() ? nullptr : &*it;
  }
};

inline DriveMap drive_map(const MachineState& s) {
  DriveMap m;
  for (const Axis& a : s.axes) m.axes.push_back({a.letter, a.drivers, a.maybe});
  m.extruders = s.extruder_drivers;
  m.axes_known = s.axes_known && !s.unknown_baseline;
  m.extruders_known = s.extruders_known && !s.unknown_baseline && s.extruders == static_cast<int>(m.extruders.size());
  return m;
}

/// Applies one M584 to the map as the machine model does (docs/firmware-behaviour.md#axes-and-m584).
inline void apply_m584(DriveMap& m, const ParsedFile& pf, const Command& c, bool maybe) {
  for (char L : allowed_axis_letters()) {
    if (!pf.find(c, L)) continue;
    auto d = get_driver_list(pf, c, L);
    std::vector<DriverId> drivers = d.known() ? d.value : std::vector<DriverId>{};
    if (auto* e = const_cast<DriveMap::Entry*>(m.axis(L))) e->drivers = drivers;
    else m.axes.push_back({L, drivers, maybe});
  }
  if (pf.find(c, 'E')) {
    auto e = get_driver_list(pf, c, 'E');
    m.extruders_known = e.known() && !maybe;
    m.extruders = m.extruders_known ? e.value : std::vector<DriverId>{};
  }
  if (pf.find(c, 'P') && (maybe || !get_int(pf, c, 'P').known())) m.axes_known = false;
}

/// Applies the M584 commands of nodes (from, to) to the map.
inline void advance(DriveMap& m, const NodeContext& cx, NodeId from, NodeId to) {
  tools::find_code(cx, from, to, 'M', 584, [&](const tools::NodeCommand& k) {
    apply_m584(m, *k.pf, *k.c, k.node.maybe);
    return false;
  });
}

/// The drivers in `now` that `before` lacks and that a setting sent at `before` time misses: local ones for
/// microstepping (CAN drivers get it from M584 itself), CAN-connected ones for currents.
inline std::vector<DriverId> added_drivers(const std::vector<DriverId>& before, const std::vector<DriverId>& now,
                                           bool can) {
  std::vector<DriverId> out;
  if (before.empty()) return out;  // unknown before
  for (DriverId d : now)
    if ((d.board > 0) == can && std::find(before.begin(), before.end(), d) == before.end()) out.push_back(d);
  return out;
}

/// Why an earlier command loses effect at an M584.
enum class Loss : uint8_t { Created, Microstepping, Current };

struct Dependent {
  NodeId node;
  char letter;  // 'E': the extruders
  Loss why;
  std::vector<DriverId> added;  // Microstepping, Current: the drivers that miss the setting
};

/// Is the setting of `letter` by a command of `number` sent again after the M584 at `m` (any later command of that
/// code naming it, even conditional or unknown)? Then the drivers it adds receive it after all.
inline bool reapplied_after(const NodeContext& cx, NodeId m, int number, char letter) {
  return tools::find_code(cx, m, cx.segment().end, 'M', number,
                          [&](const tools::NodeCommand& k) { return bool(k.pf->find(*k.c, letter)); }) != kNoNode;
}

/// The value an M350/M906/M913/M917 sets for extruder i: RRF repeats the last value of a short list. Unknown (an
/// expression, a list longer than the extruders: RRF202) gives nothing.
inline bool extruder_value(const ParsedFile& pf, const Command& c, size_t i, size_t count, double& out) {
  auto v = get_float_list(pf, c, 'E');
  if (!v.known() || v.value.empty() || v.value.size() > count) return false;
  out = v.value[std::min(i, v.value.size() - 1)];
  return true;
}

/// Is `value` (for one axis or extruder) a setting that a driver added later misses? M350: anything but x16 with
/// interpolation (RRF's default; an I given as an expression: not judged); currents: any value.
inline bool matters(const ParsedFile& pf, const Command& c, double value) {
  if (is_current_code(c.number)) return true;
  auto I = get_int(pf, c, 'I');
  if (I.unknown()) return false;
  return value >= 0 && (value != 16 || !(I.known() && I.value > 0));
}

/// The drivers that the M584 at `m` adds to `letter` (an axis, or 'E') and that miss the setting the command `d`
/// made before it, when the drivers were `before` (axes) or `at.extruders`. Empty when nothing is lost: an unknown
/// value or mapping, a conditional M584, a default M350, or the setting sent again after the M584.
inline std::vector<DriverId> lost_setting(const NodeContext& cx, const tools::NodeCommand& d, NodeId m, char letter,
                                          const std::vector<DriverId>& before, const DriveMap& at) {
  std::vector<DriverId> out;
  const tools::NodeCommand k = tools::command_at(cx.machine, cx.graph, m);
  if (!k || k.node.maybe) return out;
  const bool can = is_current_code(d.c->number);
  auto now = get_driver_list(*k.pf, *k.c, letter);
  if (!now.known()) return out;
  if (letter != 'E') {
    auto v = get_float(*d.pf, *d.c, letter);
    if (v.known() && matters(*d.pf, *d.c, v.value)) out = added_drivers(before, now.value, can);
  } else if (at.extruders_known) {
    const size_t n = std::min(at.extruders.size(), now.value.size());
    for (size_t i = 0; i < n; ++i) {
      double v = 0;
      if (at.extruders[i] == now.value[i] || (now.value[i].board > 0) != can) continue;
      if (extruder_value(*d.pf, *d.c, i, at.extruders.size(), v) && matters(*d.pf, *d.c, v))
        out.push_back(now.value[i]);
    }
  }
  if (!out.empty() && reapplied_after(cx, m, d.c->number, letter)) out.clear();
  return out;
}

/// The first M584 after node `from` in this segment that names `letter`; kNoNode if none.
inline NodeId next_m584(const NodeContext& cx, NodeId from, char letter) {
  return tools::find_code(cx, from, cx.segment().end, 'M', 584,
                          [&](const tools::NodeCommand& k) { return bool(k.pf->find(*k.c, letter)); });
}

/// The letters (axes, and 'E' for the extruders) whose earlier values or settings the M584 `k` can make lose effect,
/// when the drive mapping before it is `at`: `created`, the axes it creates (their earlier values were ignored), and
/// `remapped`, the existing axes and the extruders it gives drivers they lacked (settings sent before miss those).
struct MappingChange {
  std::string created, remapped;
  bool any() const { return !created.empty() || !remapped.empty(); }
};
inline MappingChange mapping_change(const tools::NodeCommand& k, const DriveMap& at) {
  MappingChange out;
  for (char L : allowed_axis_letters()) {
    if (!k.pf->find(*k.c, L)) continue;
    const DriveMap::Entry* e = at.axis(L);
    if (!e) {
      out.created += L;
      continue;
    }
    auto now = get_driver_list(*k.pf, *k.c, L);
    if (now.known() &&
        (!added_drivers(e->drivers, now.value, false).empty() || !added_drivers(e->drivers, now.value, true).empty()))
      out.remapped += L;
  }
  auto now = get_driver_list(*k.pf, *k.c, 'E');
  if (!now.known() || !at.extruders_known) return out;
  for (size_t i = 0; i < std::min(now.value.size(), at.extruders.size()); ++i)
    if (!(now.value[i] == at.extruders[i])) {
      out.remapped += 'E';
      break;
    }
  return out;
}

/// Where the walk for the M584 at `m` may start. When it creates an axis, any earlier value for that axis counts: the
/// first command since the start of the segment that names the letter (from the indexes of each axis code by letter),
/// not the start of the segment itself, which made a file of many M584s that each create an axis (one the board
/// lacks) quadratic. Settings of a remapped letter count only since the latest earlier M584 that names that letter
/// (that M584 cleared the older ones: see dependents()), so for those the walk starts at the earliest of such M584s.
inline NodeId walk_start(const NodeContext& cx, const MappingChange& change, NodeId m) {
  const NodeId begin = cx.segment().begin;
  NodeId created = m;  // the first command that names an axis it creates
  for (const char L : change.created) {
    created = std::min(created, tools::first_in(tools::code_index(cx.machine, cx.graph, 'G', 31)[L], begin, m));
    for (const int32_t code : kAxisMCodes)
      created = std::min(created, tools::first_in(tools::code_index(cx.machine, cx.graph, 'M', code)[L], begin, m));
  }
  std::string open = change.remapped;  // letters whose latest earlier M584 is not found yet
  NodeId start = m;
  const std::vector<NodeId>& m584s = *cx.graph.code_nodes(cx.machine, 'M', 584);
  for (auto it = std::lower_bound(m584s.begin(), m584s.end(), m); !open.empty();) {
    if (it == m584s.begin() || *(it - 1) < begin) return begin;
    const tools::NodeCommand k = tools::command_at(cx.machine, cx.graph, *--it);
    if (!k.is('M', 584)) continue;
    std::erase_if(open, [&](char L) { return bool(k.pf->find(*k.c, L)); });
    start = *it;
  }
  return std::min(start, created);
}

/// The earlier commands in this segment that lose effect because of the M584 at node `m`, whose drive mapping
/// before it runs is `at`: axis values of axes it creates (RRF201), and the RRF203 cases whose later M584 it is.
/// E values before the first `M584 E` (RRF202) are rejected with an error, not lost silently: not counted.
inline std::vector<Dependent> dependents(const NodeContext& cx, NodeId m, const DriveMap& at) {
  std::vector<Dependent> out;
  const tools::NodeCommand mk = tools::command_at(cx.machine, cx.graph, m);
  if (!mk || !at.axes_known) return out;
  const MappingChange change = mapping_change(mk, at);
  if (!change.any()) return out;
  std::map<char, std::vector<std::pair<NodeId, tools::NodeCommand>>> pending;  // RRF203 candidates by letter
  // The M584 and axis commands since the walk's start, in order, from the code index (no walk of every node). When
  // it creates no axis, only the settings that a remapped axis loses (M350 and the currents) are candidates.
  const NodeId start = walk_start(cx, change, m);
  std::vector<NodeId> ids;
  auto take = [&](char letter, int32_t number) {
    const std::vector<NodeId>& all = *cx.graph.code_nodes(cx.machine, letter, number);
    ids.insert(ids.end(), std::lower_bound(all.begin(), all.end(), start), std::lower_bound(all.begin(), all.end(), m));
  };
  take('M', 584);
  if (change.created.empty()) {
    for (const int32_t code : {350, 906, 913, 917}) take('M', code);
  } else {
    take('G', 31);
    for (const int32_t code : kAxisMCodes) take('M', code);
  }
  std::sort(ids.begin(), ids.end());
  for (const NodeId i : ids) {
    const Node n = cx.graph.nodes[i];
    const tools::NodeCommand k = tools::command_at(cx.machine, n);
    if (!k) continue;
    if (k.is('M', 584)) {
      for (auto& [L, list] : pending)
        if (k.pf->find(*k.c, L)) list.clear();
      continue;
    }
    if (!is_axis_command(*k.c)) continue;
    const bool settings = k.is('M', 350) || (k.c->fraction < 0 && is_current_code(k.c->number));
    if (change.created.empty()) {  // no axis values to judge: the settings of the remapped letters
      if (settings && !n.maybe)
        for (char L : change.remapped)
          if (k.pf->find(*k.c, L)) pending[L].push_back({i, k});
      continue;
    }
    for (const Param& p : k.pf->params(*k.c)) {
      const char L = p.letter;
      if (is_axis_value(*k.pf, *k.c, p) && !at.axis(L) && mk.pf->find(*mk.c, L)) {
        const bool override_line = (k.is('M', 208) || k.is('G', 31)) && tools::inside_m501(cx.graph, i);
        // A line that runs again after the M584 (a macro called before and after it) sets the axis then.
        if (!(k.c->letter == 'G' && L == 'C') && !(override_line && !mk.node.maybe) &&
            !tools::runs_again(cx.graph, n, m, cx.segment().end))
          out.push_back({i, L, Loss::Created, {}});
      } else if (settings && !n.maybe && change.remapped.find(L) != std::string::npos && k.pf->find(*k.c, L).is(p)) {
        pending[L].push_back({i, k});
      }
    }
  }
  for (auto& [L, list] : pending) {
    const DriveMap::Entry* e = L == 'E' ? nullptr : at.axis(L);
    if (L != 'E' && (!e || e->maybe)) continue;
    for (auto& [i, k] : list) {
      std::vector<DriverId> lost = lost_setting(cx, k, m, L, e ? e->drivers : std::vector<DriverId>{}, at);
      if (!lost.empty()) out.push_back({i, L, k.is('M', 350) ? Loss::Microstepping : Loss::Current, lost});
    }
  }
  std::sort(out.begin(), out.end(), [](const Dependent& a, const Dependent& b) { return a.node < b.node; });
  return out;
}

/// Is dependent i a second run of the line of an earlier one (a macro called twice before the M584)?
inline bool repeated_run(const Graph& g, const std::vector<Dependent>& deps, size_t i) {
  const Node& a = g.nodes[deps[i].node];
  for (size_t j = 0; j < i; ++j) {
    const Node& b = g.nodes[deps[j].node];
    if (deps[j].node != deps[i].node && b.unit == a.unit && b.index == a.index) return true;
  }
  return false;
}

/// How many distinct commands (lines of a file: a line run twice is one) the dependents are.
inline size_t command_count(const Graph& g, const std::vector<Dependent>& deps) {
  std::vector<std::pair<uint32_t, uint32_t>> lines;  // (unit, index): one per line, however often it ran
  lines.reserve(deps.size());
  for (const Dependent& d : deps) lines.emplace_back(g.nodes[d.node].unit, g.nodes[d.node].index);
  std::sort(lines.begin(), lines.end());
  return static_cast<size_t>(std::unique(lines.begin(), lines.end()) - lines.begin());
}

/// RRF213 reports an M584 that two or more earlier commands depend on.
inline bool summary_fires(const Graph& g, const std::vector<Dependent>& deps) { return command_count(g, deps) >= 2; }

/// Is the command at `cx` one of the dependents of the M584 at `m` that RRF213 reports as one finding? RRF201 and
/// RRF203 then leave it to RRF213.
inline bool summarised(const NodeContext& cx, NodeId m) {
  if (m == kNoNode || cx.graph.nodes[m].maybe) return false;
  DriveMap at = drive_map(cx.state);
  advance(at, cx, cx.id, m);
  const std::vector<Dependent> deps = dependents(cx, m, at);
  if (!summary_fires(cx.graph, deps)) return false;
  return std::any_of(deps.begin(), deps.end(), [&](const Dependent& d) { return d.node == cx.id; });
}

}  // namespace rrflint::motion
