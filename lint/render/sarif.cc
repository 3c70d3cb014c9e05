// `sarif`: SARIF 2.1.0 as GitHub code scanning wants it: every rule in tool.driver.rules with short and full
// descriptions, help text and Markdown, helpUri (only when the rule docs have a web home) and default level; no
// informationUri (rrflint has no public home page, and no link beats a dead one); each result with ruleId,
// ruleIndex, level, a located message, partialFingerprints.primaryLocationLineHash, notes as relatedLocations
// and the fix as fixes[]. URIs are relative to the repository's top-level folder (uriBaseId %SRCROOT%), which
// keeps them stable across checkouts; columns count Unicode code points (columnKind says so).
#include <fmt/format.h>

#include <map>
#include <nlohmann/json.hpp>

#include "lint/engine/rule.h"
#include "lint/render/render.h"
#include "lint/render/rule_docs.h"

namespace fs = std::filesystem;

namespace rrflint {
namespace {

using nlohmann::json;

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

struct UriMaker {
  fs::path base, cwd;
  std::map<FileId, json> cache;

  json artifact(const SourceManager& sm, FileId file) {
    if (auto it = cache.find(file); it != cache.end()) return it->second;
    json loc;
    if (file == kNoFile) {
      loc = {{"uri", "unknown"}};
    } else {
      const fs::path display(sm.get(file).display_path());
      std::error_code ec;
      const fs::path abs = (display.is_absolute() ? display : cwd / display).lexically_normal();
      fs::path rel = abs.lexically_relative(base);
      const std::string r = rel.generic_string();
      if (!rel.empty() && !r.starts_with("..")) loc = {{"uri", uri_encode(r)}, {"uriBaseId", "%SRCROOT%"}};
      else loc = {{"uri", file_uri(abs)}};
    }
    cache.emplace(file, loc);
    return loc;
  }
};

json region(const SourceManager& sm, const Location& loc) {
  const Range r = range_of(sm, loc);
  return {{"startLine", r.start.line},
          {"startColumn", r.start.column},
          {"endLine", r.end.line},
          {"endColumn", r.end.column}};
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
json rule_json(const Rule& r, std::string_view docs_base) {
  const RuleMeta& m = r.meta;
  const std::string md = fmt::format("# {} {}\n\n{}\n{}", m.code, m.name, m.summary, published_docs(m.docs));
  json j = {{"id", m.code},
            {"name", m.name},
            {"shortDescription", {{"text", m.summary}}},
            {"fullDescription", {{"text", what_it_does(m)}}},
            {"help", {{"text", plain_docs(m)}, {"markdown", md}}},
            {"defaultConfiguration", {{"level", sarif_level(m.severity)}, {"enabled", m.default_enabled}}},
            {"properties",
             {{"tags", json::array({"rrflint", category_tag(m.code)})},
              {"precision", "high"},
              {"problem.severity", m.severity == Severity::Error     ? "error"
                                   : m.severity == Severity::Warning ? "warning"
                                                                     : "recommendation"}}}};
  if (is_web_url(docs_base)) j["helpUri"] = rule_url(docs_base, m.name);
  return j;
}

// A stable fingerprint: the rule and the trimmed text of the finding's line, hashed (FNV-1a), plus the
// occurrence of that hash in the file (GitHub's "hash:n" shape). It survives lines moving up or down.
std::string line_hash(const SourceManager& sm, const Diagnostic& d, std::map<std::string, int>& seen) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](std::string_view s) {
    for (unsigned char c : s) {
      h ^= c;
      h *= 1099511628211ull;
    }
  };
  mix(d.code);
  mix("\x1f");
  if (d.loc.file != kNoFile) {
    const SourceFile& f = sm.get(d.loc.file);
    if (f.line_count() > 0) {
      std::string_view line = f.slice(f.line_span(f.line_of(std::min(d.loc.span.begin, f.size()))));
      while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
      while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
      mix(line);
    }
  }
  std::string hex = fmt::format("{:016x}", h);
  const int n = ++seen[fmt::format("{}\x1f{}", d.loc.file, hex)];
  return fmt::format("{}:{}", hex, n);
}

}  // namespace

void render_sarif(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                  const RenderOptions& o) {
  std::error_code ec;
  UriMaker uris;
  uris.cwd = o.cwd.empty() ? fs::current_path(ec) : o.cwd;
  uris.base = (o.uri_base.empty() ? uris.cwd : o.uri_base).lexically_normal();

  json rules = json::array();
  std::map<std::string_view, size_t> index;
  if (o.rules)
    for (const Rule* r : o.rules->all()) {
      index[r->meta.code] = rules.size();
      rules.push_back(rule_json(*r, o.docs_base));
    }

  json results = json::array();
  std::map<std::string, int> seen;
  for (const Diagnostic& d : diags) {
    json res;
    res["ruleId"] = d.code;
    if (auto it = index.find(d.code); it != index.end()) res["ruleIndex"] = it->second;
    res["level"] = sarif_level(d.severity);
    res["message"] = {{"text", sanitize(d.message)}};
    json phys = {{"artifactLocation", uris.artifact(sm, d.loc.file)}};
    if (d.loc.file != kNoFile) phys["region"] = region(sm, d.loc);
    res["locations"] = json::array({{{"physicalLocation", phys}}});
    res["partialFingerprints"] = {{"primaryLocationLineHash", line_hash(sm, d, seen)}};
    if (!d.notes.empty()) {
      json related = json::array();
      int id = 1;
      for (const Note& n : d.notes) {
        json rl = {{"id", id++}, {"message", {{"text", sanitize(n.message)}}}};
        if (n.loc.file != kNoFile)
          rl["physicalLocation"] = {{"artifactLocation", uris.artifact(sm, n.loc.file)}, {"region", region(sm, n.loc)}};
        related.push_back(rl);
      }
      res["relatedLocations"] = related;
    }
    if (d.fix && !d.fix->edits.empty()) {
      // One artifactChange per file, edits in order.
      std::map<FileId, json> changes;
      for (const Edit& e : d.fix->edits) {
        if (e.loc.file == kNoFile) continue;
        json& c = changes[e.loc.file];
        if (c.is_null()) c = {{"artifactLocation", uris.artifact(sm, e.loc.file)}, {"replacements", json::array()}};
        json rep = {{"deletedRegion", region(sm, e.loc)}};
        if (!e.replacement.empty()) rep["insertedContent"] = {{"text", e.replacement}};
        c["replacements"].push_back(rep);
      }
      json arr = json::array();
      for (auto& [f, c] : changes) arr.push_back(c);
      if (!arr.empty())
        res["fixes"] = json::array({{{"description", {{"text", sanitize(d.fix->title)}}}, {"artifactChanges", arr}}});
    }
    res["properties"] = {{"name", d.name}, {"severity", severity_name(d.severity)}};
    if (d.fix) res["properties"]["fixApplicability"] = applicability_name(d.fix->applicability);
    results.push_back(res);
  }

  std::string base_uri = file_uri(uris.base);
  if (!base_uri.ends_with("/")) base_uri += '/';
  json run = {
      {"tool",
       {{"driver",
         {{"name", "rrflint"},
          {"fullName", "rrflint: a static analyser for RepRapFirmware configuration"},
          {"version", RRFLINT_VERSION},
          {"semanticVersion", RRFLINT_VERSION},
          {"rules", rules}}}}},
      {"originalUriBaseIds", {{"%SRCROOT%", {{"uri", base_uri}}}}},
      {"columnKind", "unicodeCodePoints"},
      {"results", results},
  };
  json doc = {
      {"$schema", "https://json.schemastore.org/sarif-2.1.0.json"}, {"version", "2.1.0"}, {"runs", json::array({run})}};
  os << doc.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
}

}  // namespace rrflint
