// `json`: one document, {"version": 1, "diagnostics": [...], "summary": {...}}. The shape is a promise to
// editor integrations: fields are only ever added. Lines and columns are 1-based, columns count code points,
// ends are exclusive. `write_diagnostic_json` is shared with `json-lines`.
//
// Written as a stream (json_writer.h), members in sorted order as the nlohmann tree printed them before; the text
// is flushed to the stream every 64 KiB, so memory does not grow with the number of findings.
#include <algorithm>
#include <map>

#include "lint/base/parallel.h"

#include "lint/render/json_writer.h"
#include "lint/render/render.h"

namespace rrflint {
namespace {

// An edit or a note: {column, end_column, end_line, file, line, <text_key>: text}; `text` is valid UTF-8.
void write_located(JsonWriter& w, JsonPaths& paths, const Location& loc, std::string_view text_key,
                   std::string_view text) {
  const Range r = range_of(paths.sources(), loc);
  w.begin_object();
  w.member("column", r.start.column);
  w.member("end_column", r.end.column);
  w.member("end_line", r.end.line);
  w.member("file", paths.of(loc.file));
  w.member("line", r.start.line);
  w.member(text_key, text);
  w.end_object();
}

}  // namespace

const std::string& JsonPaths::of(FileId id) {
  auto [it, fresh] = paths_.try_emplace(id);
  if (fresh) it->second = id == kNoFile ? "-" : sanitize(sm_.get(id).display_path());
  return it->second;
}

void write_diagnostic_json(JsonWriter& w, JsonPaths& paths, const Diagnostic& d, std::string_view docs_base) {
  const Range r = range_of(paths.sources(), d.loc);
  w.begin_object();
  w.member("code", d.code);
  w.member("column", r.start.column);
  w.member("end_column", r.end.column);
  w.member("end_line", r.end.line);
  w.member("file", paths.of(d.loc.file));
  w.key("fix");
  if (d.fix) {
    w.begin_object();
    w.member("applicability", applicability_name(d.fix->applicability));
    w.key("edits");
    w.begin_array();
    // A fix's text keeps its line endings (the JSON escapes them); a message is sanitized.
    for (const Edit& e : d.fix->edits) write_located(w, paths, e.loc, "replacement", valid_utf8(e.replacement));
    w.end_array();
    w.member("message", sanitize(d.fix->title));
    w.end_object();
  } else {
    w.null();
  }
  w.member("line", r.start.line);
  w.member("message", sanitize(d.message));
  w.member("name", d.name);
  w.key("notes");
  w.begin_array();
  for (const Note& n : d.notes) write_located(w, paths, n.loc, "message", sanitize(n.message));
  w.end_array();
  w.member("severity", severity_name(d.severity));
  w.member("url", rule_url(docs_base, d.name));
  w.end_object();
}

void write_diagnostics_json(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                            const RenderOptions& o, size_t depth, bool first) {
  // A piece: diagnostics [b, e) into `out`, flushed to `os` every 64 KiB when it goes there directly.
  auto piece = [&](size_t b, size_t e, std::string& out, std::ostream* flush_to) {
    JsonWriter w(out, depth == 0 ? -1 : 2);
    JsonPaths paths(sm);
    for (size_t i = b; i < e; ++i) {
      if (depth == 0) w.resume(0, true);
      else w.resume(depth, first && i == 0);
      write_diagnostic_json(w, paths, diags[i], o.docs_base);
      if (depth == 0) out += '\n';
      if (flush_to && out.size() >= (64u << 10)) {
        *flush_to << out;
        out.clear();
      }
    }
  };
  constexpr size_t kPiece = 2048;  // findings: about 1.5 MB of json
  const unsigned threads = std::max(1u, o.threads);
  if (threads == 1 || diags.size() < 2 * kPiece) {
    std::string out;
    piece(0, diags.size(), out, &os);
    os << out;
    return;
  }
  // Rounds of two pieces per thread, so that memory stays a few pieces whatever the number of findings.
  const size_t round = size_t{2} * threads;
  std::vector<std::string> outs(round);
  for (size_t at = 0; at < diags.size(); at += round * kPiece) {
    const size_t n = std::min(round, (diags.size() - at + kPiece - 1) / kPiece);
    run_tasks(n, threads, [&](size_t k) {
      outs[k].clear();
      const size_t b = at + k * kPiece;
      piece(b, std::min(diags.size(), b + kPiece), outs[k], nullptr);
    });
    for (size_t k = 0; k < n; ++k) os << outs[k];
  }
}

namespace {

void write_machines(JsonWriter& w, const SourceManager& sm, const std::vector<MachineTarget>& machines) {
  w.begin_array();
  for (const MachineTarget& m : machines) {
    const Target& t = m.target;
    w.begin_object();
    w.member("board", board_name(t.board));
    w.member("board_reason", sanitize(t.board_reason));
    w.key("firmware");
    w.begin_object();
    w.key("evidence");
    w.begin_array();
    for (const Evidence& e : t.evidence) {
      w.begin_object();
      w.member("file", sanitize(sm.get(e.loc.file).display_path()));
      w.member("kind", e.kind == Evidence::Kind::Hint ? "hint" : "floor");
      w.member("line", sm.get(e.loc.file).position(e.loc.span.begin).line);
      w.member("version", floor_text(e.version));
      w.member("what", sanitize(e.what));
      w.end_object();
    }
    w.end_array();
    w.member("floor", floor_text(t.floor));
    w.member("reason", sanitize(t.reason));
    w.member("source", source_name(t.source));
    w.member("version", t.version.str());
    w.end_object();
    w.member("machine", sanitize(m.title));
    w.end_object();
  }
  w.end_array();
}

}  // namespace

void render_json(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                 const RenderOptions& o) {
  std::string buf;
  JsonWriter w(buf, 2);
  w.begin_object();
  w.key("diagnostics");
  w.begin_array();
  os << buf;
  buf.clear();
  write_diagnostics_json(os, sm, diags, o, 2, true);
  w.resume(2, diags.empty());
  w.end_array();
  w.key("machines");
  write_machines(w, sm, o.machines);
  write_summary_json(w, diags, o);
  w.member("version", 1);
  w.end_object();
  os << buf << "\n";
}

void write_summary_json(JsonWriter& w, const std::vector<Diagnostic>& diags, const RenderOptions& o) {
  const Counts c = count(diags);
  w.key("summary");
  w.begin_object();
  w.member("errors", c.errors);
  w.member("files_checked", o.files_checked);
  w.member("files_with_findings", c.files);
  w.member("fixable", c.fixable);
  w.member("fixed", o.fixed);
  w.member("infos", c.infos);
  w.member("warnings", c.warnings);
  w.end_object();
}

}  // namespace rrflint
