// RRF402 override-after-m501: a command after M501 that replaces a value config-override.g loaded.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"
#include "rules/lex_common.h"
#include "rules/override_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF402",
    .name = "override-after-m501",
    .severity = Severity::Warning,
    .summary = "A command after M501 replaces a value that config-override.g loaded: the saved setting is lost.",
    .docs = R"md(
## What it does
Reports a command in the boot sequence, after the `M501`, that sets again something config-override.g has just
loaded, with a different value. It judges by the file's content, so it stays silent when the card has no
config-override.g, and it reports only what a line of that file set and what still holds when the command runs:
- `G10 L2 P<n>` for a workplace origin the file set (M500 always writes workplaces 1 to 9);
- `G10 P<n>` (or a G10 for the current tool) for an axis offset of tool n that the file set;
- `M563 P<n>` that re-creates tool n, whose offsets the file set (re-creating a tool resets them to 0);
- `M307 H<n>` for a heater whose model the file set, when the heater existed at the M501;
- `G31` for a probe, and `M208` for an axis limit, only when the file holds such a line.

The finding names the values lost; notes point at the lines of config-override.g and at the `M501`.

It stays silent when the later command sets the same value (`G10 L2 P1 X0` after a loaded `X0.00`), on unknown
values (`{…}`), for a command in an `if` or a loop, for an M501 in an `if` (what it loads is then not known),
for a value the file set but that an earlier command after the M501 already replaced (that one is reported), for
lines of the override that failed (a tool or heater created only after the M501: see
[m501-too-early](m501-too-early.md)), in tool-change macros, in macros run after boot, and after an `M98 P"config-override.g"` (that is
[override-via-m98](override-via-m98.md)'s finding). Setting the values
*before* the M501 (`G10 P0 X0 Y0 Z0` then `M501`) is the right order and is not reported.

## Why is this bad?
M500 saves the values tuned on the machine (heater models from `M303`, probed tool offsets from `M585`,
workplace origins, probe and axis limits) into config-override.g, and `M501` reads them back. Its lines run when
the M501 runs, and later commands win: whatever config.g sets after the M501 replaces the tuned values at every
boot, and the next `M500` then saves config.g's value. The documentation says to put M501 at the end of config.g.

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
M501
G10 P0 X0 Y0 Z0
; file: sys/config-override.g
G10 P0 X22.340 Y41.620 Z-12.240
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 D0
G10 P0 X0 Y0 Z0
M501
; file: sys/config-override.g
G10 P0 X22.340 Y41.620 Z-12.240
```

## Fix safety
There is no fix: whether the line is a default to move before the M501 or a stale setting to delete is the
user's choice.

## References
- rrflint: [Saved settings: M500, M501, M502](../firmware-behaviour.md#saved-settings-m500-m501-m502)
- Duet3D G-code dictionary: [M500](https://docs.duet3d.com/User_manual/Reference/Gcodes#m500-store-parameters), [M501](https://docs.duet3d.com/User_manual/Reference/Gcodes#m501-read-stored-parameters) ("Ensure that M501 is at the end of config.g")
- RepRapFirmware 3.5: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes.cpp) (`WriteConfigOverrideFile()`), [GCodes5.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes5.cpp) (`WriteToolParameters()`)
)md",
};

using override_file::Run;

/// What a later command replaces of the values the run loaded: the letters (axes or parameters), each with the
/// value loaded, and the nodes of config-override.g that loaded them.
struct Replaced {
  std::string letters;
  std::vector<std::string> values;
  std::vector<NodeId> origins;
  void add(char letter, std::string value, NodeId origin) {
    letters += letter;
    values.push_back(std::move(value));
    if (std::find(origins.begin(), origins.end(), origin) == origins.end()) origins.push_back(origin);
  }
};

/// Reports "'<command>' after M501 <what> that config-override.g loaded (<values>): <advice>".
void report(const NodeContext& cx, Sink& out, const Run& run, const Replaced& r, const std::string& what,
            const std::string& advice) {
  std::string vals;
  for (size_t i = 0; i < r.values.size(); ++i) vals += (i ? ", " : "") + r.values[i];
  Report rep = out.report(kMeta, cx.at(cx.command().span),
                          fmt::format("{} after M501 {} that config-override.g loaded ({}): {}",
                                      tools::quote(cx.parsed(), cx.command()), what, vals, advice));
  for (const NodeId o : r.origins) rep.note(cx.where(o), "config-override.g loads the saved value here");
  rep.note(cx.where(run.m501), "M501 runs config-override.g here");
}

/// A fact loaded by the run (known, set by one of its lines) that `v` replaces with a different value.
bool replaces(const Run& run, const Fact& f, double v) {
  return run.holds(f.origin) && f.known && std::fabs(f.value - v) > 1e-9;
}

void check_tool_offsets(const NodeContext& cx, Sink& out, const Run& run) {
  const ParsedFile& pf = cx.parsed();
  const MachineState& s = cx.state;
  const ToolRef ref = addressed_tool(pf, cx.command(), s);
  if (!ref.known || ref.number < 0) return;
  const Tool* t = s.tool(ref.number);
  if (!t || t->maybe) return;
  Replaced r;
  for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i) {
    const char letter = s.axes[static_cast<size_t>(i)].letter;
    auto v = get_float(pf, cx.command(), letter);
    if (v.unknown()) return;
    const Fact& f = t->offsets[static_cast<size_t>(i)];
    if (v.known() && t->probed[static_cast<size_t>(i)] && replaces(run, f, v.value))
      r.add(letter, override_file::number(f.value), f.origin);
  }
  if (r.letters.empty()) return;
  report(cx, out, run, r,
         fmt::format("replaces tool {}'s {} offset{}", ref.number, override_file::letter_list(r.letters),
                     r.letters.size() > 1 ? "s" : ""),
         "the offsets M500 saved are lost at every boot; set them before the M501, or delete this line");
}

void check_workplace(const NodeContext& cx, Sink& out, const Run& run) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  auto L = get_int(pf, c, 'L');
  if (!L.known() || L.value != 2) return;  // L20 sets the origin from the position: not known here
  auto P = get_int(pf, c, 'P');
  int slot = P.known() ? static_cast<int>(P.value) : (P.absent() ? 1 : -1);  // as the model reads it
  if (slot == 0) slot = 1;
  if (slot < 1 || slot > 9) return;
  Replaced r;
  for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i) {
    const char letter = s.axes[static_cast<size_t>(i)].letter;
    auto v = get_float(pf, c, letter);
    if (v.unknown()) return;
    const Fact& f = s.workplaces[static_cast<size_t>(slot)].origin[static_cast<size_t>(i)];
    if (v.known() && replaces(run, f, v.value)) r.add(letter, override_file::number(f.value), f.origin);
  }
  if (r.letters.empty()) return;
  report(cx, out, run, r,
         fmt::format("replaces the {} origin of workplace {}", override_file::letter_list(r.letters), slot),
         "the origin M500 saved is lost at every boot; set it before the M501, or delete this line");
}

void check_g10(const NodeContext& cx, Sink& out, const Run& run) {
  const G10Form form = cx.g10_form();
  if (form == G10Form::Workplace) check_workplace(cx, out, run);
  if (form == G10Form::Tool) check_tool_offsets(cx, out, run);
}

void check_m563(const NodeContext& cx, Sink& out, const Run& run) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  auto P = get_int(pf, c, 'P');
  if (!m563_defines(pf, c) || !P.known()) return;
  const Tool* t = cx.state.tool(static_cast<int>(P.value));
  if (!t || t->maybe) return;
  Replaced r;
  const MachineState& s = cx.state;
  for (int i = 0; i < s.visible_axes && i < kMaxAxisSlots; ++i)
    if (t->probed[static_cast<size_t>(i)] && replaces(run, t->offsets[static_cast<size_t>(i)], 0))
      r.add(s.axes[static_cast<size_t>(i)].letter, override_file::number(t->offsets[static_cast<size_t>(i)].value),
            t->offsets[static_cast<size_t>(i)].origin);
  if (r.letters.empty()) return;
  report(cx, out, run, r,
         fmt::format("re-creates tool {}, which resets to 0 its {} offset{}", P.value,
                     override_file::letter_list(r.letters), r.letters.size() > 1 ? "s" : ""),
         "define the tool before the M501");
}

/// Is there a command between the run and this node that sets the same thing (so the loaded value is gone already
/// and that command was judged)? `same` is asked of every command of code `letter` `number`.
template <class Same>
bool set_between(const NodeContext& cx, const Run& run, char letter, int number, Same same) {
  return tools::each_code_node(cx, run.leave + 1, cx.id, letter, number,
                               [&](NodeId, const tools::NodeCommand& k) { return same(k); }) != kNoNode;
}

/// Did the device (created at `created`, kNoNode: it always existed) exist when the line `loaded` ran?
bool existed_at(NodeId created, NodeId loaded) { return created == kNoNode || created < loaded; }

/// A command that sets parameters of one device (M307 H: a heater model, G31 K: a probe) against the last line of
/// the run that set the same device. `letters` are the parameters compared.
void check_device(const NodeContext& cx, Sink& out, const Run& run, NodeId loaded, std::string_view letters,
                  const std::string& what, const std::string& advice) {
  if (loaded == kNoNode) return;
  const tools::NodeCommand self = tools::command_at(cx.machine, cx.graph, cx.id);
  const tools::NodeCommand from = tools::command_at(cx.machine, cx.graph, loaded);
  bool unknown = false;
  const std::string diff = override_file::differing(self, from, letters, unknown);
  if (unknown || diff.empty()) return;
  Replaced r;
  for (const char l : diff)
    r.add(l, fmt::format("{}{}", l, clip(from.pf->text(from.pf->find(*from.c, l)->value))), loaded);
  report(cx, out, run, r, what, advice);
}

void check_m307(const NodeContext& cx, Sink& out, const Run& run) {
  const heat::DeviceRef h = heat::heater_named(cx.parsed(), cx.command());
  if (!h.known) return;
  auto it = cx.state.heaters.find(h.number);
  if (it == cx.state.heaters.end() || it->second.maybe) return;
  auto same = [&](const tools::NodeCommand& k) {
    const heat::DeviceRef o = heat::heater_named(*k.pf, *k.c);
    return !o.known || o.number == h.number;
  };
  const NodeId loaded = override_file::last_in_run(cx, run, 'M', 307, same);
  if (loaded == kNoNode || !existed_at(it->second.created, loaded) || set_between(cx, run, 'M', 307, same)) return;
  check_device(cx, out, run, loaded, "RKDESBVAC", fmt::format("replaces heater {}'s model", h.number),
               "the tuning M303 and M500 saved is not used; delete this line, or put it before the M501");
}

void check_g31(const NodeContext& cx, Sink& out, const Run& run) {
  auto K = get_int(cx.parsed(), cx.command(), 'K');
  if (!K.known() && !K.absent()) return;
  const int k = K.known() ? static_cast<int>(K.value) : 0;
  auto it = cx.state.probes.find(k);
  if (it == cx.state.probes.end() || it->second.maybe) return;
  auto same = [&](const tools::NodeCommand& n) {
    auto o = get_int(*n.pf, *n.c, 'K');
    return o.unknown() || (o.known() ? o.value : 0) == k;
  };
  const NodeId loaded = override_file::last_in_run(cx, run, 'G', 31, same);
  if (loaded == kNoNode || !existed_at(it->second.created, loaded) || set_between(cx, run, 'G', 31, same)) return;
  check_device(cx, out, run, loaded, "PXYZ", fmt::format("replaces the trigger height or offsets of probe {}", k),
               "the values M500 saved (M500 P31) are not used; delete this line, or put it before the M501");
}

/// The limits an M208 sets for one axis: `X0:200` both, else `S1` the minimum and otherwise the maximum.
struct Limits {
  bool min = false, max = false, unknown = false;
  double lo = 0, hi = 0;
};

Limits limits(const tools::NodeCommand& k, char letter) {
  Limits l;
  auto v = get_float_list(*k.pf, *k.c, letter);
  if (v.absent()) return l;
  auto S = get_int(*k.pf, *k.c, 'S');
  if (!v.known() || v.value.empty() || S.unknown()) {
    l.unknown = true;
  } else if (v.value.size() >= 2) {
    l = Limits{true, true, false, v.value[0], v.value[1]};
  } else if (S.known() && S.value == 1) {
    l = Limits{true, false, false, v.value[0], 0};
  } else {
    l = Limits{false, true, false, 0, v.value[0]};
  }
  return l;
}

void check_m208(const NodeContext& cx, Sink& out, const Run& run) {
  const tools::NodeCommand self = tools::command_at(cx.machine, cx.graph, cx.id);
  const MachineState& s = cx.state;
  Replaced r;
  for (int i = 0; i < s.visible_axes && i < static_cast<int>(s.axes.size()); ++i) {
    const Axis& axis = s.axes[static_cast<size_t>(i)];
    const Limits mine = limits(self, axis.letter);
    if (mine.unknown) return;
    for (const bool lower : {true, false}) {
      if (lower ? !mine.min : !mine.max) continue;
      auto same = [&](const tools::NodeCommand& k) {
        const Limits o = limits(k, axis.letter);
        return o.unknown || (lower ? o.min : o.max);
      };
      const NodeId loaded = override_file::last_in_run(cx, run, 'M', 208, same);
      if (loaded == kNoNode || !existed_at(axis.created, loaded) || set_between(cx, run, 'M', 208, same)) continue;
      const Limits o = limits(tools::command_at(cx.machine, cx.graph, loaded), axis.letter);
      const double was = lower ? o.lo : o.hi;
      if (o.unknown || std::fabs(was - (lower ? mine.lo : mine.hi)) <= 1e-9) continue;
      r.add(axis.letter,
            fmt::format("{} {} {}", tools::axis_name(axis.letter), lower ? "minimum" : "maximum",
                        override_file::number(was)),
            loaded);
    }
  }
  if (r.letters.empty()) return;
  report(cx, out, run, r, "replaces axis limits", "the limits M500 saved are not used; put this line before the M501");
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is_command() || !cx.certain() || tools::in_tool_macro(cx.graph, cx.id)) return;
  const std::optional<Run> run = override_file::loaded_run(cx);
  if (!run) return;
  if (cx.is('G', 10)) check_g10(cx, out, *run);
  if (cx.is('M', 563)) check_m563(cx, out, *run);
  if (cx.is('M', 307)) check_m307(cx, out, *run);
  if (cx.is('G', 31)) check_g31(cx, out, *run);
  if (cx.is('M', 208)) check_m208(cx, out, *run);
}

}  // namespace

extern const Rule override_after_m501{.meta = kMeta, .check_node = check, .on = "G10 M307 M563 G31 M208"};

}  // namespace rrflint
