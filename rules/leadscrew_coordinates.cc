// RRF217 leadscrew-coordinates: an M671 that RRF refuses, its X and Y lists of different lengths or too long.
#include <fmt/format.h>

#include "lint/boot/commands.h"
#include "lint/engine/rule.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF217",
    .name = "leadscrew-coordinates",
    .severity = Severity::Error,
    .summary = "M671 gives its X and Y coordinates in lists of different lengths, or more than 4: RRF refuses it.",
    .docs = R"md(
## What it does
Reports an `M671` whose leadscrew (or bed levelling screw) positions RRF refuses: an `X` list without a `Y` list
or the other way round, `X` and `Y` lists of different lengths, or a list of more than 4 positions. It reads the
lists as RRF does (a blank before `:` ends a list). It stays silent when a list is an expression (`X{…}`), for an
`M671` with only `S`, `P` or `F` (those change the settings and keep the positions), and when the kinematics does
not read M671 at all (CoreXZ, deltas: another answer, not this one) or is unknown.

## Why is this bad?
`ZLeadscrewKinematics::Configure()` sets the leadscrews only when it has seen both lists with the same number of
values; otherwise it answers `Specify 1, 2, 3 or 4 X and Y coordinates in M671`, and a fifth value stops the
command with `array too long, max length = 4`. Either way the leadscrew positions stay what they were (at boot:
none), so `G32` cannot level the gantry or bed with the Z motors, and bed.g's probing ends in an error or in a plain
tilt compensation. The error shows once on the console at boot, among the others.

## Example
```gcode
M584 X0 Y1 Z2:3:4 E5
M671 X-10:150:310 Y300:-10 S5
```

## Use instead
```gcode
M584 X0 Y1 Z2:3:4 E5
M671 X-10:150:310 Y300:-10:300 S5
```

## Fix safety
There is no fix: which position is missing, or which is one too many, only the machine knows.

## References
- rrflint: [The rest of the machine](../firmware-behaviour.md#the-rest-of-the-machine)
- Duet3D G-code dictionary: [M671](https://docs.duet3d.com/User_manual/Reference/Gcodes#m671-define-positions-of-z-leadscrews-or-bed-levelling-screws)
- RepRapFirmware 3.5: [ZLeadscrewKinematics.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/Movement/Kinematics/ZLeadscrewKinematics.cpp) (`Configure()`), [StringParser.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5-dev/src/GCodes/GCodeBuffer/StringParser.cpp) (`CheckArrayLength()`)
)md",
};

void check(const NodeContext& cx, Sink& out) {
  if (!cx.is('M', 671)) return;
  const MachineState& s = cx.state;
  if (!s.kinematics_known || !has_leadscrews(s.kinematics)) return;
  const ParsedFile& pf = cx.parsed();
  const Command& c = cx.command();
  const M671Read r = m671_read(pf, c);
  if (r.form != M671Form::Mismatch && r.form != M671Form::TooLong) return;
  auto positions = [](size_t n, char axis) {  // n is 0 for a list from an expression
    return n == 0 ? fmt::format("{} {} list", axis == 'X' ? "an" : "a", axis)
                  : fmt::format("{} {} position{}", n, axis, n == 1 ? "" : "s");
  };
  const size_t nx = r.x.size(), ny = r.y.size();
  std::string what, answer;
  char at = 'X';  // the parameter the finding points at
  if (r.form == M671Form::TooLong) {
    at = nx > kMaxLeadscrews ? 'X' : 'Y';
    what = fmt::format("{}, more than the 4 RRF allows", at == 'X' ? positions(nx, 'X') : positions(ny, 'Y'));
    answer = "array too long, max length = 4";
  } else {
    at = r.has_y ? 'Y' : 'X';
    what = !r.has_y   ? positions(nx, 'X') + " and no Y list"
           : !r.has_x ? positions(ny, 'Y') + " and no X list"
                      : positions(nx, 'X') + " but " + positions(ny, 'Y');
    answer = "Specify 1, 2, 3 or 4 X and Y coordinates in M671";
  }
  // None set yet, or a change of kinematics type has dropped them (Leadscrews::dropped).
  const bool has_none = s.leadscrews.set == kNoNode || (s.leadscrews.dropped != kNoNode && !s.leadscrews.dropped_maybe);
  const ParamRef p = pf.find(c, at);
  out.report(kMeta, cx.at(p ? p->span : c.span),
             fmt::format("{} gives {}: RRF answers '{}' and {}", tools::quote(pf, c), what, answer,
                         has_none ? "sets no leadscrews, so G32 cannot level with the Z motors"
                                  : "keeps the leadscrew positions of the M671 before it"));
}

}  // namespace

extern const Rule leadscrew_coordinates{.meta = kMeta, .check_node = check, .on = "M671"};

}  // namespace rrflint
