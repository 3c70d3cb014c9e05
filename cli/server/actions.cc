// Code actions (textDocument/codeAction) for the findings of the last lint of a machine (workspace.h): each
// finding's fix as a `quickfix`, and a suppression comment on its line or for its whole file, written by the same
// code as `rrflint check --add-suppressions` (lint/engine/suppress.h); and `source.fixAll.rrflint`: every safe fix of
// the document at once, picked as `rrflint check --fix` picks them in one round (cli::apply_fixes: whole fixes,
// never two that overlap; a fix that reaches into another file is left out), as one edit of the part that changes,
// and not offered when it would leave the file with more parse errors than it has (cli::parses_worse).
#include <fmt/format.h>

#include "cli/server/model_at.h"
#include "cli/server/text.h"
#include "cli/server/workspace.h"
#include "lint/engine/suppress.h"

namespace rrflint::server {
namespace {

uint32_t line_of(const json& p) { return p.at("line").get<uint32_t>(); }

// Do the lines of two LSP ranges meet? A cursor anywhere on a finding's line (as clients send it) asks about it.
bool meets(const json& a, const json& b) {
  return line_of(a.at("start")) <= line_of(b.at("end")) && line_of(b.at("start")) <= line_of(a.at("end"));
}

constexpr std::string_view kFixAll = "source.fixAll.rrflint";

// Does the request's `context.only` (absent: every kind) admit `kind`? A kind admits its sub-kinds ("source"
// admits "source.fixAll.rrflint").
bool wants(const json& context, std::string_view kind) {
  auto only = context.find("only");
  if (only == context.end() || !only->is_array()) return true;
  for (const json& k : *only) {
    if (!k.is_string()) continue;
    const std::string& want = k.get_ref<const std::string&>();
    if (want.empty() || kind == want || (kind.starts_with(want) && kind[want.size()] == '.')) return true;
  }
  return false;
}

// The fix-all action for `file`: nullopt when it has no safe fix.
std::optional<json> fix_all(const Snapshot& s, FileId file, const std::string& uri) {
  std::map<FileId, std::string> texts;
  const size_t n = cli::apply_fixes(
      s.sm, s.result.diagnostics, cli::FixOptions{}, [&](FileId f) { return f == file; }, texts);
  auto it = texts.find(file);
  if (n == 0 || it == texts.end()) return std::nullopt;
  const SourceFile& f = s.sm.get(file);
  // A fix that made a syntax error would be a bug in a rule: the action is then not offered at all.
  if (cli::parses_worse(f, it->second)) return std::nullopt;
  const std::string_view before = f.text(), after = it->second;
  size_t head = 0, tail = 0;  // the bytes that stay at the start and at the end
  while (head < before.size() && head < after.size() && before[head] == after[head]) ++head;
  while (tail < before.size() - head && tail < after.size() - head &&
         before[before.size() - 1 - tail] == after[after.size() - 1 - tail])
    ++tail;
  // Ends where a position names the same byte, so that the edit replaces exactly the bytes that changed: not
  // inside a UTF-8 character, nor between a CR and its LF (range_json would move either end over a byte that the
  // new text then lacks, or holds twice).
  auto clean = [&](size_t i) {
    return i == 0 || i >= before.size() ||
           ((static_cast<unsigned char>(before[i]) & 0xC0) != 0x80 && !(before[i - 1] == '\r' && before[i] == '\n'));
  };
  while (!clean(head)) --head;
  while (!clean(before.size() - tail)) --tail;
  const Span changed{static_cast<uint32_t>(head), static_cast<uint32_t>(before.size() - tail)};
  json edit{{"range", range_json(f, changed)}, {"newText", after.substr(head, after.size() - tail - head)}};
  return json{{"title", fmt::format("fix all safe rrflint findings ({})", n)},
              {"kind", kFixAll},
              {"edit", {{"changes", {{uri, json::array({std::move(edit)})}}}}}};
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
  if (doc == docs_.end()) return out;
  auto m = machines_.find(doc->second.machine);
  if (m == machines_.end() || !m->second.last) return out;
  const Snapshot& s = *m->second.last;
  if (wants(context, kFixAll))
    if (const FileUnit* u = find_unit(s, [&](FileId f) { return s.uri_of(f) == uri; }))
      if (auto a = fix_all(s, u->source->id(), uri)) out.push_back(std::move(*a));
  if (!wants(context, "quickfix")) return out;
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
