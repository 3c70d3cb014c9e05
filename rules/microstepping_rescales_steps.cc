// RRF204 microstepping-rescales-steps: an M92 rescaled by a later M350 and then replaced by another M92.
#include <fmt/format.h>

#include <algorithm>

#include "lint/engine/rule.h"
#include "rules/lex_common.h"
#include "rules/motion_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF204",
    .name = "microstepping-rescales-steps",
    .severity = Severity::Info,
    .default_enabled = false,
    .tag = RuleTag::Unnecessary,
    .summary = "An M92 is rescaled by a later M350 and then replaced by another M92, so it has no effect.",
    .docs = R"md(
## What it does
Reports an `M92` value without `S` for an axis or the extruders when a later `M350` changes that axis's
microstepping (RRF then rescales the steps/mm) and a later `M92` for the same axis follows the `M350`: the first
value, rescaled or not, is replaced and has no effect. Notes point at the `M350` and at the later `M92`. Off by
default (`--extend-select RRF204`): the config works, it only does the work twice, and the order of the lines
suggests the author expected the `M350` to matter.

It stays silent for the documented order `M92 X80` then `M350 X128` with no later `M92` (RRF rescales 80 to
640 steps/mm, as intended), for `M92 … S<n>` (the value is stated for microstepping n, whatever the order), for
an `M350` that keeps the microstepping, for expressions and commands inside `if`/`while`, and where the earlier
microstepping is unknown (a standalone macro, a conditional `M350`).

## Why is this bad?
`M350` keeps the distance per step by multiplying the steps/mm by new/old microstepping, and a later `M92`
simply sets the value again. The first `M92` is dead: whoever edits it later changes nothing, and a reader may take
the rescaled value for the one in use. Keep one `M92` per axis, after the `M350`, or give it `S` (`M92 X80 S16`).

## Example
```gcode
M92 X80 Y80 Z400
M350 X16 Y16 Z16 E16 I1
M350 X128 Y128 I0
M92 X640 Y640
```

## Use instead
```gcode
M350 X128 Y128 Z16 I0
M92 X640 Y640 Z400
```

```gcode
M92 X80 Y80 Z400
M350 X128 Y128 I0
```

## References
- rrflint: [Axes and M584](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M92](https://docs.duet3d.com/User_manual/Reference/Gcodes#m92-set-axis-steps-per-unit) (`S`), [M350](https://docs.duet3d.com/User_manual/Reference/Gcodes#m350-set-microstepping-mode) (steps/mm are adjusted)
- RepRapFirmware 3.5: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes.cpp) (`ChangeMicrostepping()`), [Platform.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Platform/Platform.cpp) (`SetDriveStepsPerUnit()`: value × current / requested microstepping)
)md",
};

/// The microstepping an M350 sets for `letter` (the first value for E), or -1 when unknown or none.
int64_t microstepping(const tools::NodeCommand& k, char letter) {
  if (k.node.maybe) return -1;
  auto v = get_int_list(*k.pf, *k.c, letter);
  return v.known() && !v.value.empty() && v.value[0] >= 0 ? v.value[0] : -1;
}

/// The microstepping of `letter` before node `id`: the last M350 that names it in this boot segment, else RRF's
/// x16; -1 when it is unknown (a conditional M350, an expression, a segment that does not start at power-up).
int64_t microstepping_before(const NodeContext& cx, NodeId id, char letter) {
  const Segment& seg = cx.segment();
  const NodeId last = tools::last_before(tools::code_index(cx.machine, cx.graph, 'M', 350)[letter], seg.begin, id);
  if (last != kNoNode) return microstepping(tools::command_at(cx.machine, cx.graph, last), letter);
  return seg.boot && !cx.state.unknown_baseline ? 16 : -1;
}

/// The next command after `from` that is an M92 or M350 naming `letter` (from the indexes of both by letter: each
/// M92 used to walk the nodes before and after it).
NodeId next_for(const NodeContext& cx, NodeId from, char letter) {
  const NodeId end = cx.segment().end;
  return std::min(tools::first_after(tools::code_index(cx.machine, cx.graph, 'M', 92)[letter], from, end),
                  tools::first_after(tools::code_index(cx.machine, cx.graph, 'M', 350)[letter], from, end));
}

/// The first M350 after this M92 that changes the microstepping of `letter`, and the M92 that then replaces the
/// value; kNoNode when the value survives or anything on the way is unknown.
struct Rescale {
  NodeId m350 = kNoNode, again = kNoNode;
  int64_t before = 0, after = 0;
};

Rescale find_rescale(const NodeContext& cx, char L) {
  Rescale r;
  int64_t current = microstepping_before(cx, cx.id, L);
  if (current <= 0) return {};
  for (NodeId at = next_for(cx, cx.id, L); at != kNoNode; at = next_for(cx, at, L)) {
    const tools::NodeCommand k = tools::command_at(cx.machine, cx.graph, at);
    if (k.is('M', 92)) {
      if (r.m350 == kNoNode || k.node.maybe) return {};
      r.again = at;
      return r;
    }
    const int64_t now = microstepping(k, L);
    if (now <= 0) return {};
    if (now != current && r.m350 == kNoNode) r = {at, kNoNode, current, now};
    current = now;
  }
  return {};
}

void check_letter(const NodeContext& cx, Sink& out, const Param& p) {
  const char L = p.letter;
  const Rescale r = find_rescale(cx, L);
  if (r.again == kNoNode) return;
  const std::string who = L == 'E' ? std::string("the extruders") : "axis " + tools::axis_name(L);
  auto v = get_float(cx.parsed(), cx.command(), L);
  const std::string rescaled =
      v.known() && L != 'E' ? fmt::format(" ({} steps/mm)", v.value * static_cast<double>(r.after) / r.before) : "";
  out.report(kMeta, cx.at(p.span),
             fmt::format("'{}' for {} has no effect: the later 'M350' changes its microstepping from x{} to x{}, "
                         "which rescales it{}, and a later 'M92' then replaces it",
                         clip(cx.parsed().text(p.span)), who, r.before, r.after, rescaled))
      .note(cx.where(r.m350), fmt::format("the microstepping of {} changes here", who))
      .note(cx.where(r.again), fmt::format("{} {} steps/mm again here", who, L == 'E' ? "get their" : "gets its"));
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 92) || !cx.certain() || cx.state.unknown_baseline) return;
  const ParsedFile& pf = cx.parsed();
  const Command c = cx.command();
  if (pf.find(c, 'S')) return;  // the value is stated for microstepping S: the order does not matter
  for (const Param& p : pf.params(c)) {
    const char L = p.letter;
    if (L == 0 || !pf.find(c, L).is(p) || is_unknown_value(p)) continue;
    if (L != 'E' && cx.state.axis_index(L) < 0) continue;  // not an axis (yet): axis-before-creation
    if (L == 'E' && cx.state.extruders_known && cx.state.extruders == 0) continue;  // rejected: RRF202's
    check_letter(cx, out, p);
  }
}

}  // namespace

extern const Rule microstepping_rescales_steps{.meta = kMeta, .check_node = check, .on = "M92"};

}  // namespace rrflint
