// `gitlab`: a GitLab Code Quality report (the CodeClimate subset GitLab reads): a JSON array with one object per
// finding: check_name (the rule's code), description (the message, then the code and name in brackets, as the
// concise format ends), fingerprint (unique in the report and stable when lines move: GitLab compares them between
// the merge request and its target to show new and fixed findings), severity (error: major, warning: minor, info:
// info) and location {path relative to the repository, positions {begin, end} {line, column}}. Notes and fixes
// have no place in the format. Columns count code points, as everywhere else.
//
//   rrflint:
//     script: rrflint check --format gitlab -o gl-code-quality-report.json .
//     artifacts:
//       reports:
//         codequality: gl-code-quality-report.json
#include <fmt/format.h>

#include "lint/render/fingerprint.h"
#include "lint/render/json_writer.h"
#include "lint/render/render.h"

namespace rrflint {
namespace {

std::string_view gitlab_severity(Severity s) {
  switch (s) {
    case Severity::Error: return "major";
    case Severity::Warning: return "minor";
    case Severity::Info: break;
  }
  return "info";
}

void write_position(JsonWriter& w, std::string_view key, const LineCol& p) {
  w.key(key);
  w.begin_object();
  w.member("column", uint64_t{p.column});
  w.member("line", uint64_t{p.line});
  w.end_object();
}

}  // namespace

void render_gitlab(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                   const RenderOptions& o) {
  RepoPaths paths(o);
  Fingerprints fingerprints;
  std::string out;
  JsonWriter w(out, 2);
  w.begin_array();
  for (const Diagnostic& d : diags) {
    const RepoPath& p = paths.of(sm, d.loc.file);
    const std::string path = d.loc.file == kNoFile ? std::string("unknown") : sanitize(p.path);
    w.begin_object();
    w.member("check_name", d.code);
    w.member("description", fmt::format("{} [{} {}]", sanitize(d.message), d.code, d.name));
    // The line hash names the rule, the line's text and its occurrence in the file; the path makes it unique
    // across files. The path as it is, not as shown: two names that differ only in invalid UTF-8 show alike. Two
    // files under one path (a reader's "a/./b" and "a/b") count as one file, so their findings still differ.
    const std::string& raw = d.loc.file == kNoFile ? path : p.path;
    w.member("fingerprint", fmt::format("{:016x}", fnv1a(fingerprints(sm, d, raw), fnv1a(raw + '\x1f'))));
    w.key("location");
    w.begin_object();
    w.member("path", path);
    w.key("positions");
    w.begin_object();
    const Range r = d.loc.file == kNoFile ? Range{{1, 1}, {1, 1}} : range_of(sm, d.loc);
    write_position(w, "begin", r.start);
    write_position(w, "end", r.end);
    w.end_object();
    w.end_object();
    w.member("severity", gitlab_severity(d.severity));
    w.end_object();
    if (out.size() >= (64u << 10)) {
      os << out;
      out.clear();
    }
  }
  w.end_array();
  os << out << "\n";
}

}  // namespace rrflint
