// `rrflint rule`: one rule's page, every rule as JSON, and the generated docs (docs/rules/*.md, the README's
// rule list).
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "lint/engine/rule.h"
#include "lint/render/render.h"
#include "lint/render/rule_docs.h"
#include "rules/registry.h"

namespace rrflint::cli {
namespace {

std::string_view fix_name(FixAvailability f) {
  return f == FixAvailability::None ? "none" : f == FixAvailability::Always ? "always" : "sometimes";
}

// Writes `text` to `path` when it differs; with `check`, only reports. Returns true when the file was stale.
bool sync(const fs::path& path, const std::string& text, bool check) {
  std::string err;
  auto now = read_file(path.string(), &err);
  if (now && *now == text) return false;
  if (check) {
    std::cerr << "rrflint: stale: " << path.generic_string() << "\n";
    return true;
  }
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) error(fmt::format("{}: cannot write", path.generic_string()));
  else std::cerr << "rrflint: wrote " << path.generic_string() << "\n";
  return true;
}

int generate(const RuleOptions& ro) {
  std::error_code ec;
  const fs::path dir(ro.generate_dir);
  if (!ro.check) fs::create_directories(dir, ec);
  const auto docs = generated_rule_docs(builtin_rules());
  bool stale = false;
  for (const auto& [name, text] : docs) stale = sync(dir / name, text, ro.check) || stale;
  // Pages of rules that no longer exist (only generated ones: they carry the banner).
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.ends_with(".md") || docs.count(name)) continue;
    std::string err;
    auto text = read_file(it->path().string(), &err);
    if (!text || text->find("Generated from the rule registry") == std::string::npos) continue;
    stale = true;
    if (ro.check) std::cerr << "rrflint: stale: " << it->path().generic_string() << " (no such rule)\n";
    else if (fs::remove(it->path(), ec)) std::cerr << "rrflint: removed " << it->path().generic_string() << "\n";
  }
  if (!ro.readme.empty()) {
    std::string err;
    auto text = read_file(ro.readme, &err);
    if (!text) {
      error(fmt::format("{}: {}", ro.readme, err));
      return kExitError;
    }
    auto updated = replace_rule_list(*text, readme_rule_list(builtin_rules()));
    if (!updated) {
      error(fmt::format("{}: no '{}' … '{}' markers", ro.readme, kRulesBegin, kRulesEnd));
      return kExitError;
    }
    stale = sync(ro.readme, *updated, ro.check) || stale;
  }
  if (ro.check) return stale ? kExitFindings : kExitClean;
  if (!stale) std::cerr << "rrflint: docs are up to date\n";
  return kExitClean;
}

}  // namespace

int run_rule(const RuleOptions& ro, const CliOptions& cli) {
  using nlohmann::json;
  if (!ro.generate_dir.empty()) return generate(ro);
  std::vector<const Rule*> list;
  if (ro.all) {
    list = builtin_rules().all();
  } else if (const Rule* r = builtin_rules().find(ro.name)) {
    list.push_back(r);
  } else {
    if (ro.name.empty()) error("name a rule (code or name), or pass --all");
    else error(fmt::format("unknown rule '{}'{}", ro.name, unknown_rule_hint(ro.name)));
    return kExitError;
  }
  if (ro.format == "json") {
    // The links follow `docs-url` of the config that governs the working directory, as `check` does there.
    std::error_code ec;
    Settings settings(cli);
    Effective eff;
    if (!settings.effective(fs::current_path(ec), eff)) {
      error(settings.config_error()->str());
      return kExitError;
    }
    json arr = json::array();
    for (const Rule* r : list) {
      const RuleMeta& m = r->meta;
      arr.push_back({{"code", m.code},
                     {"name", m.name},
                     {"severity", severity_name(m.severity)},
                     {"default_enabled", m.default_enabled},
                     {"fix", fix_name(m.fix)},
                     {"fix_availability", fix_name(m.fix)},
                     {"tag", tag_name(m.tag)},
                     {"summary", m.summary},
                     {"url", rule_url(eff.docs_base, m.name)},
                     {"docs", published_docs(m.docs)}});
    }
    std::cout << (ro.all ? arr : arr[0]).dump(2) << "\n";
    return kExitClean;
  }
  for (size_t i = 0; i < list.size(); ++i) {
    std::string page = rule_page(*list[i]);
    if (page.starts_with("<!--")) page.erase(0, page.find('\n') + 1);  // the "generated" banner
    std::cout << (i ? "\n" : "") << page;
  }
  return kExitClean;
}

}  // namespace rrflint::cli
