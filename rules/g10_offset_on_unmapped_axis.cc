// RRF304 g10-offset-on-unmapped-axis: an X/Y/Z tool offset on an axis the tool's M563 map leaves out.
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF304",
    .name = "g10-offset-on-unmapped-axis",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary = "A G10 sets the X, Y or Z offset of a tool whose M563 maps that letter to other axes only.",
    .docs = R"md(
## What it does
Reports a tool-offset G10 that sets `X` (or `Y`, or `Z` from RRF 3.5) for a tool whose M563 map for that letter
does not include the physical axis of the same name, e.g. `M563 P1 … X3` (X moves drive U only) followed by
`G10 P1 X-0.4`. A note points at the M563 map.

- `warning` for a non-zero value: the offset the user measured is never applied.
- `info` for an explicit zero when the line does not also set the mapped axis: harmless today, but that is
  where a calibrated value will later be typed, and then it does nothing.
- Silent for a zero when the same line also sets the mapped axis (`G10 P1 X0 Y0 U0`), as generated configs do,
  and for values written as expressions, tools created inside an `if` or with an unknown map.
- With X and Y swapped (`M563 P1 … X1 Y0`) the tool drives neither physical X nor physical Y (each is driven only
  by a tool whose own map for that letter includes it), so both offsets are reported and the message says that
  an offset on the other letter would not be applied either.

## Why is this bad?
RRF applies offsets per *physical* axis: for each axis driven by the tool it subtracts the tool's offset for
that axis (GCodes.cpp `ToolOffsetTransform()`). With X mapped to U, physical X is not driven by the tool and
its X offset is never read; the U offset is what moves the nozzle. The Duet docs say: "if you map X to U …
you should specify a U offset not an X offset".

## Example
```gcode
M584 X0 Y1 Z2 U3 E4:5
M563 P1 D1 H2 X3
G10 P1 X-0.4 Y0.1 Z0
```

## Use instead
```gcode
M584 X0 Y1 Z2 U3 E4:5
M563 P1 D1 H2 X3
G10 P1 U-0.4 Y0.1 Z0
```

## Fix safety
When the map has exactly one axis, the tool drives that axis and the line has no offset for it yet, the fix
renames the letter (`X-0.4` → `U-0.4`). It is unsafe: the offset then takes effect and moves the nozzle. With X
and Y swapped there is no fix: renaming X to Y would put the offset on an axis the tool does not drive either.

## References
- rrflint: [Tool offsets and axis mapping](../firmware-behaviour.md#tool-offsets-and-axis-mapping)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset) (offsets apply after axis mapping), [M563: define or remove a tool](https://docs.duet3d.com/User_manual/Reference/Gcodes#m563-define-or-remove-a-tool)
- Duet3D [IDEX configuration](https://docs.duet3d.com/User_manual/Machine_configuration/Configuration_IDEX)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`ToolOffsetTransform()`)
)md",
};

/// Does the tool move physical axis `axis`? X, Y and Z (Z from 3.5; before, Z has no map) only when the tool's own
/// map for that letter includes them (GCodes.cpp ToolOffsetTransform()); any other axis always, from the letter
/// that maps to it. An unknown map answers `unknown`.
bool drives_axis(const MachineState& s, const Tool& t, int axis, bool unknown) {
  const std::pair<char, const AxisMap*> own[] = {{'X', &t.xmap}, {'Y', &t.ymap}, {'Z', &t.zmap}};
  for (auto [L, map] : own)
    if (s.axis_index(L) == axis) return map->known ? (map->bits & (1u << axis)) != 0 : unknown;
  return true;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('G', 10)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (cx.g10_form() != G10Form::Tool) return;
  const ToolRef ref = addressed_tool(pf, c, s);
  if (!ref.known) return;
  const Tool* t = s.tool(ref.number);
  if (!t || t->maybe) return;

  const std::pair<char, const AxisMap*> maps[] = {{'X', &t->xmap}, {'Y', &t->ymap}, {'Z', &t->zmap}};
  for (auto [L, map] : maps) {
    const int own = s.axis_index(L);
    if (own < 0 || !s.axis_visible(own)) continue;
    if (!map->known || map->origin == kNoNode || map->bits == 0 || (map->bits & (1u << own))) continue;
    auto v = get_float(pf, c, L);
    if (!v.known()) continue;
    const std::string mapped = s.axis_letters(map->bits);
    bool sets_mapped = false, any_driven = false;
    int single = -1, count = 0;
    for (int i = 0; i < static_cast<int>(s.axes.size()) && i < 32; ++i) {
      if (!(map->bits & (1u << i))) continue;
      ++count;
      single = i;
      if (pf.find(c, s.axes[static_cast<size_t>(i)].letter)) sets_mapped = true;
      if (drives_axis(s, *t, i, true)) any_driven = true;
    }
    const bool zero = v.value == 0;
    if (zero && sets_mapped) continue;
    // X and Y swapped (`M563 … X1 Y0`): the tool drives neither physical axis, so no offset of either is applied.
    const std::string neither =
        fmt::format("{} on {}, which the tool does not drive either (its own {} map leaves it out)",
                    zero ? "nor would one be" : "nor an offset", mapped, mapped);
    std::string msg =
        zero ? fmt::format("{} sets the {} offset of tool {}, whose {} is mapped to {}: the offset is never used; {}",
                           tools::quote(pf, c), L, ref.number, L, mapped,
                           any_driven ? fmt::format("a calibrated value belongs on {}", mapped) : neither)
             : fmt::format("{} sets the {} offset of tool {}, whose {} is mapped to {}: RRF never applies it, {}",
                           tools::quote(pf, c), L, ref.number, L, mapped,
                           any_driven ? fmt::format("it applies the {} offset instead", mapped) : neither);
    Report r = out.report(kMeta, zero ? Severity::Info : kMeta.severity, cx.at(v.param->span), std::move(msg));
    r.note(cx.where(map->origin), fmt::format("{} of tool {} is mapped to {} here", L, ref.number, mapped));
    if (count == 1 && !sets_mapped && single < static_cast<int>(s.axes.size()) && drives_axis(s, *t, single, false)) {
      const char to = s.axes[static_cast<size_t>(single)].letter;
      r.fix(
          Fix::unsafe(fmt::format("use {} instead of {}", tools::axis_name(to), L),
                      Edit::replace(cx.at(Span{v.param->span.begin, v.param->span.begin + 1}), tools::axis_name(to))));
    }
  }
}

}  // namespace

extern const Rule g10_offset_on_unmapped_axis{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
