// What a job could not lint, said on stderr: `rrflint check` must never pass over a file it was asked to lint.
#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <string>

#include "cli/cli.h"
#include "lint/base/strings.h"

namespace rrflint::cli {

// What a job could not lint. A config.g that cannot be linted makes the card an error (exit 2), and so does a file
// named on the command line that was not linted; other files that cannot be linted are findings (RRF506). The
// caller counts the files linted (Totals::linted), so that a run over nothing never passes.
bool note_unlinted(const Job& job, const Effective& eff, const Machine& m, bool& lone_hint) {
  bool failed = false;
  const std::string config = to_lower(eff.lint.sys_dir + "/config.g");
  std::set<std::string> linted;
  for (uint32_t i = 0; i < m.unit_count(); ++i) linted.insert(to_lower(m.unit(i).sd_path));
  for (const LoadProblem& p : m.problems()) {
    const std::string sd = to_lower(p.sd_path);
    if (sd == config &&
        (job.card || job.standalone.empty() || to_lower(job.standalone.filename().string()) == "config.g")) {
      error(fmt::format("{}: cannot lint config.g: {}", p.display, p.message));
      failed = true;
    } else if (job.named.count(sd) || (!job.card && job.explicit_path)) {
      error(fmt::format("{}: {}", p.display, p.message));
      failed = true;
    }
  }
  for (const auto& [named_sd, as_named] : job.named)
    if (const std::string& sd = named_sd;  // a structured binding: clang 14 lets no lambda capture one
        !linted.count(sd) && std::none_of(m.problems().begin(), m.problems().end(),
                                          [&](const LoadProblem& p) { return to_lower(p.sd_path) == sd; })) {
      error(
          fmt::format("{}: not linted: not a G-code file (rrflint lints *.g files, and macros without an extension "
                      "below macros/)",
                      as_named));
      failed = true;
    }
  if (!job.card && m.unit_count() == 0 && m.problems().empty() && job.explicit_path) {
    error(fmt::format("{}: not linted: not a G-code file (rrflint lints *.g files)", job.title));
    failed = true;
  }
  if (!job.card && job.explicit_path && m.unit_count() > 0 &&
      to_lower(job.standalone.filename().string()) != "config.g")
    lone_hint = true;
  return failed;
}

}  // namespace rrflint::cli
