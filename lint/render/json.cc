// `json`: one document, {"version": 1, "diagnostics": [...], "summary": {...}}. The shape is a promise to
// editor integrations: fields are only ever added. Lines and columns are 1-based, columns count code points,
// ends are exclusive. `diagnostic_json` is shared with `json-lines`.
#include <nlohmann/json.hpp>

#include "lint/render/render.h"

namespace rrflint {

nlohmann::json diagnostic_json(const SourceManager& sm, const Diagnostic& d, std::string_view docs_base) {
  using nlohmann::json;
  const Range r = range_of(sm, d.loc);
  json j;
  j["code"] = d.code;
  j["name"] = d.name;
  j["severity"] = severity_name(d.severity);
  j["message"] = sanitize(d.message);
  j["file"] = d.loc.file == kNoFile ? "-" : sanitize(sm.get(d.loc.file).display_path());
  j["line"] = r.start.line;
  j["column"] = r.start.column;
  j["end_line"] = r.end.line;
  j["end_column"] = r.end.column;
  j["url"] = rule_url(docs_base, d.name);
  json notes = json::array();
  for (const Note& n : d.notes) {
    const Range nr = range_of(sm, n.loc);
    json jn;
    jn["file"] = n.loc.file == kNoFile ? "-" : sanitize(sm.get(n.loc.file).display_path());
    jn["line"] = nr.start.line;
    jn["column"] = nr.start.column;
    jn["end_line"] = nr.end.line;
    jn["end_column"] = nr.end.column;
    jn["message"] = sanitize(n.message);
    notes.push_back(jn);
  }
  j["notes"] = notes;
  if (d.fix) {
    json edits = json::array();
    for (const Edit& e : d.fix->edits) {
      const Range er = range_of(sm, e.loc);
      edits.push_back({{"file", sanitize(sm.get(e.loc.file).display_path())},
                       {"line", er.start.line},
                       {"column", er.start.column},
                       {"end_line", er.end.line},
                       {"end_column", er.end.column},
                       {"replacement", sanitize(e.replacement)}});
    }
    j["fix"] = {{"applicability", applicability_name(d.fix->applicability)},
                {"message", sanitize(d.fix->title)},
                {"edits", edits}};
  } else {
    j["fix"] = nullptr;
  }
  return j;
}

void render_json(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                 const RenderOptions& o) {
  using nlohmann::json;
  json doc;
  doc["version"] = 1;
  json arr = json::array();
  for (const Diagnostic& d : diags) arr.push_back(diagnostic_json(sm, d, o.docs_base));
  doc["diagnostics"] = arr;
  json machines = json::array();
  for (const MachineTarget& m : o.machines) {
    const Target& t = m.target;
    json ev = json::array();
    for (const Evidence& e : t.evidence)
      ev.push_back({{"kind", e.kind == Evidence::Kind::Hint ? "hint" : "floor"},
                    {"version", floor_text(e.version)},
                    {"what", sanitize(e.what)},
                    {"file", sanitize(sm.get(e.loc.file).display_path())},
                    {"line", sm.get(e.loc.file).position(e.loc.span.begin).line}});
    machines.push_back({{"machine", sanitize(m.title)},
                        {"firmware",
                         {{"version", t.version.str()},
                          {"source", source_name(t.source)},
                          {"floor", floor_text(t.floor)},
                          {"reason", sanitize(t.reason)},
                          {"evidence", ev}}},
                        {"board", board_name(t.board)},
                        {"board_reason", sanitize(t.board_reason)}});
  }
  doc["machines"] = machines;
  const Counts c = count(diags);
  doc["summary"] = {{"errors", c.errors},   {"warnings", c.warnings},         {"infos", c.infos},
                    {"fixable", c.fixable}, {"files_with_findings", c.files}, {"files_checked", o.files_checked},
                    {"fixed", o.fixed}};
  os << doc.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
}

}  // namespace rrflint
