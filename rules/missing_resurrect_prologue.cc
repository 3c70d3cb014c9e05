// RRF507 missing-resurrect-prologue: M911 sets up resume after power failure, resurrect.g is on the card, and the
// resurrect-prologue.g that M916 requires is not.
#include <fmt/format.h>

#include "lint/engine/linter.h"
#include "lint/engine/rule.h"
#include "lint/syntax/values.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF507",
    .name = "missing-resurrect-prologue",
    .severity = Severity::Warning,
    .summary = "M911 sets up resume after power failure, but the resurrect-prologue.g that M916 needs is missing.",
    .docs = R"md(
## What it does
Reports an `M911 S…` (power-fail auto-save, with a save voltage of 10 V or more) that certainly runs at boot when
the system folder holds `resurrect.g` but no `resurrect-prologue.g`. A note points at the line of resurrect.g that
calls the prologue (RRF writes `M98 P"resurrect-prologue.g"` with the machine position into every resurrect.g).

It stays silent without an `M911 S…` on the boot path (or with one inside an `if`, or with an expression or
`S` below 10, which disables auto-save): resume after power failure is not set up, and resurrect.g is just the
snapshot of a pause. It stays silent, too, when the card has no resurrect.g at all: `M916` then answers
`No resume file found` before it looks for the prologue, and a repository's copy of the card shows no resume to
judge. The `M98` inside resurrect.g is not reported by `missing-macro` (RRF501) either: no rule reports a line of
that firmware-written file.

## Why is this bad?
`M916` (resume after power failure) first checks for `/sys/resurrect.g` and then for `/sys/resurrect-prologue.g`;
without the prologue it refuses with `Resume prologue file 'resurrect-prologue.g' not found` and runs nothing.
The prologue is the user's file (it homes the machine before resurrect.g moves back to the print), so the print
that M911 was set up to save cannot be resumed.

## Example
```gcode
M911 S10 R11 P"M913 X0 Y0 G91 M83 G1 Z3 E-5 F1000"
; file: sys/resurrect.g
; Resume printing file "part.gcode" after power failure
G21
M98 P"resurrect-prologue.g" X10.000 Y20.000 Z0.300
```

## Use instead
```gcode
M911 S10 R11 P"M913 X0 Y0 G91 M83 G1 Z3 E-5 F1000"
; file: sys/resurrect.g
; Resume printing file "part.gcode" after power failure
G21
M98 P"resurrect-prologue.g" X10.000 Y20.000 Z0.300
; file: sys/resurrect-prologue.g
G28 X Y
```

## Fix safety
There is no fix: the prologue depends on the machine (how it can home without crashing into the print).

## References
- rrflint: [System files](../firmware-behaviour.md#system-files)
- Duet3D: [Setting up to resume a print after a power failure](https://docs.duet3d.com/User_manual/Tuning/Power_failure), [M911](https://docs.duet3d.com/User_manual/Reference/Gcodes#m911-configure-auto-save-on-loss-of-power), [M916](https://docs.duet3d.com/User_manual/Reference/Gcodes#m916-resume-print-after-power-failure)
- RepRapFirmware 3.5: [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes2.cpp) (cases 911 and 916), [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodes.cpp) (`SaveResumeInfo()`)
)md",
};

/// The loaded unit at this SD path (case-insensitive), or null.
const FileUnit* unit_at(const Machine& m, const std::string& sd_path) {
  for (uint32_t i = 0; i < m.unit_count(); ++i)
    if (to_lower(m.unit(i).sd_path) == sd_path) return &m.unit(i);
  return nullptr;
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 911) || !cx.certain() || !cx.in_boot()) return;
  const Command c = cx.command();
  const auto S = get_float(cx.parsed(), c, 'S');
  if (!S.known() || S.value < 10.0) return;  // no S reports the settings; below 10 V disables auto-save
  const std::string sys = to_lower(cx.options.sys_dir);
  const std::string resurrect = sys + "/resurrect.g", prologue = sys + "/resurrect-prologue.g";
  if (!cx.machine.has_file(resurrect) || cx.machine.has_file(prologue)) return;
  Report r = out.report(kMeta, cx.at(c.span),
                        fmt::format("'{}' sets up resume after power failure, but {} does not exist: M916 refuses "
                                    "with 'Resume prologue file 'resurrect-prologue.g' not found' and resumes nothing",
                                    cx.parsed().text(c.span), prologue));
  const FileUnit* u = unit_at(cx.machine, resurrect);
  if (!u) return;
  for (const uint32_t i : u->parsed.with_code('M', 98)) {
    const Command call = u->parsed.commands[i];
    const auto P = get_string(u->parsed, call, 'P');
    if (!P.known() || !to_lower(P.value).ends_with("resurrect-prologue.g")) continue;
    r.note(Location{u->source->id(), call.span}, "resurrect.g, written by the firmware, calls the prologue here");
    return;
  }
}

}  // namespace

extern const Rule missing_resurrect_prologue{.meta = kMeta, .check_node = check, .on = "M911"};

}  // namespace rrflint
