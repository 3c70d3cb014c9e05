// Code actions (textDocument/codeAction) for the findings of the last lint of a machine (workspace.h): each
// finding's fix as a `quickfix`, and a suppression comment on its line or for its whole file, written by the same
// code as `rrflint check --add-suppressions` (lint/engine/suppress.h).
#include <fmt/format.h>

#include "cli/server/model_at.h"
#include "cli/server/workspace.h"
#include "lint/engine/suppress.h"

namespace rrflint::server {
namespace {

uint32_t line_of(const json& p) { return p.at("line").get<uint32_t>(); }

// Do the lines of two LSP ranges meet? A cursor anywhere on a finding's line (as clients send it) asks about it.
bool meets(const json& a, const json& b) {
  return line_of(a.at("start")) <= line_of(b.at("end")) && line_of(b.at("start")) <= line_of(a.at("end"));
}

// Does the request's `context.only` (absent: every kind) admit `quickfix`?
bool wants_quickfix(const json& context) {
  auto only = context.find("only");
  if (only == context.end() || !only->is_array()) return true;
  for (const json& k : *only)
    if (k.is_string() && (k == "quickfix" || k == "")) return true;
  return false;
}

// A WorkspaceEdit for `edits`; nullopt when one of them is in a file without a URI.
std::optional<json> workspace_edit(const Snapshot& s, const std::vector<Edit>& edits) {
  json changes = json::object();
  for (const Edit& e : edits) {
    if (e.loc.file == kNoFile) return std::nullopt;
    std::optional<std::string> uri = s.uri_of(e.loc.file);
    if (!uri) return std::nullopt;
    changes[*uri].push_back({{"range", range_json(s.sm.get(e.loc.file), e.loc.span)}, {"newText", e.replacement}});
  }
  if (changes.empty()) return std::nullopt;
  return json{{"changes", std::move(changes)}};
}

json action(std::string title, const json& diagnostic, json edit, bool preferred) {
  json a{{"title", std::move(title)},
         {"kind", "quickfix"},
         {"diagnostics", json::array({diagnostic})},
         {"edit", std::move(edit)}};
  if (preferred) a["isPreferred"] = true;
  return a;
}

// The two suppressions of one finding: on its line (when the line holds code: on a line without code the CLI's
// edit is a file-wide one, offered below anyway) and in its file.
void add_suppressions(const Snapshot& s, const Diagnostic& d, const json& dj, json& out) {
  if (is_suppression_finding(d)) return;  // as --add-suppressions: RRF900/RRF901 are fixed, not suppressed
  const FileUnit* u = unit_of(s, d.loc.file);
  if (!u) return;
  const SourceFile& f = *u->source;
  const std::map<uint32_t, std::vector<std::string>> by_line{{f.line_of(d.loc.span.begin), {std::string(d.name)}}};
  std::vector<Edit> line = suppression_edits(u->parsed, builtin_rules(), by_line, "");
  const bool file_wide =
      line.size() == 1 && line[0].loc.span.begin == 0 && line[0].replacement.starts_with("; rrflint: disable-file=");
  if (!line.empty() && !file_wide)
    if (auto e = workspace_edit(s, line))
      out.push_back(action(fmt::format("suppress {} on this line", d.code), dj, std::move(*e), false));
  if (auto e = workspace_edit(s, {file_suppression_edit(f, d.name, "")}))
    out.push_back(action(fmt::format("suppress {} in this file", d.code), dj, std::move(*e), false));
}

}  // namespace

json Workspace::code_actions(const std::string& uri, const json& range, const json& context) const {
  json out = json::array();
  auto doc = docs_.find(uri);
  if (doc == docs_.end() || !wants_quickfix(context)) return out;
  auto m = machines_.find(doc->second.machine);
  if (m == machines_.end() || !m->second.last) return out;
  const Snapshot& s = *m->second.last;
  auto uri_of = [&](FileId id) { return s.uri_of(id); };
  for (const Diagnostic& d : s.result.diagnostics) {
    if (d.loc.file == kNoFile || s.uri_of(d.loc.file) != uri) continue;
    const json dj = diagnostic_json(s.sm, d, m->second.docs_base, uri_of);
    if (!meets(dj.at("range"), range)) continue;
    if (d.fix && !d.fix->edits.empty())
      if (auto e = workspace_edit(s, d.fix->edits)) {
        const bool safe = d.fix->applicability == Applicability::Safe;
        out.push_back(action(safe ? d.fix->title : d.fix->title + " (unsafe)", dj, std::move(*e), safe));
      }
    add_suppressions(s, d, dj, out);
  }
  return out;
}

}  // namespace rrflint::server
