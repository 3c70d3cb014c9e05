// RRF213 m584-after-dependents: an M584 that two or more earlier commands depend on, as one finding with notes.
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/motion_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF213",
    .name = "m584-after-dependents",
    .severity = Severity::Warning,
    .summary = "An M584 comes after two or more commands that lose their effect because of it.",
    .docs = R"md(
## What it does
Reports an `M584` once, with a note per earlier command that loses its effect because of it, when there are
two or more such commands:
- an axis letter of an axis this `M584` creates, in `M92`, `M201`, `M203`, `M350`, `M566`, `M906`, `M208`, `G31`
  and the other commands of [axis-before-creation](axis-before-creation.md): RRF ignores it;
- an `M350` (not x16 with interpolation) or `M906`/`M913`/`M917` for an axis or extruder to which this `M584`
  adds drivers that miss the setting, as [drive-settings-before-mapping](drive-settings-before-mapping.md)
  describes.

Those two rules leave the commands that this finding lists to it, so one mistake is reported once; with a single
such command they report it themselves. Not counted, because nothing is lost: `M92`, `M566`, `M203`, `M201` for
axes that exist already (RRF stores them per axis, and they survive a remap), current on local drivers, and
`M906 I…` (no axis). E values before the first `M584 E` on RRF 3.3 and later are not counted either: RRF rejects
them with an error message, and they stay [extruder-before-creation](extruder-before-creation.md)'s errors.
Silent for an `M584` inside `if`/`while` and where the axes are unknown. A line that runs again after this
`M584` (a macro called before and after it) is not counted, and a line run twice before it (a macro called twice)
counts once.

## Why is this bad?
RRF applies most axis settings to the axes and drivers that exist when the command runs. An `M584` placed after
them creates axes that then have none of their settings, or adds drivers that never get the microstepping or the
current, all without a message. The fix is one move: put the `M584` before the commands that configure its axes.

## Example
```gcode
M350 X16 Y16 Z32 I1
M92 X80 Y80 Z400 U80
M906 X800 Y800 Z800 U800
M584 X0 Y1 Z2:3 U4
```

## Use instead
```gcode
M584 X0 Y1 Z2:3 U4
M350 X16 Y16 Z32 I1
M92 X80 Y80 Z400 U80
M906 X800 Y800 Z800 U800
```

## References
- rrflint: [Axes and M584](../firmware-behaviour.md#axes-and-m584)
- Duet3D G-code dictionary: [M584: set drive mapping](https://docs.duet3d.com/User_manual/Reference/Gcodes#m584-set-drive-mapping) (order dependency), [Command Order](https://docs.duet3d.com/User_manual/Reference/Gcodes#command-order)
- RepRapFirmware 3.5: [GCodes3.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes3.cpp) (`DoDriveMapping()`), [Move.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/Move.cpp) (`SetMicrostepping()`, `EnableDrivers()`)
)md",
};

std::string drivers_text(const std::vector<DriverId>& ds) {
  std::string out;
  for (DriverId d : ds) out += (out.empty() ? "" : ", ") + d.str();
  return fmt::format("{} {}", ds.size() == 1 ? "driver" : "drivers", out);
}

std::string note_text(const NodeContext& cx, const motion::Dependent& d) {
  const tools::NodeCommand k = tools::command_at(cx.machine, cx.graph, d.node);
  const std::string code(k.pf->text(k.c->word));
  const std::string who = d.letter == 'E' ? std::string("the extruders") : "axis " + tools::axis_name(d.letter);
  switch (d.why) {
    case motion::Loss::Created: return fmt::format("'{}' sets {} before it exists: ignored", code, who);
    case motion::Loss::Microstepping:
      return fmt::format("'{}' sets the microstepping of {}: {} stay{} at x16", code, who, drivers_text(d.added),
                         d.added.size() == 1 ? "s" : "");
    case motion::Loss::Current:
      return fmt::format("'{}' sets the current of {}: CAN-connected {} never receive{} it", code, who,
                         drivers_text(d.added), d.added.size() == 1 ? "s" : "");
  }
  return {};
}

/// The dependent's parameter (`U80`, `E800`), or its command.
Location where(const NodeContext& cx, const motion::Dependent& d) {
  const Node n = cx.graph.nodes[d.node];
  const tools::NodeCommand k = tools::command_at(cx.machine, n);
  if (ParamRef p = k.pf->find(*k.c, d.letter)) return Location{cx.machine.unit(n.unit).source->id(), p->span};
  return cx.where(d.node);
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 584) || !cx.certain()) return;
  const std::vector<motion::Dependent> deps = motion::dependents(cx, cx.id, motion::drive_map(cx.state));
  if (!motion::summary_fires(cx.graph, deps)) return;
  const Command c = cx.command();
  Report r = out.report(kMeta, cx.at(c.span),
                        fmt::format("{} comes after {} commands that configure the axes or drivers it maps, and they "
                                    "lose their effect: move this M584 before them",
                                    tools::quote(cx.parsed(), c), motion::command_count(cx.graph, deps)));
  for (size_t i = 0; i < deps.size(); ++i)
    if (!motion::repeated_run(cx.graph, deps, i)) r.note(where(cx, deps[i]), note_text(cx, deps[i]));
}

}  // namespace

extern const Rule m584_after_dependents{.meta = kMeta, .check_node = check, .on = "M584"};

}  // namespace rrflint
