// `sarif`: SARIF 2.1.0 as GitHub code scanning wants it: every rule in tool.driver.rules with short and full
// descriptions, help text and Markdown, helpUri (only when the rule docs have a web home) and default level; no
// informationUri (rrflint has no public home page, and no link beats a dead one); each result with ruleId,
// ruleIndex, level, a located message, partialFingerprints.primaryLocationLineHash, notes as relatedLocations
// and the fix as fixes[]. URIs are relative to the repository's top-level folder (uriBaseId %SRCROOT%), which
// keeps them stable across checkouts; columns count Unicode code points (columnKind says so).
//
// Written as a stream (json_writer.h), members in sorted order as the nlohmann tree printed them before, flushed to
// the stream every 64 KiB: the tree took 1 GB and 5.6 s for the 50,000 findings of gen-corpus-big at 100 MB.
#include <fmt/format.h>

#include <map>

#include "lint/engine/rule.h"
#include "lint/render/fingerprint.h"
#include "lint/render/json_writer.h"
#include "lint/render/render.h"
#include "lint/render/rule_docs.h"

namespace fs = std::filesystem;

namespace rrflint {
namespace {

std::string_view sarif_level(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Info: return "note";
  }
  return "none";
}

// Percent-encodes a '/'-separated path for a URI (RFC 3986: unreserved characters and '/' stay).
std::string uri_encode(std::string_view path) {
  std::string out;
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') out += static_cast<char>(c);
    else out += fmt::format("%{:02X}", c);
  }
  return out;
}

std::string file_uri(const fs::path& abs) {
  std::string p = abs.generic_string();
  if (!p.starts_with("/")) p = "/" + p;
  return "file://" + uri_encode(p);
}

// An artifactLocation: {"uri", "uriBaseId"?}.
struct Artifact {
  std::string uri;
  bool in_base = false;  // relative to %SRCROOT%
};

// Each file's artifactLocation: relative to the repository (%SRCROOT%) when inside it, else a file:// URI.
struct UriMaker {
  RepoPaths paths;
  std::map<FileId, Artifact> cache;

  const Artifact& artifact(const SourceManager& sm, FileId file) {
    auto [it, fresh] = cache.try_emplace(file);
    if (!fresh) return it->second;
    Artifact& a = it->second;
    const RepoPath& p = paths.of(sm, file);
    if (file == kNoFile) a.uri = "unknown";
    else if (p.in_base) a = {uri_encode(p.path), true};
    else a.uri = file_uri(p.abs);
    return a;
  }
};

void write_artifact(JsonWriter& w, const Artifact& a) {
  w.key("artifactLocation");
  w.begin_object();
  w.member("uri", a.uri);
  if (a.in_base) w.member("uriBaseId", "%SRCROOT%");
  w.end_object();
}

void write_region(JsonWriter& w, const SourceManager& sm, const Location& loc, std::string_view k = "region") {
  const Range r = range_of(sm, loc);
  w.key(k);
  w.begin_object();
  w.member("endColumn", r.end.column);
  w.member("endLine", r.end.line);
  w.member("startColumn", r.start.column);
  w.member("startLine", r.start.line);
  w.end_object();
}

/// {"text": text}, under key k.
void write_text(JsonWriter& w, std::string_view k, std::string_view text) {
  w.key(k);
  w.begin_object();
  w.member("text", text);
  w.end_object();
}

// The "## What it does" section of a rule's docs, as one plain paragraph.
std::string what_it_does(const RuleMeta& m) {
  std::string_view docs = m.docs;
  size_t at = docs.find("## What it does");
  if (at == std::string_view::npos) return std::string(m.summary);
  docs.remove_prefix(at + 15);
  size_t end = docs.find("\n## ");
  std::string_view body = docs.substr(0, end);
  std::string out;
  bool space = false;
  for (char c : body) {
    if (c == '\n' || c == ' ' || c == '\t') {
      space = !out.empty();
      continue;
    }
    if (space) out += ' ';
    space = false;
    out += c;
  }
  return out.empty() ? std::string(m.summary) : out;
}

// The docs as plain text: headings without '#', code fences dropped.
std::string plain_docs(const RuleMeta& m) {
  std::string out = fmt::format("{} {}: {}\n", m.code, m.name, m.summary);
  std::string_view docs = m.docs;
  while (!docs.empty()) {
    size_t nl = docs.find('\n');
    std::string_view line = docs.substr(0, nl);
    docs = nl == std::string_view::npos ? std::string_view{} : docs.substr(nl + 1);
    if (line.starts_with("```")) continue;
    if (line.starts_with("## ")) line.remove_prefix(3);
    out += line;
    out += '\n';
  }
  return out;
}

std::string_view category_tag(std::string_view code) {
  if (code.size() < 4) return "other";
  switch (code[3]) {
    case '1': return "syntax";
    case '2': return "order";
    case '3': return "tools";
    case '4': return "config-override";
    case '5': return "files";
    case '9': return "suppression";
  }
  return "other";
}

// helpUri only for a web home of the docs: code scanning opens it in the reader's browser, where a file:// page
// of the machine that ran rrflint does not exist (help.markdown carries the page either way).
void write_rule(JsonWriter& w, const Rule& r, std::string_view docs_base) {
  const RuleMeta& m = r.meta;
  w.begin_object();
  w.key("defaultConfiguration");
  w.begin_object();
  w.member("enabled", m.default_enabled);
  w.member("level", sarif_level(m.severity));
  w.end_object();
  write_text(w, "fullDescription", what_it_does(m));
  w.key("help");
  w.begin_object();
  w.member("markdown", fmt::format("# {} {}\n\n{}\n{}", m.code, m.name, m.summary, published_docs(m.docs)));
  w.member("text", plain_docs(m));
  w.end_object();
  if (is_web_url(docs_base)) w.member("helpUri", rule_url(docs_base, m.name));
  w.member("id", m.code);
  w.member("name", m.name);
  w.key("properties");
  w.begin_object();
  w.member("precision", "high");
  w.member("problem.severity", m.severity == Severity::Error     ? "error"
                               : m.severity == Severity::Warning ? "warning"
                                                                 : "recommendation");
  w.key("tags");
  w.begin_array();
  w.value("rrflint");
  w.value(category_tag(m.code));
  w.end_array();
  w.end_object();
  write_text(w, "shortDescription", m.summary);
  w.end_object();
}

// One result; `index`: each rule's place in tool.driver.rules.
void write_result(JsonWriter& w, const SourceManager& sm, UriMaker& uris, const Diagnostic& d,
                  const std::map<std::string_view, size_t>& index, Fingerprints& fingerprints) {
  w.begin_object();
  if (d.fix && !d.fix->edits.empty()) {
    // One artifactChange per file, edits in order.
    std::map<FileId, std::vector<const Edit*>> changes;
    for (const Edit& e : d.fix->edits)
      if (e.loc.file != kNoFile) changes[e.loc.file].push_back(&e);
    if (!changes.empty()) {
      w.key("fixes");
      w.begin_array();
      w.begin_object();
      w.key("artifactChanges");
      w.begin_array();
      for (const auto& [file, edits] : changes) {
        w.begin_object();
        write_artifact(w, uris.artifact(sm, file));
        w.key("replacements");
        w.begin_array();
        for (const Edit* e : edits) {
          w.begin_object();
          write_region(w, sm, e->loc, "deletedRegion");
          if (!e->replacement.empty()) write_text(w, "insertedContent", valid_utf8(e->replacement));
          w.end_object();
        }
        w.end_array();
        w.end_object();
      }
      w.end_array();
      write_text(w, "description", sanitize(d.fix->title));
      w.end_object();
      w.end_array();
    }
  }
  w.member("level", sarif_level(d.severity));
  w.key("locations");
  w.begin_array();
  w.begin_object();
  w.key("physicalLocation");
  w.begin_object();
  write_artifact(w, uris.artifact(sm, d.loc.file));
  if (d.loc.file != kNoFile) write_region(w, sm, d.loc);
  w.end_object();
  w.end_object();
  w.end_array();
  write_text(w, "message", sanitize(d.message));
  w.key("partialFingerprints");
  w.begin_object();
  w.member("primaryLocationLineHash", fingerprints(sm, d));
  w.end_object();
  w.key("properties");
  w.begin_object();
  if (d.fix) w.member("fixApplicability", applicability_name(d.fix->applicability));
  w.member("name", d.name);
  w.member("severity", severity_name(d.severity));
  w.end_object();
  if (!d.notes.empty()) {
    w.key("relatedLocations");
    w.begin_array();
    int id = 1;
    for (const Note& n : d.notes) {
      w.begin_object();
      w.member("id", id++);
      write_text(w, "message", sanitize(n.message));
      if (n.loc.file != kNoFile) {
        w.key("physicalLocation");
        w.begin_object();
        write_artifact(w, uris.artifact(sm, n.loc.file));
        write_region(w, sm, n.loc);
        w.end_object();
      }
      w.end_object();
    }
    w.end_array();
  }
  w.member("ruleId", d.code);
  if (auto it = index.find(d.code); it != index.end()) w.member("ruleIndex", uint64_t{it->second});
  w.end_object();
}

}  // namespace

void render_sarif(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                  const RenderOptions& o) {
  UriMaker uris{RepoPaths(o)};
  std::string base_uri = file_uri(uris.paths.base());
  if (!base_uri.ends_with("/")) base_uri += '/';

  std::string out;
  auto flush = [&] {
    if (out.size() < (64u << 10)) return;
    os << out;
    out.clear();
  };
  JsonWriter w(out, 2);
  w.begin_object();
  w.member("$schema", "https://json.schemastore.org/sarif-2.1.0.json");
  w.key("runs");
  w.begin_array();
  w.begin_object();
  w.member("columnKind", "unicodeCodePoints");
  w.key("originalUriBaseIds");
  w.begin_object();
  w.key("%SRCROOT%");
  w.begin_object();
  w.member("uri", base_uri);
  w.end_object();
  w.end_object();

  std::map<std::string_view, size_t> index;
  if (o.rules)
    for (const Rule* r : o.rules->all()) index.emplace(r->meta.code, index.size());
  w.key("results");
  w.begin_array();
  Fingerprints fingerprints;
  for (const Diagnostic& d : diags) {
    write_result(w, sm, uris, d, index, fingerprints);
    flush();
  }
  w.end_array();

  w.key("tool");
  w.begin_object();
  w.key("driver");
  w.begin_object();
  w.member("fullName", "rrflint: a static analyser for RepRapFirmware configuration");
  w.member("name", "rrflint");
  w.key("rules");
  w.begin_array();
  if (o.rules)
    for (const Rule* r : o.rules->all()) write_rule(w, *r, o.docs_base);
  w.end_array();
  w.member("semanticVersion", RRFLINT_VERSION);
  w.member("version", RRFLINT_VERSION);
  w.end_object();
  w.end_object();
  w.end_object();
  w.end_array();
  w.member("version", "2.1.0");
  w.end_object();
  os << out << "\n";
}

}  // namespace rrflint
