// The G10 rules about a tool offset line without Z (RRF306 g10-missing-z, RRF331 g10-implicit-z): which tool and
// Z offset such a line leaves, whether the Z is set again before the tool is used, and the fix that appends it.
#pragma once

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "rules/tool_helpers.h"

namespace rrflint::tools {

/// A tool-offset G10 that sets other axes but not Z (RRF306, RRF331): the tool and its Z offset before the line.
struct MissingZ {
  int tool = -1;
  const Tool* t = nullptr;
  Fact z;
  bool probed = false;  // loaded by M501 or measured by M585
};

/// For z_set_later, built once per graph (Graph::derived): the nodes that set a tool's Z or re-create it (a G10
/// with Z in the tool form, an M563 that defines a tool), and the T nodes that select one, by tool number; those of
/// an unknown tool apart. A config of thousands of G10 lines without Z walked, for each, every node after it.
struct ZSetters {
  std::unordered_map<int64_t, std::vector<NodeId>> set_by_tool, select_by_tool;
  std::vector<NodeId> set_unknown, select_unknown;  // P{expr}: may be any tool; T{expr} (not a deselect)
};
inline const ZSetters& z_setters(const NodeContext& cx) {
  const Version fw = cx.state.firmware;
  return cx.graph.derived<ZSetters>("tools.z_setters." + fw.str(), [&] {
    ZSetters out;
    for (const int number : {10, 563})
      each_code_command(cx.machine, cx.graph, number == 10 ? 'G' : 'M', number,
                        [&](NodeId id, const Node&, const ParsedFile& pf, const Command& c) {
                          auto P = get_int(pf, c, 'P');
                          if (!P.present()) return;
                          bool sets = false;
                          if (number == 563) {
                            sets = m563_defines(pf, c);
                          } else if (pf.find(c, 'Z')) {
                            const G10Form f = g10_form(pf, c, nullptr, fw);  // P is present: never Unknown for axes
                            sets = f == G10Form::Tool || f == G10Form::Unknown;
                          }
                          if (!sets) return;
                          if (P.known()) out.set_by_tool[P.value].push_back(id);
                          else out.set_unknown.push_back(id);
                        });
    for (auto& [tool, ids] : out.set_by_tool) std::sort(ids.begin(), ids.end());
    std::sort(out.set_unknown.begin(), out.set_unknown.end());
    cx.graph.nodes.each_whole([&](NodeId id, const Node& n) {
      if (n.kind != NodeKind::ToolSelect) return;
      if (n.index != kNoToolNumber) out.select_by_tool[n.index].push_back(id);
      else if (!is_deselect(cx.machine, cx.graph, id)) out.select_unknown.push_back(id);
    });
    return out;
  });
}

/// The nodes z_set_later has walked so far in a graph (Graph::derived): past a budget it asks the index instead.
struct ZWalked {
  std::shared_ptr<std::atomic<uint64_t>> nodes = std::make_shared<std::atomic<uint64_t>>(0);
};

/// Is tool n's Z set again (or the tool re-created) later in this segment before a T selects it?
inline bool z_set_later(const NodeContext& cx, int n) {
  // The first T that selects tool n (or may: T{…}), or the first M563 / G10 that sets its Z, decides. It is
  // usually a few lines on, so the nodes are walked to it, as long as all the walks of the graph stay within a
  // budget of half its nodes (and 64 Ki more). Past that (thousands of G10 lines without Z and no T between), the
  // index answers: built once, it costs a lexing of every G10 and M563 (25 ms in a 100 MB config), more than the
  // walks of a real config.
  std::atomic<uint64_t>& walked = *cx.graph.derived<ZWalked>("tools.z_walked", [] { return ZWalked{}; }).nodes;
  const uint64_t budget = cx.graph.nodes.size() / 2 + 65536;
  const NodeId end = cx.segment().end;
  const uint64_t left = budget - std::min(budget, walked.load(std::memory_order_relaxed));
  const NodeId walk_end = end - cx.id - 1 > left ? static_cast<NodeId>(cx.id + 1 + left) : end;
  bool set = false;
  const NodeId decided = cx.graph.nodes.find_if(cx.id + 1, walk_end, [&](NodeId i, const Node& node) {
    if (node.kind == NodeKind::ToolSelect)
      return node.index == static_cast<uint32_t>(n) ||
             (node.index == kNoToolNumber && !is_deselect(cx.machine, cx.graph, i));
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
      const G10Form f = g10_form(pf, c, nullptr, cx.state.firmware);  // P is present: never Unknown for axes
      if (f == G10Form::Tool || f == G10Form::Unknown) set = true;
    }
    return set;
  });
  walked.fetch_add(decided != kNoNode ? decided - cx.id : walk_end - cx.id - 1, std::memory_order_relaxed);
  if (decided != kNoNode || walk_end == end) return set;
  const ZSetters& z = z_setters(cx);
  const NodeId stop = std::min(first_later(cx, z.select_by_tool, int64_t{n}), first_later(cx, z.select_unknown));
  const NodeId first_set = std::min(first_later(cx, z.set_by_tool, int64_t{n}), first_later(cx, z.set_unknown));
  return first_set < stop;  // kNoNode (none in the segment) is never less
}

inline std::optional<MissingZ> missing_z(const NodeContext& cx) {
  if (!cx.is('G', 10) || !cx.certain()) return std::nullopt;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (s.running_m501) return std::nullopt;  // config-override.g: M500 writes only the probed axes, on purpose
  if (cx.g10_form() != G10Form::Tool) return std::nullopt;
  const ToolRef ref = addressed_tool(pf, c, s);
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
  const uint32_t end = cx.command().span.end;
  return Fix::safe(fmt::format("append 'Z{}'", value), Edit::insert(cx.at(Span{end, end}), " Z" + value));
}

}  // namespace rrflint::tools
