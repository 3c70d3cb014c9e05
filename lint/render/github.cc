// `github`: GitHub Actions workflow commands, one annotation per finding:
//   ::error file=sys/config.g,line=12,endLine=12,col=1,endColumn=5,title=rrflint RRF101 unknown-command::message
// Message data escapes % CR LF; property values also ':' and ','. `col`/`endColumn` are left out when a
// finding spans lines (GitHub rejects that combination). Errors come first. GitHub shows at most 10 errors,
// 10 warnings and 10 notices per step (50 per job) and silently drops the rest, so findings past those limits
// are printed as plain log lines inside a folded group, and one notice says how many were left out.
#include <fmt/format.h>

#include <array>

#include "lint/render/render.h"

namespace fs = std::filesystem;

namespace rrflint {
namespace {

constexpr size_t kPerKind = 10;

std::string escape_data(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '%') out += "%25";
    else if (c == '\r') out += "%0D";
    else if (c == '\n') out += "%0A";
    else out += c;
  }
  return out;
}

std::string escape_property(std::string_view s) {
  std::string out;
  for (char c : escape_data(s)) {
    if (c == ':') out += "%3A";
    else if (c == ',') out += "%2C";
    else out += c;
  }
  return out;
}

std::string_view command(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Info: return "notice";
  }
  return "notice";
}

struct Paths {
  fs::path base, cwd;
  // Annotations need repository-relative paths; fall back to the display path outside the repository.
  std::string operator()(const SourceManager& sm, FileId file) const {
    if (file == kNoFile) return "-";
    const std::string& display = sm.get(file).display_path();
    const fs::path p(display);
    const fs::path abs = (p.is_absolute() ? p : cwd / p).lexically_normal();
    const fs::path rel = abs.lexically_relative(base);
    const std::string r = rel.generic_string();
    return rel.empty() || r.starts_with("..") ? display : r;
  }
};

}  // namespace

void render_github(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                   const RenderOptions& o) {
  std::error_code ec;
  Paths path{o.uri_base.empty() ? fs::current_path(ec) : o.uri_base, o.cwd.empty() ? fs::current_path(ec) : o.cwd};
  path.base = path.base.lexically_normal();

  // Errors first, then warnings, then infos; the order inside each kind is kept.
  std::array<std::vector<const Diagnostic*>, 3> by_kind;
  for (const Diagnostic& d : diags)
    by_kind[d.severity == Severity::Error ? 0 : d.severity == Severity::Warning ? 1 : 2].push_back(&d);
  std::array<size_t, 3> shown{};
  size_t overflow = 0;
  for (size_t k = 0; k < 3; ++k) {
    shown[k] = std::min(kPerKind, by_kind[k].size());
    overflow += by_kind[k].size() - shown[k];
  }
  // The summary is a notice itself: keep a notice slot free for it.
  if (overflow > 0 && shown[2] == kPerKind) {
    --shown[2];
    ++overflow;
  }

  auto plain = [&](const Diagnostic& d) {
    const Range r = range_of(sm, d.loc);
    return fmt::format("{}:{}:{}: {}: {} [{} {}]", path(sm, d.loc.file), r.start.line, r.start.column,
                       severity_name(d.severity), sanitize(d.message), d.code, d.name);
  };
  for (size_t k = 0; k < 3; ++k) {
    for (size_t i = 0; i < shown[k]; ++i) {
      const Diagnostic& d = *by_kind[k][i];
      const Range r = range_of(sm, d.loc);
      std::string props =
          fmt::format("file={},line={},endLine={}", escape_property(path(sm, d.loc.file)), r.start.line, r.end.line);
      if (r.start.line == r.end.line)
        props += fmt::format(",col={},endColumn={}", r.start.column, std::max(r.end.column, r.start.column + 1));
      props += ",title=" + escape_property(fmt::format("rrflint {} {}", d.code, d.name));
      std::string body = sanitize(d.message);
      for (const Note& n : d.notes) {
        if (n.loc.file == kNoFile) {
          body += fmt::format("\nnote: {}", sanitize(n.message));
          continue;
        }
        const Range nr = range_of(sm, n.loc);
        body += fmt::format("\nnote: {}:{}:{}: {}", path(sm, n.loc.file), nr.start.line, nr.start.column,
                            sanitize(n.message));
      }
      if (d.fix)
        body += fmt::format(
            "\nhelp: {} ({})", sanitize(d.fix->title),
            d.fix->applicability == Applicability::Safe ? "rrflint check --fix" : "rrflint check --fix --unsafe-fixes");
      // The annotation is read on github.com: a file:// page of the runner would not open there.
      if (is_web_url(o.docs_base)) body += fmt::format("\n{}", rule_url(o.docs_base, d.name));
      else body += fmt::format("\nrrflint rule {}", d.code);
      os << "::" << command(d.severity) << " " << props << "::" << escape_data(body) << "\n";
    }
  }
  if (overflow == 0) return;
  os << "::group::rrflint: " << overflow << " more finding" << (overflow == 1 ? "" : "s")
     << " (not shown as annotations)\n";
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = shown[k]; i < by_kind[k].size(); ++i) os << plain(*by_kind[k][i]) << "\n";
  os << "::endgroup::\n";
  os << "::notice title=rrflint::"
     << escape_data(fmt::format(
            "{} of {} findings are not shown as annotations: GitHub shows at most {} errors, {} warnings and {} "
            "notices per step (50 per job). They are listed in the log; upload the SARIF report "
            "(--format sarif) to see every finding.",
            overflow, diags.size(), kPerKind, kPerKind, kPerKind))
     << "\n";
}

}  // namespace rrflint
