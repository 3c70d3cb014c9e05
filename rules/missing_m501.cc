// RRF404 missing-m501: a config-override.g beside config.g that no M501 (or M98) loads.
#include <fmt/format.h>

#include "lint/boot/commands.h"
#include "lint/engine/rule.h"
#include "lint/syntax/values.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF404",
    .name = "missing-m501",
    .severity = Severity::Info,
    .summary = "A config-override.g beside config.g that nothing loads: the values M500 saved in it are never used.",
    .docs = R"md(
## What it does
Reports `sys/config-override.g` when the card has a `sys/config.g` and no file on the card runs `M501` or
`M98 P"config-override.g"`. The finding sits on the override's first line and names what the file holds that is
then lost: heater models (`M307`), delta calibration (`M665`/`M666`), tool offsets (`G10`), probe offsets (`G31`),
workplace origins (`G10 L2`).

It stays silent when any file runs `M501` (even a macro run by hand, or inside an `if`), when an `M98` names its
file with an expression (it may be the override), and for a lone macro or a folder with no config.g.

## Why is this bad?
`M500` writes the values tuned on the machine (heater tuning with `M303`, delta auto-calibration with `G32`, probed
tool offsets) into config-override.g, and only `M501` reads them back, normally as the last line of config.g. With
no `M501` the machine boots with config.g's untuned values every time, and nothing says so.

## Example
```gcode
M584 X0 Y1 Z2 E3
M950 H1 C"out1" T1
M563 P0 D0 H1
; file: sys/config-override.g
M307 H1 R2.43 K0.56:0.00 D5.50 E1.35 S1.00 B0 V24.0
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M950 H1 C"out1" T1
M563 P0 D0 H1
M501
; file: sys/config-override.g
M307 H1 R2.43 K0.56:0.00 D5.50 E1.35 S1.00 B0 V24.0
```

## Fix safety
There is no fix: where M501 belongs (after the commands the override depends on) is the user's choice; see
[m501-too-early](m501-too-early.md).

## References
- rrflint: [Saved settings: M500, M501, M502](../firmware-behaviour.md#saved-settings-m500-m501-m502)
- Duet3D G-code dictionary: [M501](https://docs.duet3d.com/User_manual/Reference/Gcodes#m501-read-stored-parameters)
)md",
};

// The kinds of tuned values config-override.g holds, for the message ("heater models (M307), tool offsets (G10)").
std::string held_values(const ParsedFile& pf) {
  std::string out;
  auto add = [&](bool any, std::string_view what) {
    if (any) out += (out.empty() ? "" : ", ") + std::string(what);
  };
  add(!pf.with_code('M', 307).empty(), "heater models (M307)");
  add(!pf.with_code('M', 665).empty() || !pf.with_code('M', 666).empty(), "delta calibration (M665/M666)");
  add(!pf.with_code('G', 10).empty(), "tool offsets or workplace origins (G10)");
  add(!pf.with_code('G', 31).empty(), "probe offsets (G31)");
  return out;
}

// Does any file run M501, or an M98 that may name config-override.g?
bool maybe_loaded(const Machine& m) {
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const ParsedFile& pf = m.unit(i).parsed;
    if (!pf.with_code('M', 501).empty()) return true;
    for (const uint32_t ci : pf.with_code('M', 98)) {
      const Command& c = pf.commands[ci];
      if (!c.is('M', 98)) continue;
      const auto path = get_string(pf, c, 'P');
      if (!path.known() || file_role(path.value) == FileRole::ConfigOverride) return true;
    }
  }
  return false;
}

void check(const EndContext& cx, Sink& out) {
  const Machine& m = cx.machine;
  const FileUnit *config = nullptr, *override_file = nullptr;
  for (uint32_t i = 0; i < m.unit_count(); ++i) {
    const FileUnit& u = m.unit(i);
    const std::string path = to_lower(u.sd_path);
    if (path == "/sys/config.g") config = &u;
    if (path == "/sys/config-override.g") override_file = &u;
  }
  if (!config || !override_file || maybe_loaded(m)) return;
  const ParsedFile& pf = override_file->parsed;
  if (pf.commands.size() == 0) return;  // an empty or comment-only file holds nothing to lose
  const std::string held = held_values(pf);
  const SourceFile& src = *override_file->source;
  out.report(kMeta, Location{src.id(), src.line_span(0)},
             fmt::format("config-override.g is never loaded: no file runs M501, so the {} saved here by M500 are "
                         "never used",
                         held.empty() ? "values" : held));
}

}  // namespace

extern const Rule missing_m501{.meta = kMeta, .check_end = check};

}  // namespace rrflint
