// RRF306 g10-missing-z: a tool-offset G10 without Z where the tool's Z offset may be non-zero.
#include "rules/append_fix.h"
#include "rules/missing_z.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF306",
    .name = "g10-missing-z",
    .severity = Severity::Warning,
    .fix = FixAvailability::Sometimes,
    .summary = "A tool-offset G10 leaves Z out where the tool's Z offset may be non-zero, so Z keeps that value.",
    .docs = R"md(
## What it does
Reports a tool-offset G10 that sets X/Y (or other axes) but not Z, where the machine model says the tool's Z
offset may be non-zero at that point:
- an earlier G10 gave it a non-zero Z, or a Z written as an expression;
- config-override.g, loaded by an earlier M501, set a Z for that tool (a value M500 saved);
- an M585 measured it.

It stays silent:
- where Z is provably 0: right after the tool's M563 (a fresh tool has every offset at 0), including the IDEX
  copy and mirror tools of the Duet docs (`G10 P2 X90 Y0 U-90 S0 R0`); `g10-implicit-z` covers those, opt-in;
- when a later G10 in the same boot sequence sets that tool's Z before a `T` selects it (configs that split
  X/Y and Z offsets into two files);
- when the Z came from a G10 that set Z and no other axis (`G10 P0 Z-1.2`, then `G10 P0 X21.5 Y-0.3`): the
  config keeps Z apart from X/Y on purpose;
- in macros that run outside the boot sequence, unless the Z became non-zero in that same macro: a
  calibration macro that sets X/Y deliberately keeps the Z that config.g set;
- for a G10 inside an `if`/`while`, for tools created with an unknown number or inside an `if`, and inside
  config-override.g, where M500 writes only the axes that were probed.

## Why is this bad?
G10 changes only the axes it names; every other offset keeps its value (GCodes.cpp `SetOrReportOffsets()`).
A line that looks like the tool's complete offset definition then silently keeps an old Z. The Duet docs
advise: "you want explicitly to set Z0.0".

## Example
```gcode
M584 X0 Y1 Z2 E3
M563 P0 S"Left" D0 H1
G10 P0 X0 Y0 Z-1.2
; offsets re-measured later
G10 P0 X21.5 Y-0.3      ; Z stays -1.2
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M563 P0 S"Left" D0 H1
G10 P0 X0 Y0 Z-1.2
; offsets re-measured later
G10 P0 X21.5 Y-0.3 Z-1.2
```

## Fix safety
When the model knows the Z value from a literal G10 earlier in the boot sequence, the fix appends it
(` Z-1.2`) right after the last parameter, before any comment. That keeps what the line does and makes it
visible, so it is safe. There is no fix for a Z loaded from config-override.g or measured by M585: writing
that value into config.g would freeze it, nor where the appended text would not be read as a parameter (after an
unterminated string or `{`, a ';' that cuts an expression open, or a CNC-mode `(` comment that no `)` closes).

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms), [Saved settings: M500, M501, M502](../firmware-behaviour.md#saved-settings-m500-m501-m502)
- Duet3D G-code dictionary: [G10: set workplace coordinate offset or tool offset](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-set-workplace-coordinate-offset-or-tool-offset)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`SetOrReportOffsets()`: axes not named keep their offsets)
)md",
};

/// Is node `id` a G10 that sets Z and no other axis? Configs that keep Z apart from X/Y do it on purpose.
bool z_only_g10(const NodeContext& cx, NodeId id) {
  if (id == kNoNode) return false;
  tools::NodeCommand nc = tools::command_at(cx.machine, cx.graph, id);
  if (!nc.is('G', 10) || !nc.pf->find(*nc.c, 'Z')) return false;
  for (const Param& p : nc.pf->params(*nc.c))
    if (p.letter != 'Z' && tools::is_axis_letter(p.letter, cx.state)) return false;
  return true;
}

void check(const NodeContext& cx, Sink& out) {
  auto m = tools::missing_z(cx);
  if (!m) return;
  const bool maybe_nonzero = !m->z.known || m->z.value != 0 || m->probed;
  if (!maybe_nonzero) return;
  if (!cx.in_boot() && (m->z.origin == kNoNode || m->z.origin < cx.segment().begin)) return;
  if (!m->probed && z_only_g10(cx, m->z.origin)) return;  // Z kept apart on purpose: `G10 P0 Z-1.2`, then X/Y

  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  std::string why, value;
  if (m->probed) {
    const tools::NodeCommand origin =
        m->z.origin != kNoNode ? tools::command_at(cx.machine, cx.graph, m->z.origin) : tools::NodeCommand{};
    why = origin.is('M', 585) ? "the value M585 measured" : "a value loaded from config-override.g";
  } else if (!m->z.known) {
    why = "a value rrflint cannot know";
  } else {
    tools::NodeCommand origin =
        m->z.origin != kNoNode ? tools::command_at(cx.machine, cx.graph, m->z.origin) : tools::NodeCommand{};
    if (origin.is('G', 10))
      if (ParamRef p = origin.pf->find(*origin.c, 'Z'); p && !is_unknown_value(*p) && p->kind == ValueKind::Number)
        value = clip(origin.pf->text(p->value));
    why = fmt::format("{}", value.empty() ? fmt::format("{:g}", m->z.value) : value);
  }
  Report r = out.report(kMeta, cx.at(c.span),
                        fmt::format("{} sets offsets of tool {} but not Z, so Z keeps its earlier value ({}): "
                                    "set Z on this line too",
                                    tools::quote(pf, c), m->tool, why));
  if (m->z.origin != kNoNode) r.note(cx.where(m->z.origin), fmt::format("tool {} gets its Z offset here", m->tool));
  if (!value.empty() && !m->probed && tools::appendable_z(cx, value)) r.fix(tools::append_z(cx, value));
}

}  // namespace

extern const Rule g10_missing_z{.meta = kMeta, .check_node = check, .on = "G10"};

}  // namespace rrflint
