// Helpers shared by the tool and temperature rules (RRF307–RRF329): how RRF dispatches G10, which tool a
// G10/M568 addresses, a tool's X/Y/Z maps with their defaults, and short quotes of commands for messages.
#pragma once

#include <fmt/format.h>

#include <string>
#include <string_view>

#include "lint/engine/rule.h"

namespace rrflint::tools {

/// G10's form as RRF dispatches it (docs/firmware-behaviour.md#g10-forms; GCodes2.cpp case 10).
enum class G10Form : uint8_t { Tool, Workplace, Retraction, BadL, Unknown };

/// With `s`, visible axis letters count towards the tool form; without it, only L, P, R and S decide, and a
/// G10 with axis letters alone is Unknown.
inline G10Form g10_form(const ParsedFile& pf, const Command& c, const MachineState* s, Version fw) {
  auto L = get_int(pf, c, 'L');
  if (L.present()) {
    if (!L.known()) return G10Form::Unknown;
    if (L.value == 1) return G10Form::Tool;
    if (L.value == 2 || L.value == 20) return G10Form::Workplace;
    return G10Form::BadL;
  }
  if (pf.find(c, 'P') || pf.find(c, 'R') || pf.find(c, 'S')) return G10Form::Tool;
  if (fw >= Version(3, 3, 0, 0, 0) && fw < Version(3, 5, 0, 0, 0) && pf.find(c, 'F')) return G10Form::Tool;
  if (!s) return G10Form::Unknown;
  for (int i = 0; i < s->visible_axes && i < static_cast<int>(s->axes.size()); ++i)
    if (pf.find(c, s->axes[static_cast<size_t>(i)].letter)) return s->axes_known ? G10Form::Tool : G10Form::Unknown;
  return s->axes_known ? G10Form::Retraction : G10Form::Unknown;
}

/// Is this command a G10 in tool form or an M568 that sets tool settings (3.3+)?
inline bool sets_tool_settings(const ParsedFile& pf, const Command& c, const MachineState& s) {
  if (c.is('G', 10)) return g10_form(pf, c, &s, s.firmware) == G10Form::Tool;
  return c.is('M', 568) && s.firmware >= Version(3, 3, 0, 0, 0);
}

/// The tool a G10/M568 addresses: P, or the current tool. -1 with `known` false when it cannot be told.
inline int addressed_tool(const ParsedFile& pf, const Command& c, const MachineState& s, bool& known) {
  auto P = get_int(pf, c, 'P');
  known = P.known() || (P.absent() && s.current_tool_known);
  if (P.known()) return static_cast<int>(P.value);
  return P.absent() ? s.current_tool : -1;
}

/// A tool that certainly exists, with certain heaters, or nullptr.
inline const Tool* certain_tool(const MachineState& s, int n) {
  const Tool* t = s.tool(n);
  return t && !t->maybe && t->heaters_known && !s.unknown_baseline ? t : nullptr;
}

/// The tool whose temperatures a G10/M568 at this node sets, when the command certainly runs, sets R or S,
/// and names a tool that certainly exists; nullptr otherwise.
inline const Tool* temperature_tool(const NodeContext& cx) {
  if (!cx.is_command() || cx.runs < 2) return nullptr;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  if (!sets_tool_settings(pf, c, cx.state)) return nullptr;
  if (!pf.find(c, 'R') && !pf.find(c, 'S')) return nullptr;
  bool known = false;
  const int n = addressed_tool(pf, c, cx.state, known);
  if (!known || n < 0) return nullptr;
  return certain_tool(cx.state, n);
}

/// Heater numbers of a tool, without the `-1` of `H-1`.
inline std::vector<int> real_heaters(const Tool& t) {
  std::vector<int> out;
  for (int64_t h : t.heaters)
    if (h >= 0) out.push_back(static_cast<int>(h));
  return out;
}

/// Are all axes certain: no M584 we could not read, none created inside a conditional block?
inline bool axes_certain(const MachineState& s) {
  if (!s.axes_known || s.unknown_baseline) return false;
  for (const Axis& a : s.axes)
    if (a.maybe) return false;
  return true;
}

inline uint32_t visible_mask(const MachineState& s) {
  return s.visible_axes >= 32 ? 0xFFFFFFFFu : ((1u << s.visible_axes) - 1);
}

/// One M563 axis map (X, Y or Z) as RRF builds it: the given indices ANDed with the visible axes, or the
/// default (X→X, Y→Y, Z→Z) when the letter is absent. `known` is false for expressions.
struct ToolMap {
  char letter = 'X';
  bool given = false;
  bool known = true;
  uint32_t bits = 0;
  std::vector<int64_t> indices;  // as written
  ParamRef param;
};

inline ToolMap tool_map(const ParsedFile& pf, const Command& c, const MachineState& s, char letter) {
  ToolMap m;
  m.letter = letter;
  const int def = letter - 'X';
  auto v = get_int_list(pf, c, letter);
  if (v.absent()) {
    m.bits = 1u << def;
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

/// Does M563 have a Z map on this firmware (3.5+)? Before that `Z` is ignored.
inline bool has_z_map(Version fw) { return fw >= Version(3, 5, 0, 0, 0); }

/// The letter of axis index i in the standard creation order (XYZUVWABCD, then lowercase), for messages.
inline std::string axis_name(const MachineState& s, int i) {
  if (i < 0 || i >= static_cast<int>(s.axes.size())) return fmt::format("#{}", i);
  const char L = s.axes[static_cast<size_t>(i)].letter;
  return L >= 'a' ? fmt::format("'{}", L) : std::string(1, L);
}

/// The command as written, quoted for a message; long commands are cut after a few parameters.
inline std::string quote(const ParsedFile& pf, const Command& c) {
  std::string_view t = pf.text(c.span);
  if (t.size() <= 40) return fmt::format("'{}'", t);
  size_t cut = t.rfind(' ', 36);
  if (cut == std::string_view::npos || cut < pf.text(c.word).size()) cut = 36;
  return fmt::format("'{} …'", t.substr(0, cut));
}

/// Formats a temperature without needless decimals: 285, 212.5.
inline std::string degrees(double v) {
  std::string s = fmt::format("{:.1f}", v);
  if (s.ends_with(".0")) s.resize(s.size() - 2);
  return s + " °C";
}

/// Is node `id` part of a run of config-override.g (M501), directly or through M98?
inline bool inside_m501(const Graph& g, NodeId id) {
  if (id == kNoNode) return false;
  for (NodeId e = g.nodes[id].kind == NodeKind::Enter ? id : g.nodes[id].enter; e != kNoNode; e = g.nodes[e].enter)
    if (g.nodes[e].call == CallKind::M501) return true;
  return false;
}

/// The first later command in the node's segment that satisfies `pred` (look-ahead for notes), or kNoNode.
template <class Pred>
NodeId find_later(const NodeContext& cx, Pred pred) {
  return cx.graph.nodes.find_if(cx.id + 1, cx.segment().end, [&](NodeId, const Node& n) {
    if (n.kind != NodeKind::Command) return false;
    const FileUnit& u = cx.machine.unit(n.unit);
    return pred(u.parsed, u.parsed.commands[n.index], n);
  });
}

}  // namespace rrflint::tools
