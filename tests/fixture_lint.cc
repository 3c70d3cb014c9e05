#include "tests/fixture_lint.h"

#include <algorithm>
#include <sstream>
#include <tuple>

#include "lint/render/render.h"

namespace rrflint::fixture {

std::unique_ptr<LintRun> lint_card(const std::map<std::string, std::string>& card, const LintOptions& options) {
  auto run = std::make_unique<LintRun>();
  MemoryReader reader;
  for (const auto& [sd, text] : card) reader.add(sd, text);
  run->result = lint_machine(run->sources, reader, builtin_rules(), options);
  for (const Diagnostic& d : run->result.diagnostics) {
    Finding f;
    f.rule = std::string(d.name);
    f.message = d.message;
    f.diag = &d;
    if (d.loc.file != kNoFile && d.loc.file < run->sources.size()) {
      const SourceFile& src = run->sources.get(d.loc.file);
      const LineCol at = src.position(d.loc.span.begin);
      f.sd_path = src.sd_path();
      f.line = at.line;
      f.column = at.column;
    }
    run->findings.push_back(std::move(f));
  }
  return run;
}

std::vector<std::string> finding_lines(const LintRun& run) {
  std::vector<std::string> out;
  for (const Finding& f : run.findings)
    out.push_back(f.sd_path + ":" + std::to_string(f.line) + ":" + std::to_string(f.column) + ": " + f.message);
  return out;
}

std::string render_text_report(const LintRun& run, bool unsafe_fixes) {
  const SourceManager& sm = run.sources;
  std::vector<Diagnostic> diags = run.result.diagnostics;
  // The order cli/check.cc reports in: by display path, then position and code.
  std::stable_sort(diags.begin(), diags.end(), [&](const Diagnostic& a, const Diagnostic& b) {
    const std::string& fa = a.loc.file == kNoFile ? std::string() : sm.get(a.loc.file).display_path();
    const std::string& fb = b.loc.file == kNoFile ? std::string() : sm.get(b.loc.file).display_path();
    if (fa != fb) return fa < fb;
    return std::tie(a.loc.span.begin, a.code) < std::tie(b.loc.span.begin, b.code);
  });
  RenderOptions ro;
  ro.color = false;
  ro.docs_base = "docs/rules/";  // the pages in the repository: no machine-dependent path in a snapshot
  ro.unsafe_fixes_enabled = unsafe_fixes;
  ro.files_checked = run.result.machine ? run.result.machine->unit_count() : 0;
  std::ostringstream os;
  render_text(os, sm, diags, ro);
  return os.str();
}

}  // namespace rrflint::fixture
