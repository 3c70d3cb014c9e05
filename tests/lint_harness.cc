#include "tests/lint_harness.h"

#include <sstream>

#include <fmt/format.h>

namespace rrflint::harness {

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
      f.sd_path = src.sd_path();
      f.line = src.position(d.loc.span.begin).line;
    }
    run->findings.push_back(std::move(f));
  }
  return run;
}

std::vector<std::pair<size_t, size_t>> split_lines(std::string_view t) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t b = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] != '\n' && t[i] != '\r') continue;
    out.emplace_back(b, i);
    if (t[i] == '\r' && i + 1 < t.size() && t[i + 1] == '\n') ++i;
    b = i + 1;
  }
  if (b < t.size() || out.empty()) out.emplace_back(b, t.size());
  return out;
}

bool read_options_line(std::string_view line, CaseOptions& o, std::vector<std::string>& problems) {
  const size_t at = line.find("rrflint-options:");
  if (at == std::string_view::npos || line.substr(0, at).find(';') == std::string_view::npos) return false;
  std::string_view rest = line.substr(at + 16);
  rest = rest.substr(0, rest.find(';'));  // an expectation may follow on the same line
  std::istringstream words{std::string(rest)};
  std::string w;
  while (words >> w) {
    std::string arg;
    if (w == "--tool-changer") {
      o.lint.tool_changer = true;
    } else if (w == "--unsafe-fixes") {
      o.unsafe_fixes = true;
    } else if (w == "--extend-select" && words >> arg) {
      o.lint.extend_select.push_back(arg);  // another rule on as well (RRF900 needs a rule to suppress)
    } else if (w == "--firmware" && words >> arg) {
      if (auto v = Version::parse(arg)) o.lint.firmware = *v;
      else problems.push_back(fmt::format("bad --firmware '{}'", arg));
    } else if (w == "--board" && words >> arg) {
      if (auto b = parse_board(arg)) o.lint.board = *b;
      else problems.push_back(fmt::format("bad --board '{}'", arg));
    } else {
      problems.push_back(fmt::format("unknown rrflint-options word '{}'", w));
    }
  }
  return true;
}

}  // namespace rrflint::harness
