// RRF307 g10-temperature-form: G10 sets tool temperatures where M568 does that job (RRF 3.3+).
#include <fmt/format.h>

#include "lint/engine/rule.h"
#include "rules/append_fix.h"
#include "rules/lex_common.h"
#include "rules/tool_helpers.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF307",
    .name = "g10-temperature-form",
    .severity = Severity::Info,
    .fix = FixAvailability::Sometimes,
    .tag = RuleTag::Deprecated,
    .summary = "G10 with R/S sets tool temperatures, which M568 does from RRF 3.3.",
    .docs = R"md(
## What it does
Reports a tool-form `G10` (no `L`, or `L1`) that sets standby (`R`) or active (`S`) temperatures, on targets
RRF 3.3 and later. The rule is silent for older targets, where `M568` does not set temperatures, and in
resurrect.g, which the firmware writes itself (with `G10` up to RRF 3.4).

## Firmware versions
A **deprecation** from RRF 3.3, where M568 is the documented form. It is judged at the target only.

## Why is this bad?
From RRF 3.3 `M568` sets tool temperatures, and the G-code dictionary says the temperature form of `G10` may be
removed in a future version. The firmware's deprecation warning is compiled out, so nothing on the machine tells
you. Keeping offsets on `G10` and temperatures on `M568` also makes each line do one thing.

## Example
```gcode
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M563 P0 D0 H1
G10 P0 X0 Y0 Z0 R150 S210
```

## Use instead
```gcode
M584 X0 Y1 Z2 E3
M308 S1 P"temp1" Y"thermistor" T100000 B4138
M950 H1 C"out1" T1
M563 P0 D0 H1
G10 P0 X0 Y0 Z0
M568 P0 R150 S210
```

## Fix safety
The fix moves `R` and `S` to a new `M568 P<n> R… S…` line right after the `G10`, with the same indentation and
line ending, and keeps the offsets on the `G10`; a `G10` that held only `P` and temperatures becomes the
`M568`. From RRF 3.3 both commands run the same firmware code (`SetOrReportOffsets`), so the effect is
unchanged: the fix is safe when the files rule out older firmware (`--firmware`, `.rrflint.toml`, or a command
that needs RRF 3.3 or later). When the target is 3.3 or later only because it is the newest release or a version
comment says so, the fix is unsafe: on RRF 3.2 and earlier `M568` does nothing, and the tool would lose its
temperatures. It is offered only when the `G10` is alone on its line and parses whole (no `;` cutting an
expression open), and for a `G10` without `P` only from RRF 3.4 (3.3's `M568` requires `P`).

## References
- rrflint: [G10 forms](../firmware-behaviour.md#g10-forms), [M568 tool settings](../firmware-behaviour.md#m568-tool-settings)
- Duet3D G-code dictionary: [G10: tool temperature setting](https://docs.duet3d.com/User_manual/Reference/Gcodes#g10-tool-temperature-setting), [M568: set tool settings](https://docs.duet3d.com/User_manual/Reference/Gcodes#m568-set-tool-settings)
- RepRapFirmware 3.5.3: [GCodes.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes.cpp) (`SetOrReportOffsets()`), [GCodes2.cpp](https://github.com/Duet3D/RepRapFirmware/blob/3.5.3/src/GCodes/GCodes2.cpp) (case 568)
)md",
};

/// The fix: move R/S to an M568 line after the G10, or turn the G10 into that M568.
std::optional<Fix> make_fix(const FileContext& cx, const Command& c) {
  const ParsedFile& pf = cx.parsed();
  const SourceFile& src = cx.source();
  const Line& line = pf.line_of(c);
  if (line.command_count != 1) return std::nullopt;
  // Not a command that does not parse whole: the M568 would copy the broken text (`P{pa@am.T}`, or an `S{…` that a
  // ';' cuts open), a new syntax error.
  if (!tools::parses_whole(pf, c)) return std::nullopt;
  const std::vector<Param> params(pf.params(c).begin(), pf.params(c).end());
  const Param *P = nullptr, *R = nullptr, *S = nullptr;
  bool others = false;
  for (const Param& p : params) {
    if (p.letter == 'P' || p.letter == 'R' || p.letter == 'S') {
      const Param*& slot = p.letter == 'P' ? P : p.letter == 'R' ? R : S;
      if (slot) return std::nullopt;  // a repeated letter: RRF reads the first; leave such lines alone
      slot = &p;
    } else if (p.letter != 'L') {
      others = true;
    }
  }
  const Version needs = P ? kRrf3_3 : kRrf3_4;  // 3.3's M568 requires P
  if (cx.target.version < needs) return std::nullopt;
  // Safe only when the files rule out the versions whose M568 does nothing (or lacks the P-less form): a target of
  // 3.3 or later that is only the newest release, or a version comment, may be a 3.2 machine, where the G10 works
  // and the M568 would not.
  const Applicability a = cx.target.floor >= needs ? Applicability::Safe : Applicability::Unsafe;
  std::string m568 = "M568";
  for (const Param* p : {P, R, S})
    if (p) m568 += " " + std::string(pf.text(p->span));
  const std::string why =
      a == Applicability::Safe ? std::string() : fmt::format(" if the firmware is RRF {} or later", floor_text(needs));
  Fix fix =
      others ? Fix::safe(fmt::format("move the temperatures to '{}'{}", clip(m568, 100), why))
             : Fix::safe(fmt::format("replace with '{}'{}", clip(m568, 100), why), Edit::replace(cx.at(c.span), m568));
  fix.applicability = a;
  if (!others) return fix;
  // Delete each of R and S with the blanks before it.
  for (const Param* p : {R, S}) {
    if (!p) continue;
    uint32_t begin = c.word.end;
    for (const Param* q = params.data(); q != p; ++q) begin = q->span.end;
    fix.edits.push_back(Edit::remove(cx.at(Span{begin, p->span.end})));
  }
  const Span ls = src.line_span(src.line_of(c.span.begin));
  fix.edits.push_back(Edit::insert(cx.at(Span{ls.end, ls.end}), lex::new_line_after(pf, line) + m568));
  return fix;
}

void check(const FileContext& cx, Sink& out) {
  if (cx.target.version < kRrf3_3) return;
  const ParsedFile& pf = cx.parsed();
  for (const uint32_t ci : pf.with_code('G', 10)) {
    const Command& c = pf.commands[ci];
    if (!c.is('G', 10)) continue;
    if (!pf.find(c, 'R') && !pf.find(c, 'S')) continue;
    if (g10_form(pf, c, nullptr, cx.target.version) != G10Form::Tool) continue;
    auto P = get_int(pf, c, 'P');
    const std::string tool = P.present() ? fmt::format("tool {}", clip(pf.text(P.param->value))) : "the current tool";
    Report r = out.report(kMeta, cx.at(c.span),
                          fmt::format("{} sets {}'s temperatures with G10: from RRF 3.3 'M568' sets them, and the "
                                      "temperature form of G10 may be removed",
                                      tools::quote(pf, c), tool));
    if (auto f = make_fix(cx, c)) r.fix(std::move(*f));
  }
}

}  // namespace

extern const Rule g10_temperature_form{.meta = kMeta, .check_file = check};

}  // namespace rrflint
