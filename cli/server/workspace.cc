// The language server's documents and machines (workspace.h).
#include "cli/server/workspace.h"

#include <fmt/format.h>

#include <algorithm>

#include "cli/server/text.h"
#include "lint/render/render.h"

namespace rrflint::server {
namespace {

namespace fs = std::filesystem;

// The lone document's file name for a URI that names no file ("untitled:Untitled-1" -> "Untitled-1.g": the client
// sent it as G-code, so it is linted as a macro whatever its name).
std::string name_of_uri(const std::string& uri) {
  const size_t cut = uri.find_last_of("/:");
  std::string name = cut == std::string::npos ? uri : uri.substr(cut + 1);
  if (!to_lower(name).ends_with(".g")) name += ".g";
  return name;
}

int severity_of(Severity s) {
  switch (s) {
    case Severity::Error: return 1;
    case Severity::Warning: return 2;
    case Severity::Info: return 3;
  }
  return 2;
}

}  // namespace

json diagnostic_json(const SourceManager& sm, const Diagnostic& d, const std::string& docs_base,
                     const std::function<std::optional<std::string>(FileId)>& uri_of) {
  json j{{"range", range_json(sm.get(d.loc.file), d.loc.span)},
         {"severity", severity_of(d.severity)},
         {"code", d.code},
         {"codeDescription", {{"href", rule_url(docs_base, d.name)}}},
         {"source", "rrflint"},
         {"message", d.message}};
  if (const Rule* r = builtin_rules().find(d.code); r && r->meta.tag != RuleTag::None)
    j["tags"] = json::array({r->meta.tag == RuleTag::Unnecessary ? 1 : 2});
  json related = json::array();
  for (const Note& n : d.notes) {
    if (n.loc.file == kNoFile) continue;
    auto uri = uri_of(n.loc.file);
    if (!uri) continue;
    related.push_back(
        {{"location", {{"uri", *uri}, {"range", range_json(sm.get(n.loc.file), n.loc.span)}}}, {"message", n.message}});
  }
  if (!related.empty()) j["relatedInformation"] = std::move(related);
  return j;
}

std::optional<std::string> Snapshot::uri_of(FileId id) const {
  auto it = uris.find(id);
  return it == uris.end() ? std::nullopt : it->second;
}

void OverlayReader::add(const std::string& sd_path, std::string display, std::string bytes) {
  buffers_[to_lower(sd_path)] = Buffer{sd_path, std::move(display), std::move(bytes)};
}

ReadResult OverlayReader::read(std::string_view sd_path) {
  auto it = buffers_.find(to_lower(sd_path));
  if (it == buffers_.end()) return base_.read(sd_path);
  ReadResult r;
  r.status = ReadResult::Status::Ok;
  r.bytes = it->second.bytes;
  r.display = it->second.display;
  r.sd_path = it->second.sd_path;
  return r;
}

std::vector<std::string> OverlayReader::list(std::string_view sd_dir) {
  std::vector<std::string> out = base_.list(sd_dir);
  std::string prefix = to_lower(sd_dir);
  if (!prefix.ends_with('/')) prefix += '/';
  std::set<std::string> seen;
  for (const std::string& p : out) seen.insert(to_lower(p));
  for (const auto& [lower, b] : buffers_)  // buffers not saved yet
    if (lower.starts_with(prefix) && seen.insert(lower).second) out.push_back(b.sd_path);
  std::sort(out.begin(), out.end());
  return out;
}

const std::string* Workspace::text(const std::string& uri) const {
  auto it = docs_.find(uri);
  return it == docs_.end() ? nullptr : &it->second.text;
}

void Workspace::place(Document& doc) {
  doc.sd_path.clear();
  std::optional<cli::FilePlace> at;
  if (doc.path) at = cli::place_file(*doc.path);
  if (at) {
    doc.machine = at->card.sys_dir.string();
    doc.sd_path = at->sd_path;
    machines_[doc.machine].card = at->card;
  } else {
    doc.machine = "lone:" + doc.uri;
    machines_[doc.machine].lone_uri = doc.uri;
  }
}

void Workspace::open(const std::string& uri, std::string text, int64_t version) {
  Document& doc = docs_[uri];
  const std::string before = doc.machine;
  doc.uri = uri;
  doc.path = path_of_uri(uri);
  if (doc.path) doc.path = absolute_normal(*doc.path);
  doc.text = std::move(text);
  doc.version = version;
  place(doc);
  if (!before.empty() && before != doc.machine) schedule(before, true);  // opened again elsewhere
  schedule(doc.machine, true);
}

void Workspace::change(const std::string& uri, int64_t version, const json& changes) {
  auto it = docs_.find(uri);
  if (it == docs_.end()) {
    log_(2, fmt::format("didChange for a document that is not open: {}", uri));
    return;
  }
  Document& doc = it->second;
  for (const json& c : changes) {
    if (!c.contains("range")) {
      doc.text = c.at("text").get<std::string>();
      continue;
    }
    const json& r = c.at("range");
    auto pos = [](const json& p) { return Position{p.at("line").get<uint32_t>(), p.at("character").get<uint32_t>()}; };
    apply_change(doc.text, pos(r.at("start")), pos(r.at("end")), c.at("text").get<std::string>());
  }
  doc.version = version;
  schedule(doc.machine, false);
}

void Workspace::save(const std::string& uri) {
  auto it = docs_.find(uri);
  if (it == docs_.end()) return;
  replace(it->second);  // saving can make a card (a config.g written): the document may move to another machine
  schedule(it->second.machine, true);
}

void Workspace::replace(Document& doc) {
  const std::string before = doc.machine;
  place(doc);
  if (before == doc.machine) return;
  if (std::none_of(docs_.begin(), docs_.end(), [&](const auto& d) { return d.second.machine == before; }))
    clear(before);
  else schedule(before, true);
  schedule(doc.machine, true);
}

void Workspace::close(const std::string& uri) {
  auto it = docs_.find(uri);
  if (it == docs_.end()) return;
  const std::string key = it->second.machine;
  docs_.erase(it);
  if (std::any_of(docs_.begin(), docs_.end(), [&](const auto& d) { return d.second.machine == key; }))
    schedule(key, true);
  else clear(key);
}

void Workspace::schedule(const std::string& key, bool now) {
  waiting_.insert(key);
  due_ = now ? Clock::now() : Clock::now() + options_.debounce;
}

std::optional<Workspace::Clock::time_point> Workspace::due() const {
  if (waiting_.empty()) return std::nullopt;
  return due_;
}

void Workspace::flush() {
  for (const std::string& key : std::exchange(waiting_, {})) lint(key);
}

void Workspace::set_options(const ServerOptions& o) {
  options_ = o;
  shown_.clear();  // a configuration error is shown again if it is still there
  for (const auto& [key, m] : machines_) schedule(key, true);
}

void Workspace::files_changed(const std::vector<std::string>& paths) {
  for (auto& [uri, d] : docs_) replace(d);
  for (const std::string& p : paths) {
    const bool config = fs::path(p).filename() == ".rrflint.toml";
    for (const auto& [key, m] : machines_)
      if (config || (m.card && relative_below(fs::path(p), m.card->root))) schedule(key, true);
  }
}

// The job for a machine entry: the card with every file reported, or the lone document as standard input.
cli::Job Workspace::job_of(const MachineEntry& m, const Document* lone) const {
  cli::Job job;
  if (m.card) {
    job.card = m.card;
    job.report_all = true;
    job.title = m.card->root.string();
    job.dirs = std::make_shared<DirCache>();  // listed afresh: files come and go on disk between lints
  } else {
    job.standalone = lone->path ? fs::path(*lone->path) : fs::path(name_of_uri(lone->uri));
    job.stdin_bytes = lone->text;
    job.title = job.standalone.string();
  }
  return job;
}

void Workspace::lint(const std::string& key) {
  auto mit = machines_.find(key);
  if (mit == machines_.end()) return;
  MachineEntry& m = mit->second;
  const Document* lone = nullptr;
  if (!m.card) {
    auto d = docs_.find(m.lone_uri);
    if (d == docs_.end()) return;
    lone = &d->second;
  }
  auto snap = std::make_unique<Snapshot>(job_of(m, lone));
  m.last.reset();
  cli::Settings settings(options_.cli);  // afresh each time: .rrflint.toml may have changed
  cli::Effective eff;
  std::error_code ec;
  const fs::path dir =
      m.card ? m.card->sys_dir : (lone->path ? fs::path(*lone->path).parent_path() : fs::current_path(ec));
  if (!settings.effective(dir, eff)) {
    // Logged each time, shown once until it changes (not on every keystroke).
    const std::string why = fmt::format("rrflint: not linted: {}", settings.config_error()->str());
    log_(1, why);
    if (why != shown_) send_(notification("window/showMessage", {{"type", 1}, {"message", why}}));
    shown_ = why;
    std::map<std::string, json> none;  // what was published is for texts that have changed since: cleared
    publish_all(key, m, none);
    return;
  }
  shown_.clear();
  eff.lint.threads = cli::default_threads();
  std::map<std::string, const Document*> by_sd;  // lower-cased SD path -> open buffer
  for (const auto& [uri, d] : docs_)
    if (m.card && d.machine == key) {
      snap->reader.add(d.sd_path, d.path.value_or(uri), d.text);
      by_sd[to_lower(d.sd_path)] = &d;
    }
  SourceManager& sm = snap->sm;
  snap->result = lint_machine(sm, snap->reader, builtin_rules(), eff.lint);
  // A graph cut at its node limit leaves the machine rules silent on the rest: said once (as check says on stderr),
  // and again only after a lint that was whole.
  if (snap->result.graph.truncated && !m.truncated) {
    const std::string why = "rrflint: " + cli::truncated_warning(snap->job.title, eff.lint.max_graph_nodes);
    log_(2, why);
    send_(notification("window/showMessage", {{"type", 2}, {"message", why}}));
  }
  m.truncated = snap->result.graph.truncated;
  auto uri_of = [&](FileId id) -> std::optional<std::string> {
    auto [it, fresh] = snap->uris.try_emplace(id);
    if (!fresh) return it->second;
    const SourceFile& f = sm.get(id);
    if (lone) it->second = lone->uri;  // a lone machine has one file
    else if (auto d = by_sd.find(to_lower(f.sd_path())); d != by_sd.end()) it->second = d->second->uri;
    else if (auto abs = snap->disk.disk_path(f.sd_path()); abs && !settings.excluded(*abs))
      it->second = uri_of_path(*abs);
    return it->second;
  };
  std::map<std::string, json> found;
  for (const Diagnostic& d : snap->result.diagnostics) {
    if (d.loc.file == kNoFile) continue;
    if (auto uri = uri_of(d.loc.file)) found[*uri].push_back(diagnostic_json(sm, d, eff.docs_base, uri_of));
    if (d.fix)
      for (const Edit& e : d.fix->edits)
        if (e.loc.file != kNoFile) uri_of(e.loc.file);
  }
  m.docs_base = eff.docs_base;
  m.last = std::move(snap);
  publish_all(key, m, found);
}

// Publishes the findings of a machine: for each file with findings, for each that had some, and for each open
// buffer of the machine (an empty list says "checked, nothing found").
void Workspace::publish_all(const std::string& key, MachineEntry& m, std::map<std::string, json>& found) {
  std::set<std::string> targets = std::move(m.published);
  m.published.clear();
  for (const auto& [uri, d] : docs_)
    if (d.machine == key) targets.insert(uri);
  for (const auto& [uri, list] : found) targets.insert(uri);
  for (const std::string& uri : targets) {
    auto it = found.find(uri);
    if (it == found.end()) {
      publish(uri, json::array());
      continue;
    }
    m.published.insert(uri);
    publish(uri, std::move(it->second));
  }
}

void Workspace::publish(const std::string& uri, json diagnostics) {
  json params{{"uri", uri}, {"diagnostics", std::move(diagnostics)}};
  if (auto it = docs_.find(uri); it != docs_.end()) params["version"] = it->second.version;
  send_(notification("textDocument/publishDiagnostics", std::move(params)));
}

void Workspace::clear(const std::string& key) {
  waiting_.erase(key);
  auto it = machines_.find(key);
  if (it == machines_.end()) return;
  for (const std::string& uri : it->second.published) publish(uri, json::array());
  machines_.erase(it);
}

}  // namespace rrflint::server
