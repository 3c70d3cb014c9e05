// Version-gated hazards: a rule whose finding applies to some firmware versions only reports it at the target's
// severity, or as info with a note when it applies only at another version the files do not rule out
// (lint/boot/infer.h hazard_at; docs/firmware-behaviour.md#firmware-target).
#pragma once

#include <optional>
#include <string_view>

#include "lint/boot/infer.h"
#include "lint/engine/rule.h"

namespace rrflint::gate {

struct Gate {
  HazardAt at;
  Severity severity;
};

/// Where the hazard `applies` and how to report it: `own` at the target, info at another possible version; nullopt
/// when no possible version has it.
inline std::optional<Gate> hazard(const Target& t, bool (*applies)(Version), Severity own) {
  const HazardAt at = hazard_at(t, applies);
  if (at == HazardAt::Nowhere) return std::nullopt;
  return Gate{at, at == HazardAt::Target ? own : Severity::Info};
}

/// "RRF 3.6" at the target, else "RRF versions <versions>" ("RRF versions before 3.6.0-beta.3"), for the message.
inline std::string on(const Gate& g, const Target& t, std::string_view versions) {
  return g.at == HazardAt::Target ? "RRF " + t.version.str() : "RRF versions " + std::string(versions);
}

/// For a finding at another possible version: the note that says so, at the evidence of the floor (else at `at`).
inline void explain(Report& r, const Gate& g, const Target& t, Location at, std::string_view versions) {
  if (g.at != HazardAt::Possible) return;
  for (const Evidence& e : t.evidence)
    if (e.kind == Evidence::Kind::Floor && e.version == t.floor) at = e.loc;
  r.note(at, possible_note(t, versions));
}

}  // namespace rrflint::gate
