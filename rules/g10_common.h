// Helpers shared by the G10 and tool rules (RRF202, RRF301–RRF306, RRF331): how RRF dispatches a G10, which
// tool it names, look-ahead in the command graph, and the "move this line after that one" fix.
#pragma once

#include <fmt/format.h>

#include <optional>
#include <string>
#include <string_view>

#include "lint/engine/rule.h"

namespace rrflint::g10 {

/// The form RRF gives a G10 (docs/firmware-behaviour.md#g10-forms; GCodes2.cpp case 10).
enum class Form : uint8_t {
  Tool,       // tool offsets/temperatures (L1, or P/R/S/a visible axis letter)
  Workplace,  // L2 / L20
  Retract,    // none of the above: firmware retraction
  BadL,       // another L: `Bad or missing parameter`
  Unknown,    // L from an expression, or axes not known
};

/// Is `letter` an axis letter on this target, whether or not the axis exists?
inline bool is_axis_letter(char letter, const MachineState& s) {
  if (letter >= 'a' && letter <= 'z') {
    const char hi = highest_lowercase_axis(s.board, s.firmware);
    return hi != 0 && letter <= hi;
  }
  const std::string_view upper = s.firmware < Version(3, 0, 0, 0, 0) ? "XYZUVWABC" : "XYZUVWABCD";
  return letter != 0 && upper.find(letter) != std::string_view::npos;
}

inline bool axis_visible(const MachineState& s, char letter) { return s.axis_visible(s.axis_index(letter)); }

/// "U" or "'a", as the letter is written in a command.
inline std::string axis_name(char letter) {
  return letter >= 'a' && letter <= 'z' ? std::string("'") + letter : std::string(1, letter);
}

inline Form classify(const ParsedFile& pf, const Command& c, const MachineState& s) {
  auto L = get_int(pf, c, 'L');
  if (L.present()) {
    if (!L.known()) return Form::Unknown;
    if (L.value == 1) return Form::Tool;
    if (L.value == 2 || L.value == 20) return Form::Workplace;
    return Form::BadL;
  }
  if (pf.find(c, 'P') || pf.find(c, 'R') || pf.find(c, 'S')) return Form::Tool;
  if (s.firmware >= Version(3, 3, 0, 0, 0) && s.firmware < Version(3, 5, 0, 0, 0) && pf.find(c, 'F'))
    return Form::Tool;  // 3.3–3.4.x count F as well
  for (int i = 0; i < s.visible_axes && i < static_cast<int>(s.axes.size()); ++i)
    if (pf.find(c, s.axes[static_cast<size_t>(i)].letter)) return Form::Tool;
  if (!s.axes_known || s.unknown_baseline) return Form::Unknown;
  return Form::Retract;
}

/// The tool a G10/M568 acts on: P, or the current tool.
struct ToolRef {
  int number = -1;
  bool known = false;
  bool explicit_p = false;
};

inline ToolRef tool_ref(const ParsedFile& pf, const Command& c, const MachineState& s) {
  auto P = get_int(pf, c, 'P');
  if (P.known()) return {static_cast<int>(P.value), true, true};
  if (P.present()) return {-1, false, true};
  return {s.current_tool, s.current_tool_known && !s.unknown_baseline, false};
}

/// The command of a graph node, or nullptr for Enter/Leave/ToolSelect nodes.
struct NodeCommand {
  const ParsedFile* pf = nullptr;
  std::optional<Command> c;
  explicit operator bool() const { return c.has_value(); }
  bool is(char letter, int number) const { return c && c->letter == letter && c->number == number && c->fraction < 0; }
};

inline NodeCommand command_at(const Machine& m, const Node& n) {
  if (n.kind != NodeKind::Command) return {};
  const ParsedFile& pf = m.unit(n.unit).parsed;
  return {&pf, pf.commands[n.index]};
}
inline NodeCommand command_at(const Machine& m, const Graph& g, NodeId id) { return command_at(m, g.nodes[id]); }

/// Does this M563 define (create or re-create) a tool, rather than report one?
inline bool m563_defines(const ParsedFile& pf, const Command& c) {
  for (char L : {'S', 'D', 'H', 'X', 'Y', 'Z', 'F', 'R'})
    if (pf.find(c, L)) return true;
  return false;
}

/// The first command node after this one in its segment with code `letter` `number` (no fraction) for which
/// `pred(command)` holds; kNoNode if none. Other commands are passed over on their code alone.
template <class Pred>
NodeId find_later(const NodeContext& cx, char letter, int number, Pred pred) {
  return cx.graph.nodes.find_if(cx.id + 1, cx.segment().end, [&](NodeId, const Node& n) {
    if (n.kind != NodeKind::Command) return false;
    const ParsedFile& pf = cx.machine.unit(n.unit).parsed;
    const CommandTable::Code code = pf.commands.code(n.index);
    return code.letter == letter && code.number == number && code.fraction < 0 && pred(NodeCommand{&pf, pf.commands[n.index]});
  });
}

/// The later M563 in this segment that defines tool n.
inline NodeId later_m563(const NodeContext& cx, int n) {
  return find_later(cx, 'M', 563, [&](const NodeCommand& nc) {
    if (!m563_defines(*nc.pf, *nc.c)) return false;
    auto P = get_int(*nc.pf, *nc.c, 'P');
    return P.known() && P.value == n;
  });
}

/// The later M584 in this segment that names axis `letter`.
inline NodeId later_m584_for(const NodeContext& cx, char letter) {
  return find_later(cx, 'M', 584, [&](const NodeCommand& nc) { return nc.pf->find(*nc.c, letter) != nullptr; });
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

/// The lower-cased file name of an SD path ("/sys/tpost0.g" -> "tpost0.g").
inline std::string base_name(std::string_view sd_path) {
  const size_t slash = sd_path.rfind('/');
  return to_lower(sd_path.substr(slash == std::string_view::npos ? 0 : slash + 1));
}

/// Is this file one of tool n's change macros (tfree<n>.g, tpre<n>.g, tpost<n>.g)? They run only for a tool
/// that exists.
inline bool is_tool_macro_for(std::string_view sd_path, int n) {
  const std::string b = base_name(sd_path), num = std::to_string(n) + ".g";
  return b == "tfree" + num || b == "tpre" + num || b == "tpost" + num;
}

/// RRF's answer to a G10 for a tool that does not exist, by version (docs/firmware-behaviour.md#g10-forms).
inline std::string invalid_tool_text(Version v, int n) {
  if (v >= Version(3, 4, 0, 0, 0)) return "Invalid tool number";
  if (v >= Version(3, 3, 0, 0, 0)) return fmt::format("Tool {} not found", n);
  return fmt::format("Attempt to set/report offsets and temperatures for non-existent tool: {}", n);
}

/// A command as quoted in a message: the word and its first parameters, "…" when there are more.
inline std::string quote(const ParsedFile& pf, const Command& c, uint32_t max_params = 3) {
  std::string out(pf.text(c.word));
  uint32_t shown = 0;
  for (auto p = pf.params(c).begin(); p != ParamRange::iterator(); ++p) {
    if (shown == max_params) {
      out += " …";
      break;
    }
    out += ' ';
    out += pf.text(p->span);
    ++shown;
  }
  return out;
}

/// "G10 P3": the command word and its P parameter.
inline std::string quote_with_p(const ParsedFile& pf, const Command& c) {
  std::string out(pf.text(c.word));
  if (ParamRef p = pf.find(c, 'P')) out += " " + std::string(pf.text(p->span));
  return out;
}

/// Is there a G10, M563 or M568 for tool n (or an unknown tool) between the command at `cx` and node `to`? Then
/// moving the line past it would change which value wins; the later line moves first, in an earlier round.
inline bool same_tool_between(const NodeContext& cx, NodeId to, int n) {
  for (NodeId i = cx.id + 1; i < to; ++i) {
    NodeCommand nc = command_at(cx.machine, cx.graph, i);
    if (!nc.is('G', 10) && !nc.is('M', 563) && !nc.is('M', 568)) continue;
    auto P = get_int(*nc.pf, *nc.c, 'P');
    if (!P.known() || P.value == n) return true;
  }
  return false;
}

/// The fix that moves the line of the command at `cx` to just after the line of the command at `target`, both in
/// the same file: delete the whole line with its terminator, insert it after the target line, keeping the
/// file's line ending. Nullopt when the move is not plainly possible (other commands on the line, conditional
/// blocks, another file).
inline std::optional<Fix> move_line_after(const NodeContext& cx, NodeId target, std::string title) {
  const Node& here = cx.node();
  const Node& there = cx.graph.nodes[target];
  if (there.kind != NodeKind::Command || there.unit != here.unit) return std::nullopt;
  const FileUnit& u = cx.unit();
  const ParsedFile& pf = u.parsed;
  const SourceFile& src = *u.source;
  const Command& c = cx.command();
  const Command& t = pf.commands[there.index];
  const Line& cl = pf.lines[c.line];
  const Line& tl = pf.lines[t.line];
  if (cl.command_count != 1 || cl.conditional || cl.in_loop || cl.after_nul || cl.indent != 0) return std::nullopt;
  if (tl.conditional || tl.in_loop || tl.indent != 0) return std::nullopt;
  const uint32_t from = src.line_of(c.span.begin), to = src.line_of(t.span.begin);
  if (to <= from) return std::nullopt;
  const Span fl = src.line_span(from), tls = src.line_span(to);
  const std::string_view fterm = src.terminator(from), tterm = src.terminator(to);
  if (fterm.empty()) return std::nullopt;
  const std::string line(src.slice(fl));
  Fix fix;
  fix.title = std::move(title);
  fix.applicability = Applicability::Unsafe;
  const FileId f = src.id();
  fix.edits.push_back(Edit{Location{f, Span{fl.begin, fl.end + static_cast<uint32_t>(fterm.size())}}, ""});
  if (tterm.empty()) {
    fix.edits.push_back(Edit{Location{f, Span{tls.end, tls.end}}, std::string(fterm) + line});
  } else {
    const uint32_t at = tls.end + static_cast<uint32_t>(tterm.size());
    fix.edits.push_back(Edit{Location{f, Span{at, at}}, line + std::string(fterm)});
  }
  return fix;
}

/// A tool-offset G10 that sets other axes but not Z (RRF306, RRF331): the tool and its Z offset before the line.
struct MissingZ {
  int tool = -1;
  const Tool* t = nullptr;
  Fact z;
  bool probed = false;  // loaded by M501 or measured by M585
};

/// Is this ToolSelect node a `T-1` (deselect, uses no tool)?
inline bool is_deselect(const Machine& m, const Graph& g, NodeId id) {
  const Node& n = g.nodes[id];
  if (n.call_site == kNoNode) return false;
  NodeCommand nc = command_at(m, g, n.call_site);
  return nc && nc.c->letter == 'T' && !nc.c->number_expr && nc.c->has_number && nc.c->number < 0;
}

/// Is tool n's Z set again (or the tool re-created) later in this segment before a T selects it?
inline bool z_set_later(const NodeContext& cx, int n) {
  // Walks on to the first T that selects tool n (or may: T{…}), or the first M563 / G10 that sets its Z.
  bool set = false;
  cx.graph.nodes.find_if(cx.id + 1, cx.segment().end, [&](NodeId i, const Node& node) {
    if (node.kind == NodeKind::ToolSelect)
      return node.index == static_cast<uint32_t>(n) || (node.index == UINT32_MAX && !is_deselect(cx.machine, cx.graph, i));
    if (node.kind != NodeKind::Command) return false;
    const ParsedFile& pf = cx.machine.unit(node.unit).parsed;
    const CommandTable::Code code = pf.commands.code(node.index);
    const bool m563 = code.letter == 'M' && code.number == 563 && code.fraction < 0;
    const bool g10 = code.letter == 'G' && code.number == 10 && code.fraction < 0;
    if (!m563 && !g10) return false;
    const Command c = pf.commands[node.index];
    auto P = get_int(pf, c, 'P');
    const bool this_tool = P.present() && (!P.known() || P.value == n);  // an unknown P may be this tool
    if (m563 && m563_defines(pf, c) && this_tool) set = true;
    if (g10 && this_tool && pf.find(c, 'Z')) {
      auto L = get_int(pf, c, 'L');
      if (!L.present() || !L.known() || L.value == 1) set = true;
    }
    return set;
  });
  return set;
}

inline std::optional<MissingZ> missing_z(const NodeContext& cx) {
  if (!cx.is('G', 10) || cx.runs < 2) return std::nullopt;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (s.running_m501) return std::nullopt;  // config-override.g: M500 writes only the probed axes, on purpose
  if (classify(pf, c, s) != Form::Tool) return std::nullopt;
  const ToolRef ref = tool_ref(pf, c, s);
  if (!ref.known || ref.number < 0) return std::nullopt;
  const Tool* t = s.tool(ref.number);
  if (!t || t->maybe) return std::nullopt;
  const int z = s.axis_index('Z');
  if (z < 0 || z >= kMaxAxisSlots || !s.axis_visible(z) || pf.find(c, 'Z')) return std::nullopt;
  bool other = false;
  for (int i = 0; i < s.visible_axes && i < static_cast<int>(s.axes.size()) && !other; ++i)
    other = i != z && pf.find(c, s.axes[static_cast<size_t>(i)].letter) != nullptr;
  if (!other || z_set_later(cx, ref.number)) return std::nullopt;
  MissingZ m;
  m.tool = ref.number;
  m.t = t;
  m.z = t->offsets[static_cast<size_t>(z)];
  m.probed = t->probed[static_cast<size_t>(z)];
  return m;
}

/// The fix that appends ` Z<value>` to the G10 at `cx`, right after its last parameter.
inline Fix append_z(const NodeContext& cx, const std::string& value) {
  Fix fix;
  fix.title = fmt::format("append 'Z{}'", value);
  fix.applicability = Applicability::Safe;
  const uint32_t end = cx.command().span.end;
  fix.edits.push_back(Edit{cx.at(Span{end, end}), " Z" + value});
  return fix;
}

}  // namespace rrflint::g10
