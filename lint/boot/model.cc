#include "lint/boot/model.h"

#include <algorithm>

#include "lint/boot/commands.h"
#include "lint/boot/model_commands.h"

namespace rrflint {

int MachineState::axis_index(char letter) const {
  for (size_t i = 0; i < axes.size(); ++i)
    if (axes[i].letter == letter) return static_cast<int>(i);
  return -1;
}

std::string MachineState::axis_letters(uint32_t bits) const {
  std::string out;
  for (int i = 0; i < 32; ++i) {
    if (!(bits & (1u << i))) continue;
    if (!out.empty()) out += '+';
    if (i < static_cast<int>(axes.size())) {
      if (axes[static_cast<size_t>(i)].letter >= 'a') out += '\'';
      out += axes[static_cast<size_t>(i)].letter;
    } else {
      out += "#" + std::to_string(i);
    }
  }
  return out.empty() ? "(none)" : out;
}

ModelBuilder::ModelBuilder(const Machine& m, const Graph& g, Version fw, Board board)
    : m_(m), g_(g), fw_(fw), board_(board), exec_(g.nodes.size(), Runs::Yes) {}

MachineState ModelBuilder::initial_state() const {
  MachineState s;
  s.firmware = fw_;
  s.board = board_;
  for (char L : {'X', 'Y', 'Z'}) {
    Axis a;
    a.letter = L;
    a.drivers = {DriverId{0, static_cast<uint16_t>(L - 'X'), false}};
    s.axes.push_back(a);
  }
  s.visible_axes = 3;
  s.axes[2].drive.steps.value = fw_ >= kRrf3_5 ? 800 : 4000;  // DefaultZDriveStepsPerUnit
  for (DriveSettings& d : s.extruder_drive) d.steps.value = 420;
  if (fw_ < kRrf3_0) {
    // RRF 2 has default extruders, heaters and fans; what exists depends on the board.
    s.extruders_known = false;
    s.heaters_known = s.fans_known = s.sensors_known = false;
    s.extruders = 2;
  } else {
    s.extruders = default_extruders(fw_);
  }
  return s;
}

void ModelBuilder::decide(const MachineState& s, NodeId id, const Node& n) {
  Runs parent = n.enter == kNoNode ? Runs::Yes : exec_[n.enter];
  if (n.kind == NodeKind::Enter && n.call_site != kNoNode) parent = exec_[n.call_site];
  Runs e = std::min(parent, n.maybe ? Runs::Maybe : Runs::Yes);
  if (n.kind == NodeKind::Enter && (n.call == CallKind::ToolPre || n.call == CallKind::ToolPost)) {
    const int t = static_cast<int>(n.index);
    if (s.tool_certainly_absent(t)) e = Runs::No;
    else if (!s.tool(t) || s.tool(t)->maybe || !s.tools_known) e = std::min(e, Runs::Maybe);
  }
  exec_[id] = e;
}

void ModelBuilder::decide_commands(const MachineState& s, NodeId begin, NodeId end, const Node& n) {
  decide(s, begin, n);  // a command's decision depends only on its file run and maybe: the run's first decides all
  std::fill(exec_.begin() + begin + 1, exec_.begin() + end, exec_[begin]);
}

void ModelBuilder::step(MachineState& s, NodeId id, const Node& n) const {
  const Runs e = exec_[id];
  if (e == Runs::No) return;
  switch (n.kind) {
    case NodeKind::Enter:
      if (n.call == CallKind::M501) {
        s.running_m501 = true;
        s.m501 = n.call_site;
      }
      enter_tool_macro(s, n, e);
      return;
    case NodeKind::Leave:
      if (n.call == CallKind::M501) s.running_m501 = false;
      return;
    case NodeKind::ToolSelect: {
      if (e == Runs::Yes && n.index == kNoToolNumber && n.call_site != kNoNode) {
        const Node& site = g_.nodes[n.call_site];
        const Command& c = m_.unit(site.unit).parsed.commands[site.index];
        if (c.has_number && c.number < 0) {  // T-1: no tool is selected afterwards
          s.current_tool = kNoTool;
          s.current_tool_known = true;
          s.current_tool_set = n.call_site;
          return;
        }
      }
      if (e == Runs::Maybe || n.index == kNoToolNumber) {
        s.current_tool_known = false;
        s.current_tool_set = n.call_site;
        return;
      }
      const int t = static_cast<int>(n.index);
      const Tool* tool = s.tool(t);
      s.current_tool = tool ? t : kNoTool;  // selecting a tool that does not exist selects none, silently
      s.current_tool_known = tool ? !tool->maybe : (s.tools_known && !s.unknown_baseline);
      s.current_tool_set = n.call_site;
      return;
    }
    case NodeKind::Command: apply_command(s, id, n); return;
  }
}

// A tool-change macro runs only when its tool exists: inside tpre<n>.g no tool is current (the old one is
// deselected, n not yet selected); inside tfree<n>.g and tpost<n>.g tool n is. A call from a T at boot knows the
// tool from the T; a macro linted after boot (an entry) takes it from its name, and when the boot did not certainly
// create tool n, the tools are unknown (it exists whenever the macro runs).
void ModelBuilder::enter_tool_macro(MachineState& s, const Node& n, Runs e) const {
  if (n.call == CallKind::ToolPre) {
    s.current_tool = kNoTool;
    s.current_tool_known = e == Runs::Yes;
    s.current_tool_set = n.call_site;
    return;
  }
  if (n.call != CallKind::Entry) return;
  int t = -1;
  const FileRole role = file_role(m_.unit(n.unit).sd_path, &t);
  if (!is_tool_change_role(role)) return;
  const Tool* tool = t >= 0 ? s.tool(t) : nullptr;
  if (!tool || tool->maybe) {
    if (t >= 0) s.tools_known = false;
    s.current_tool_known = false;
    s.current_tool_set = kNoNode;
    return;
  }
  s.current_tool = role == FileRole::ToolPre ? kNoTool : t;
  s.current_tool_known = true;
  s.current_tool_set = kNoNode;
}

void ModelBuilder::apply_command(MachineState& s, NodeId id, const Node& n) const {
  const FileUnit& u = m_.unit(n.unit);
  // Most commands change nothing here (moves, settings): their code is read from the record alone.
  const CommandTable::Code code = u.parsed.commands.code(n.index);
  if (!changes_state(code)) return;
  if (code.is('M', 98) && g_.evaluated(id)) return;  // the graph followed it: its effects are the file's own
  interpret_command(s, u.parsed, u.parsed.commands[n.index], id, exec_[id] == Runs::Maybe);
}

}  // namespace rrflint
