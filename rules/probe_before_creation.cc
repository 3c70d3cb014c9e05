// RRF209 probe-before-creation: G31 for a Z probe before the M558 that creates it (RRF rejects it), or an M558 P
// that re-creates a probe after a G31 set it (the G31 values are lost).
#include <fmt/format.h>

#include <optional>

#include "lint/engine/rule.h"
#include "rules/heat_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF209",
    .name = "probe-before-creation",
    .severity = Severity::Error,
    .summary = "G31 sets a Z probe before the M558 that creates it, or an M558 P re-creates a probe after its G31.",
    .docs = R"md(
## What it does
On RRF 3 targets, reports two mistakes of order between `M558` and `G31`:
- **error**: `G31 K<k>` (no `K`: probe 0) where probe k does not exist yet: the `M558 K<k> P…` that creates it
  comes later in the boot sequence, or nowhere. A note points at the later `M558`.
- **warning** (3.2 and later): `M558 K<k> P…` for a probe that exists and that a `G31` has set since it was
  created, and that no later `G31` sets again (a probe-switching macro that re-creates the probe and then runs its
  `G31` is fine). A note points at the `G31`. `M558` without `P` changes the existing probe and is not reported.

It stays silent where probes may exist that the model cannot see (an `M558 K{…}`, a macro whose path is an
expression, a lone macro), when the probe is created inside an `if` branch, on an `M558` that may not run (inside
an `if`), on `G31` without `K` on 3.0 (which addressed the current probe), and inside config-override.g and
resurrect.g.

## Why is this bad?
RRF 3 has no default Z probe (the PCCB aside). `G31` for a probe that does not exist fails with `invalid Z probe
index` (`Invalid Z probe index` before 3.5) and sets nothing: the probe keeps the default trigger height of
0.7 mm and X/Y offsets of 0, so the first `G30` or mesh probes at the wrong height and place.

`M558` with `P` deletes the probe and creates a new one (`EndstopsManager::HandleM558()`), with the defaults:
the trigger height, offsets and temperature coefficients that the earlier `G31` set are gone. `M558` without `P`
(or with `C` alone, which RRF rejects: `Missing Z probe type number`) keeps the probe.

## Example
```gcode
G31 P500 X-30 Y0 Z2.1
M558 P5 C"^io3.in" H5 F120 T6000
```

## Use instead
```gcode
M558 P5 C"^io3.in" H5 F120 T6000
G31 P500 X-30 Y0 Z2.1
M558 H3 F300         ; no P: changes the probe, keeps its G31 values
```

## Fix safety
There is no fix.

## References
- Duet3D G-code dictionary: [M558](https://docs.duet3d.com/User_manual/Reference/Gcodes#m558-set-z-probe-type), [G31](https://docs.duet3d.com/User_manual/Reference/Gcodes#g31-set-or-report-current-probe-status)
- RepRapFirmware 3.5: [EndstopsManager.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Endstops/EndstopsManager.cpp) (`HandleM558()`, `HandleG31()`), [ZProbe.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Endstops/ZProbe.cpp) (`SetDefaults()`)
)md",
};

/// The probe number a G31/M558 names (K; absent: 0). Not known for an expression.
heat::DeviceRef probe_named(const ParsedFile& pf, const Command& c) {
  auto K = get_int(pf, c, 'K');
  if (K.known()) return {static_cast<int>(K.value), K.value >= 0};
  if (K.absent()) return {0, true};
  return {};
}

/// Does this G31 set something (any parameter but K)? Without one it only reports.
bool g31_sets(const ParsedFile& pf, const Command& c) {
  for (const Param& p : pf.params(c))
    if (p.letter != 'K') return true;
  return false;
}

/// The M558s with P (which create a probe) and the G31s that set something, by the probe they name, built once per
/// graph: a config of thousands of G31s asked each later M558 for each.
const tools::DeviceIndex& m558_creating(const NodeContext& cx) {
  return tools::device_index(cx.machine, cx.graph, "probe.m558_p", 'M', 558,
                             [](const ParsedFile& pf, const Command& c) -> std::optional<heat::DeviceRef> {
                               if (!pf.find(c, 'P')) return std::nullopt;
                               return probe_named(pf, c);
                             });
}

/// The G31s that set something, by the probe they name; built once per graph.
const tools::DeviceIndex& g31_setting(const NodeContext& cx) {
  return tools::device_index(
      cx.machine, cx.graph, "probe.g31_sets", 'G', 31, [](const ParsedFile& pf, const Command& c) {
        return g31_sets(pf, c) ? std::optional<heat::DeviceRef>(probe_named(pf, c)) : std::nullopt;
      });
}

/// Is probe k set by a G31 after node `from` in this segment?
bool g31_later(const NodeContext& cx, NodeId from, int k) {
  return g31_setting(cx).first_after(from, cx.segment().end, k) != kNoNode;
}

void check_g31(const NodeContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_1 && !pf.find(c, 'K')) return;  // 3.0: G31 without K addresses the current probe
  const heat::DeviceRef k = probe_named(pf, c);
  if (!k.known || s.probes.count(k.number)) return;
  bool unknown = false;  // the first M558 P that may create it names an expression
  const NodeId create = !cx.in_boot() ? kNoNode : m558_creating(cx).first_later(cx, k.number, &unknown);
  if (unknown || (create != kNoNode && heat::runs_again(cx, create))) return;  // set once the probe exists
  const std::string where = create == kNoNode ? fmt::format("no 'M558 K{} P…' creates it anywhere", k.number)
                                              : "the M558 that creates it comes only later";
  const bool later = create != kNoNode && g31_later(cx, create, k.number);
  Report rep = out.report(
      kMeta, cx.at(c.span),
      fmt::format("{} names Z probe {}, which does not exist yet ({}): RRF answers '{} Z probe index' and sets "
                  "nothing{}",
                  tools::quote(pf, c), k.number, where, s.firmware >= kRrf3_5 ? "invalid" : "Invalid",
                  later ? " (a later G31 sets the probe)"
                        : ", so the probe keeps the default trigger height (0.7 mm) and offsets (0)"));
  if (create != kNoNode) rep.note(cx.where(create), fmt::format("Z probe {} is created here", k.number));
}

void check_m558(const NodeContext& cx, Sink& out) {
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_2 || !cx.certain() || !pf.find(c, 'P')) return;
  const heat::DeviceRef k = probe_named(pf, c);
  if (!k.known) return;
  auto it = s.probes.find(k.number);
  if (it == s.probes.end() || it->second.maybe || it->second.created == kNoNode) return;
  NodeId g31 = kNoNode;  // the last G31 that set the probe since its creation
  for (const auto& [b, e] : heat::since(cx, it->second.created))
    if (const NodeId last = g31_setting(cx).last_in(b, e, k.number); last != kNoNode) g31 = last;
  if (g31 == kNoNode || g31_later(cx, cx.id, k.number)) return;  // set again after
  Report rep = out.report(kMeta, Severity::Warning, cx.at(c.span),
                          fmt::format("{} re-creates Z probe {} (P deletes it and makes a new one with the defaults), "
                                      "so the trigger height and offsets the earlier G31 set are lost: put the G31 "
                                      "after this line, or drop P to change the probe in place",
                                      tools::quote(pf, c), k.number));
  rep.note(cx.where(g31), fmt::format("Z probe {} gets its trigger height and offsets here", k.number));
}

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('G', 31) && !cx.is('M', 558)) return;
  const MachineState& s = cx.state;
  if (s.firmware < kRrf3_0 || !s.probes_known || s.unknown_baseline || heat::judged_elsewhere(cx)) return;
  if (cx.is('G', 31)) check_g31(cx, out);
  else check_m558(cx, out);
}

}  // namespace

extern const Rule probe_before_creation{.meta = kMeta, .check_node = check, .on = "G31 M558"};

}  // namespace rrflint
