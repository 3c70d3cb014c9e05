// Helpers shared by the G10, tool and temperature rules (RRF202, RRF301–RRF331): look-ahead in the command graph,
// the "move this line after that one" fix, and how a command is quoted in a message. What RRF makes of a command
// (G10's form, whether an M563 defines a tool and its X/Y/Z maps, the tool a command addresses, a file's role) is
// decided in lint/boot/commands.h, never here.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "lint/base/strings.h"
#include "lint/boot/commands.h"
#include "lint/engine/rule.h"
#include "rules/node_index.h"

namespace rrflint::tools {

/// Is `letter` an axis letter on this target, whether or not the axis exists?
inline bool is_axis_letter(char letter, const MachineState& s) {
  if (letter >= 'a' && letter <= 'z') {
    const char hi = highest_lowercase_axis(s.board, s.firmware);
    return hi != 0 && letter <= hi;
  }
  const std::string_view upper = s.firmware < kRrf3_0 ? "XYZUVWABC" : "XYZUVWABCD";
  return letter != 0 && upper.find(letter) != std::string_view::npos;
}

/// "U" or "'a", as the letter is written in a command.
inline std::string axis_name(char letter) {
  return letter >= 'a' && letter <= 'z' ? std::string("'") + letter : std::string(1, letter);
}

/// The letter of axis index i ("U", "'a"), or "#i" for an index with no axis, for messages.
inline std::string axis_name(const MachineState& s, int i) {
  if (i < 0 || i >= static_cast<int>(s.axes.size())) return fmt::format("#{}", i);
  return axis_name(s.axes[static_cast<size_t>(i)].letter);
}

inline bool axis_visible(const MachineState& s, char letter) { return s.axis_visible(s.axis_index(letter)); }

/// The command of a graph node, or nullptr for Enter/Leave/ToolSelect nodes. The node is a copy: Graph::nodes
/// decodes nodes on access, so a pointer to one would dangle (found by fuzzing: a stack use after scope).
struct NodeCommand {
  const ParsedFile* pf = nullptr;
  std::optional<Command> c;
  Node node;
  explicit operator bool() const { return c.has_value(); }
  bool is(char letter, int number) const { return c && c->letter == letter && c->number == number && c->fraction < 0; }
};

inline NodeCommand command_at(const Machine& m, const Node& n) {
  if (n.kind != NodeKind::Command) return {};
  const ParsedFile& pf = m.unit(n.unit).parsed;
  return {&pf, pf.commands[n.index], n};
}
inline NodeCommand command_at(const Machine& m, const Graph& g, NodeId id) { return command_at(m, g.nodes[id]); }

/// Calls f(id, command) for each command node in [begin, end) with code `letter` `number` (no fraction), in order,
/// until it returns true; returns that node, or kNoNode. It visits only the nodes of that code (Graph::code_nodes;
/// a number outside 0…1023 has no index and walks the nodes).
template <class F>
NodeId each_code_node(const NodeContext& cx, NodeId begin, NodeId end, char letter, int number, F f) {
  auto visit = [&](NodeId id, const Node& n) {
    const ParsedFile& pf = cx.machine.unit(n.unit).parsed;
    const CommandTable::Code code = pf.commands.code(n.index);
    return code.letter == letter && code.number == number && code.fraction < 0 &&
           f(id, NodeCommand{&pf, pf.commands[n.index], n});
  };
  if (const std::vector<NodeId>* ids = cx.graph.code_nodes(cx.machine, letter, number)) {
    for (auto it = std::lower_bound(ids->begin(), ids->end(), begin); it != ids->end() && *it < end; ++it)
      if (visit(*it, cx.graph.nodes[*it])) return *it;
    return kNoNode;
  }
  return cx.graph.nodes.find_if(begin, end,
                                [&](NodeId id, const Node& n) { return n.kind == NodeKind::Command && visit(id, n); });
}

/// Calls f(id, command) for each command node in [begin, end) whose code is `letter` with one of `numbers` (no
/// fraction), in node order, until it returns true; returns that node, or kNoNode. Like each_code_node, it visits
/// only the nodes of those codes.
template <class F>
NodeId each_code_node(const NodeContext& cx, NodeId begin, NodeId end, char letter, std::initializer_list<int> numbers,
                      F f) {
  std::vector<NodeId> ids;
  for (const int number : numbers) {
    const std::vector<NodeId>* all = cx.graph.code_nodes(cx.machine, letter, number);
    if (!all) {  // no index for this number: one walk of the nodes
      return cx.graph.nodes.find_if(begin, end, [&](NodeId id, const Node& n) {
        if (n.kind != NodeKind::Command) return false;
        const ParsedFile& pf = cx.machine.unit(n.unit).parsed;
        const CommandTable::Code code = pf.commands.code(n.index);
        return code.letter == letter && code.fraction < 0 &&
               std::find(numbers.begin(), numbers.end(), code.number) != numbers.end() &&
               f(id, NodeCommand{&pf, pf.commands[n.index], n});
      });
    }
    ids.insert(ids.end(), std::lower_bound(all->begin(), all->end(), begin),
               std::lower_bound(all->begin(), all->end(), end));
  }
  std::sort(ids.begin(), ids.end());
  for (const NodeId id : ids) {
    const Node n = cx.graph.nodes[id];
    const ParsedFile& pf = cx.machine.unit(n.unit).parsed;
    if (pf.commands.code(n.index).fraction < 0 && f(id, NodeCommand{&pf, pf.commands[n.index], n})) return id;
  }
  return kNoNode;
}

/// Calls f(id, command) for each command node in [begin, end) whose code is `letter` with one of `numbers` (no
/// fraction; each 0…1023), latest first, until it returns true; returns that node, or kNoNode. For "the last
/// command before this one that …": it stops at the nearest, where a forward walk visits them all.
template <class F>
NodeId each_code_node_backward(const NodeContext& cx, NodeId begin, NodeId end, char letter,
                               std::initializer_list<int> numbers, F f) {
  std::vector<std::pair<const std::vector<NodeId>*, size_t>> lists;  // each code's nodes, and how many are before
  for (const int number : numbers)
    if (const std::vector<NodeId>* ids = cx.graph.code_nodes(cx.machine, letter, number))
      lists.emplace_back(ids, std::lower_bound(ids->begin(), ids->end(), end) - ids->begin());
  for (;;) {
    std::pair<const std::vector<NodeId>*, size_t>* latest = nullptr;  // the list whose next node is the latest
    for (auto& l : lists)
      if (l.second > 0 && (!latest || (*l.first)[l.second - 1] > (*latest->first)[latest->second - 1])) latest = &l;
    if (!latest) return kNoNode;
    const NodeId id = (*latest->first)[--latest->second];
    if (id < begin) return kNoNode;
    const NodeCommand k = command_at(cx.machine, cx.graph, id);
    if (k.c->fraction < 0 && f(id, k)) return id;
  }
}

/// The first command node in (from, to) with code `letter` `number` (no fraction) for which `pred(command)` holds;
/// kNoNode if none.
template <class Pred>
NodeId find_code(const NodeContext& cx, NodeId from, NodeId to, char letter, int number, Pred pred) {
  return each_code_node(cx, from + 1, to, letter, number, [&](NodeId, const NodeCommand& k) { return pred(k); });
}

/// The first command node after this one in its segment with code `letter` `number` (no fraction) for which
/// `pred(command)` holds; kNoNode if none.
template <class Pred>
NodeId find_later(const NodeContext& cx, char letter, int number, Pred pred) {
  return find_code(cx, cx.id, cx.segment().end, letter, number, pred);
}

/// Per file unit, the commands that more than one command node runs (a macro called twice), from the runs of the
/// graph: the only lines for which runs_again must walk the nodes. Built once per graph (Graph::derived).
struct RepeatedLines {
  std::vector<std::vector<bool>> by_unit;  // empty for a unit none of whose lines runs twice
  bool repeated(const Node& n) const {
    return n.unit < by_unit.size() && n.index < by_unit[n.unit].size() && by_unit[n.unit][n.index];
  }
};
inline const RepeatedLines& repeated_lines(const Graph& g) {
  return g.derived<RepeatedLines>("tools.repeated_lines", [&] {
    std::vector<std::vector<int32_t>> cover;  // per unit, a difference array of how many runs cover each command
    g.nodes.each_command_run([&](NodeId, uint32_t unit, uint32_t index, uint32_t count) {
      if (cover.size() <= unit) cover.resize(unit + 1);
      std::vector<int32_t>& c = cover[unit];
      if (c.size() < size_t{index} + count + 1) c.resize(size_t{index} + count + 1, 0);
      ++c[index];
      --c[index + count];
    });
    RepeatedLines out;
    out.by_unit.resize(cover.size());
    for (size_t u = 0; u < cover.size(); ++u) {
      std::vector<bool> twice(cover[u].size());
      bool any = false;
      int32_t runs = 0;
      for (size_t i = 0; i < cover[u].size(); ++i) {
        runs += cover[u][i];
        if (runs > 1) twice[i] = any = true;
      }
      if (any) out.by_unit[u] = std::move(twice);
    }
    return out;
  });
}

/// Does this very line run again after `from` (a macro called twice, a loop), where the setting then takes effect?
/// The device, axis and extruder order rules stay silent then (RRF201, RRF202, RRF205, RRF209, RRF213).
inline bool runs_again(const Graph& g, const Node& self, NodeId from, NodeId end) {
  if (!repeated_lines(g).repeated(self)) return false;  // it runs once: no walk
  return g.nodes.find_if(from + 1, end, [&](NodeId, const Node& n) {
    return n.kind == NodeKind::Command && n.unit == self.unit && n.index == self.index;
  }) != kNoNode;
}
inline bool runs_again(const NodeContext& cx, NodeId from) {
  return runs_again(cx.graph, cx.self, from, cx.segment().end);
}

/// Per tool number, the M563 nodes that define it with a known P, in node order. Built once per graph
/// (Graph::derived): a config of thousands of tools asked for each G10 which of the thousands of M563 after it
/// comes next, lexing each.
struct M563ByTool {
  std::unordered_map<int64_t, std::vector<NodeId>> by_tool;
};
inline const M563ByTool& m563_by_tool(const Machine& m, const Graph& g) {
  return g.derived<M563ByTool>("tools.m563_by_tool", [&] {
    M563ByTool out;
    each_code_command(m, g, 'M', 563, [&](NodeId id, const Node&, const ParsedFile& pf, const Command& c) {
      if (!m563_defines(pf, c)) return;
      if (auto P = get_int(pf, c, 'P'); P.known()) out.by_tool[P.value].push_back(id);
    });
    return out;
  });
}

/// The later M563 in this segment that defines tool n.
inline NodeId later_m563(const NodeContext& cx, int n) {
  return first_later(cx, m563_by_tool(cx.machine, cx.graph).by_tool, int64_t{n});
}

/// The M584 nodes by the axis letters they name. A card that repeats its M584s thousands of times asked each later
/// one, for each line naming a missing axis.
inline const CodeIndex& m584_by_letter(const Machine& m, const Graph& g) { return code_index(m, g, 'M', 584); }

/// The later M584 in this segment that names axis `letter`.
inline NodeId later_m584_for(const NodeContext& cx, char letter) {
  return first_later(cx, m584_by_letter(cx.machine, cx.graph)[letter]);
}

/// Does any M584 on the card name axis `letter`? A macro run after boot may create the axis.
inline bool any_m584_names(const Machine& m, char letter) {
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const ParsedFile& pf = m.unit(i).parsed;
    for (const Command& c : pf.commands)
      if (c.is('M', 584) && (pf.find(c, letter) || pf.find(c, 'P'))) return true;
  }
  return false;
}

/// Does node `id` run inside a tool-change macro (tfree/tpre/tpost), directly or through M98?
inline bool in_tool_macro(const Graph& g, NodeId id) {
  NodeId e = g.nodes[id].kind == NodeKind::Enter ? id : g.nodes[id].enter;
  while (e != kNoNode) {
    const Node& n = g.nodes[e];
    if (n.call == CallKind::ToolFree || n.call == CallKind::ToolPre || n.call == CallKind::ToolPost) return true;
    e = n.call_site == kNoNode ? kNoNode : g.nodes[n.call_site].enter;
  }
  return false;
}

/// Does node `id` certainly run when config.g runs: outside if/while (here and in its callers), and not in a
/// tool-change macro?
inline bool certain_at_boot(const Graph& g, NodeId id) { return !g.nodes[id].maybe && !in_tool_macro(g, id); }

/// RRF's answer to a G10 for a tool that does not exist (docs/firmware-behaviour.md#g10-forms).
inline std::string invalid_tool_text(Version v, int n) {
  if (v >= kRrf3_4) return "Invalid tool number";
  if (v >= kRrf3_3) return fmt::format("Tool {} not found", n);
  return fmt::format("Attempt to set/report offsets and temperatures for non-existent tool: {}", n);
}

/// A command as written, quoted for a message: 'G10 P0 X0 Y0 Z0'; long commands are cut after a few parameters
/// and end in "…". The one way rules quote a command.
inline std::string quote(const ParsedFile& pf, const Command& c) {
  std::string_view t = pf.text(c.span);
  if (t.size() <= 40) return fmt::format("'{}'", t);
  size_t cut = t.rfind(' ', 36);
  if (cut == std::string_view::npos || cut < pf.text(c.word).size()) cut = 36;
  return fmt::format("'{} …'", utf8_prefix(t, cut));
}

/// The G10 and M568 commands for tool n between the command at `cx` and node `to`, in order; nullopt when an M563
/// for tool n, or a G10, M563 or M568 whose tool is not known, lies between (nothing may move past it).
inline std::optional<std::vector<NodeId>> tool_lines_between(const NodeContext& cx, NodeId to, int n) {
  // The G10, M563 and M568 nodes between, in order, from the code index (not a walk of every node between). More
  // than kMaxBetween of them: nullopt, as for an unknown tool (a fix across hundreds of other tools' lines is no
  // plain move, and asking each of them cost a config of thousands of tools seconds).
  constexpr size_t kMaxBetween = 256;
  std::vector<NodeId> between;
  bool too_many = false;
  auto collect = [&](NodeId id, const NodeCommand&) {
    between.push_back(id);
    too_many = between.size() > kMaxBetween;
    return too_many;
  };
  each_code_node(cx, cx.id + 1, to, 'G', 10, collect);
  if (!too_many) each_code_node(cx, cx.id + 1, to, 'M', {563, 568}, collect);
  if (too_many) return std::nullopt;
  std::sort(between.begin(), between.end());
  std::vector<NodeId> lines;
  for (const NodeId i : between) {
    const NodeCommand nc = command_at(cx.machine, cx.graph, i);
    auto P = get_int(*nc.pf, *nc.c, 'P');
    if (!P.known() || (P.value == n && nc.is('M', 563))) return std::nullopt;
    if (P.value == n) lines.push_back(i);
  }
  return lines;
}

/// Is there a G10, M563 or M568 for tool n (or an unknown tool) between the command at `cx` and node `to`? Then
/// moving the line past it would change which value wins; the later line moves first, in an earlier round.
inline bool same_tool_between(const NodeContext& cx, NodeId to, int n) {
  const auto lines = tool_lines_between(cx, to, n);
  return !lines || !lines->empty();
}

/// The fix that moves the line of the command at `cx`, and the lines of the commands at `also` (later nodes before
/// `target`, in order), to just after the line of the command at `target`, all in one file: delete each whole line
/// with its terminator, insert them in their order after the target line, keeping the file's line endings. Moving
/// them in one fix lets one round of --fix settle a run of lines (one fix per line would insert at the same point,
/// which apply_fixes takes one round at a time). Nullopt when a move is not plainly possible (other commands on a
/// line, conditional blocks, another file).
inline std::optional<Fix> move_lines_after(const NodeContext& cx, const std::vector<NodeId>& also, NodeId target,
                                           std::string title) {
  const Node& here = cx.node();
  const Node& there = cx.graph.nodes[target];
  if (there.kind != NodeKind::Command || there.unit != here.unit) return std::nullopt;
  const FileUnit& u = cx.unit();
  const ParsedFile& pf = u.parsed;
  const SourceFile& src = *u.source;
  const Command& t = pf.commands[there.index];
  const Line& tl = pf.lines[t.line];
  if (tl.conditional || tl.in_loop || tl.indent != 0) return std::nullopt;
  const uint32_t to = src.line_of(t.span.begin);
  const Span tls = src.line_span(to);
  const std::string_view tterm = src.terminator(to);
  const FileId f = src.id();
  Fix fix = Fix::unsafe(std::move(title));
  std::string moved;
  uint32_t last = 0;
  std::string_view fterm;
  for (size_t k = 0; k <= also.size(); ++k) {
    const Node& n = k == 0 ? here : cx.graph.nodes[also[k - 1]];
    if (n.kind != NodeKind::Command || n.unit != here.unit) return std::nullopt;
    const Command& c = pf.commands[n.index];
    const Line& cl = pf.lines[c.line];
    if (cl.command_count != 1 || cl.conditional || cl.in_loop || cl.after_nul || cl.indent != 0) return std::nullopt;
    const uint32_t from = src.line_of(c.span.begin);
    if (from >= to || (k > 0 && from <= last)) return std::nullopt;
    last = from;
    const Span fl = src.line_span(from);
    fterm = src.terminator(from);
    if (fterm.empty()) return std::nullopt;
    fix.edits.push_back(Edit::remove(Location{f, Span{fl.begin, fl.end + static_cast<uint32_t>(fterm.size())}}));
    moved += std::string(src.slice(fl)) + std::string(fterm);
  }
  if (tterm.empty()) {  // the target is the last line: a line ending first, none after the last moved line
    moved.resize(moved.size() - fterm.size());
    fix.edits.push_back(Edit::insert(Location{f, Span{tls.end, tls.end}}, std::string(fterm) + moved));
  } else {
    const uint32_t at = tls.end + static_cast<uint32_t>(tterm.size());
    fix.edits.push_back(Edit::insert(Location{f, Span{at, at}}, moved));
  }
  return fix;
}

/// The fix that moves the line of the command at `cx` alone (move_lines_after).
inline std::optional<Fix> move_line_after(const NodeContext& cx, NodeId target, std::string title) {
  return move_lines_after(cx, {}, target, std::move(title));
}

/// Is this node's command a G10 in tool form or an M568 that sets tool settings (3.3+)?
inline bool sets_tool_settings(const NodeContext& cx) {
  if (cx.is('G', 10)) return cx.g10_form() == G10Form::Tool;
  return cx.is('M', 568) && cx.state.firmware >= kRrf3_3;
}

/// A tool that certainly exists, with certain heaters, or nullptr.
inline const Tool* certain_tool(const MachineState& s, int n) {
  const Tool* t = s.tool(n);
  return t && !t->maybe && t->heaters_known && !s.unknown_baseline ? t : nullptr;
}

/// The tool whose temperatures a G10/M568 at this node sets, when the command certainly runs, sets R or S,
/// and names a tool that certainly exists; nullptr otherwise.
inline const Tool* temperature_tool(const NodeContext& cx) {
  if (!cx.is_command() || !cx.certain()) return nullptr;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  if (!sets_tool_settings(cx)) return nullptr;
  if (!pf.find(c, 'R') && !pf.find(c, 'S')) return nullptr;
  const ToolRef ref = addressed_tool(pf, c, cx.state);
  if (!ref.known || ref.number < 0) return nullptr;
  return certain_tool(cx.state, ref.number);
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

/// Is this ToolSelect node a `T-1` (deselect, uses no tool)?
inline bool is_deselect(const Machine& m, const Graph& g, NodeId id) {
  const Node& n = g.nodes[id];
  if (n.call_site == kNoNode) return false;
  NodeCommand nc = command_at(m, g, n.call_site);
  return nc && nc.c->letter == 'T' && !nc.c->number_expr && nc.c->has_number && nc.c->number < 0;
}

}  // namespace rrflint::tools
