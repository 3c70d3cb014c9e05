#include "frontend/config.h"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <cctype>
#include <set>

#include "lint/engine/rule.h"
#include "lint/engine/suppress.h"
#include "rules/registry.h"

namespace fs = std::filesystem;

namespace rrflint {
namespace {

std::string show_path(const fs::path& p) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (!ec)
    if (auto rel = relative_below(p, cwd)) return rel->empty() ? std::string(".") : *rel;
  return p.generic_string();
}

struct Loader {
  Config& cfg;
  ConfigError& err;
  std::set<std::string> visiting;

  bool fail(const fs::path& file, const toml::source_region& at, std::string message) {
    err.file = file;
    err.line = at.begin.line;
    err.column = at.begin.column;
    err.message = std::move(message);
    return false;
  }

  Origin origin(const fs::path& file, const toml::source_region& at) {
    return Origin{Origin::Kind::File, file, at.begin.line};
  }

  // A list of rule selectors: codes, names, code prefixes ("RRF3") or "ALL". Returns false on an unknown one.
  bool rule_list(const fs::path& file, const toml::node& node, std::string_view key, std::vector<std::string>& out) {
    const toml::array* arr = node.as_array();
    if (!arr) return fail(file, node.source(), fmt::format("'{}' must be an array of rule codes or names", key));
    for (const toml::node& item : *arr) {
      const auto* s = item.as_string();
      if (!s) return fail(file, item.source(), fmt::format("'{}' must be an array of rule codes or names", key));
      const std::string v = s->get();
      if (!rule_selector_known(v))
        return fail(file, item.source(), fmt::format("unknown rule '{}' in '{}'{}", v, key, unknown_rule_hint(v)));
      out.push_back(v);
    }
    return true;
  }

  bool string_value(const fs::path& file, const toml::node& node, std::string_view key, std::string& out) {
    const auto* s = node.as_string();
    if (!s) return fail(file, node.source(), fmt::format("'{}' must be a string", key));
    out = s->get();
    return true;
  }

  // Reads and parses one config file (and, first, the file it extends). `abs` is its canonical path.
  bool open(const fs::path& path, const toml::source_region* from, const fs::path& from_file, toml::table& tbl,
            fs::path& abs) {
    std::error_code ec;
    abs = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (!fs::is_regular_file(abs, ec)) {
      const std::string why = fs::is_directory(abs, ec) ? "is a folder, not a config file"
                              : fs::exists(abs, ec)     ? "is not a regular file"
                                                        : "no such file";
      if (from) return fail(from_file, *from, fmt::format("'extend': {}: {}", show_path(abs), why));
      err.file = abs;
      err.message = why;
      return false;
    }
    if (!visiting.insert(abs.string()).second) {
      if (from) return fail(from_file, *from, fmt::format("'extend': {} extends itself (a cycle)", show_path(abs)));
      return false;
    }
    try {
      tbl = toml::parse_file(abs.string());
    } catch (const toml::parse_error& e) {
      return fail(abs, e.source(), std::string(e.description()));
    }
    // `extend` first: the extended file's settings come before this file's.
    if (const toml::node* ext = tbl.get("extend")) {
      std::string target;
      if (!string_value(abs, *ext, "extend", target)) return false;
      fs::path next = fs::path(target).is_absolute() ? fs::path(target) : abs.parent_path() / target;
      if (!load(next, &ext->source(), abs)) return false;
    }
    return true;
  }

  // firmware, board, fail-on, docs-url. False on a bad value; `known` false for another key.
  bool scalar_key(const fs::path& abs, const std::string& key, const toml::source_region& at, const toml::node& v,
                  bool& known) {
    known = true;
    if (key == "firmware") {
      std::string s;
      if (!v.is_string())
        return fail(abs, v.source(),
                    "'firmware' must be a string such as \"3.5\" (a TOML number loses digits: 3.10 is 3.1)");
      string_value(abs, v, key, s);
      std::string warn, why;
      auto ver = parse_target_version(s, &warn, &why);
      if (!ver) return fail(abs, v.source(), "'firmware': " + why);
      if (!warn.empty()) cfg.warnings.push_back(fmt::format("{}: 'firmware': {}", abs.string(), warn));
      cfg.firmware = {*ver, origin(abs, at)};
    } else if (key == "board") {
      std::string s;
      if (!string_value(abs, v, key, s)) return false;
      auto b = parse_board(s);
      if (!b)
        return fail(abs, v.source(),
                    fmt::format("'board': unknown board '{}' (duet2, duet3-6hc, duet3-mini, maestro)", s));
      cfg.board = {*b, origin(abs, at)};
    } else if (key == "fail-on") {
      std::string s;
      if (!string_value(abs, v, key, s)) return false;
      auto sev = parse_severity(s);
      if (!sev) return fail(abs, v.source(), fmt::format("'fail-on': '{}' is not error, warning or info", s));
      cfg.fail_on = {*sev, origin(abs, at)};
    } else if (key == "docs-url") {
      std::string s, why;
      if (!string_value(abs, v, key, s)) return false;
      auto url = parse_docs_url(s, &why);
      if (!url) return fail(abs, v.source(), "'docs-url': " + why);
      cfg.docs_url = {*url, origin(abs, at)};
    } else {
      known = false;
    }
    return true;
  }

  // exclude, [severity], [machine], [per-file-ignores]. False on a bad value; `known` false for another key.
  bool table_key(const fs::path& abs, const fs::path& base, const std::string& key, const toml::node& v, bool& known) {
    known = true;
    if (key == "exclude") {
      const toml::array* arr = v.as_array();
      if (!arr) return fail(abs, v.source(), "'exclude' must be an array of path patterns");
      for (const toml::node& item : *arr) {
        const auto* s = item.as_string();
        if (!s || s->get().empty()) return fail(abs, item.source(), "'exclude' must be an array of path patterns");
        cfg.exclude.push_back(PathPattern{s->get(), base, {}, origin(abs, item.source())});
      }
    } else if (key == "severity") {
      const toml::table* t = v.as_table();
      if (!t) return fail(abs, v.source(), "'severity' must be a table: [severity] then RRF306 = \"error\"");
      for (auto&& [rk, rv] : *t) {
        const Rule* r = builtin_rules().find(rk.str());
        if (!r)
          return fail(abs, rk.source(),
                      fmt::format("[severity]: unknown rule '{}'{}", rk.str(), unknown_rule_hint(rk.str())));
        std::string s;
        if (!string_value(abs, rv, fmt::format("severity.{}", rk.str()), s)) return false;
        auto sev = parse_severity(s);
        if (!sev) return fail(abs, rv.source(), fmt::format("[severity]: '{}' is not error, warning or info", s));
        cfg.severity[std::string(r->meta.code)] = {*sev, origin(abs, rk.source())};
      }
    } else if (key == "machine") {
      const toml::table* t = v.as_table();
      if (!t) return fail(abs, v.source(), "'machine' must be a table: [machine] then tool-changer = true");
      for (auto&& [mk, mv] : *t) {
        if (mk.str() != "tool-changer")
          return fail(abs, mk.source(), fmt::format("[machine]: unknown key '{}' (known: tool-changer)", mk.str()));
        const auto* b = mv.as_boolean();
        if (!b) return fail(abs, mv.source(), "[machine] tool-changer must be true or false");
        cfg.tool_changer = {b->get(), origin(abs, mk.source())};
      }
    } else if (key == "per-file-ignores") {
      const toml::table* t = v.as_table();
      if (!t)
        return fail(abs, v.source(),
                    "'per-file-ignores' must be a table: [per-file-ignores] then \"macros/**\" = [\"RRF101\"]");
      for (auto&& [gk, gv] : *t) {
        std::vector<std::string> rules;
        if (!rule_list(abs, gv, fmt::format("per-file-ignores.\"{}\"", gk.str()), rules)) return false;
        cfg.per_file_ignores.push_back(
            PathPattern{std::string(gk.str()), base, selector_codes(rules), origin(abs, gk.source())});
      }
    } else {
      known = false;
    }
    return true;
  }

  bool load(const fs::path& path, const toml::source_region* from, const fs::path& from_file) {
    toml::table tbl;
    fs::path abs;
    if (!open(path, from, from_file, tbl, abs)) return false;
    cfg.files.push_back(abs);
    const fs::path base = abs.parent_path();
    SelectionLayer layer;
    bool has_layer = false;
    for (auto&& [k, v] : tbl) {
      const std::string key(k.str());
      const toml::source_region& at = k.source();
      if (key == "extend") continue;
      if (key == "select" || key == "extend-select" || key == "ignore") {
        Setting<std::vector<std::string>>& s = key == "select"   ? layer.select
                                               : key == "ignore" ? layer.ignore
                                                                 : layer.extend_select;
        s.value.emplace();
        if (!rule_list(abs, v, key, *s.value)) return false;
        s.origin = origin(abs, at);
        has_layer = true;
        continue;
      }
      bool known = false;
      if (!scalar_key(abs, key, at, v, known)) return false;
      if (!known && !table_key(abs, base, key, v, known)) return false;
      if (!known)
        return fail(abs, at,
                    fmt::format("unknown key '{}' (known: extend, select, extend-select, ignore, firmware, board, "
                                "fail-on, exclude, docs-url, [severity], [machine], [per-file-ignores])",
                                key));
    }
    if (has_layer) cfg.selection.push_back(std::move(layer));
    return true;
  }
};

bool match_class(std::string_view p, size_t& i, char c) {
  // p[i] == '['; on return i is past the closing ']'.
  size_t j = i + 1;
  bool negate = j < p.size() && (p[j] == '!' || p[j] == '^');
  if (negate) ++j;
  bool hit = false;
  bool first = true;
  while (j < p.size() && (p[j] != ']' || first)) {
    first = false;
    if (j + 2 < p.size() && p[j + 1] == '-' && p[j + 2] != ']') {
      if (c >= p[j] && c <= p[j + 2]) hit = true;
      j += 3;
    } else {
      if (c == p[j]) hit = true;
      ++j;
    }
  }
  i = j < p.size() ? j + 1 : j;
  return hit != negate;
}

bool match_segment(std::string_view p, std::string_view s) {
  // Classic wildcard match within one segment, with backtracking on '*'.
  size_t pi = 0, si = 0, star = std::string_view::npos, mark = 0;
  while (si < s.size()) {
    if (pi < p.size() && p[pi] == '*') {
      star = pi++;
      mark = si;
    } else if (pi < p.size() && p[pi] == '[') {
      size_t next = pi;
      if (match_class(p, next, s[si])) {
        pi = next;
        ++si;
      } else if (star != std::string_view::npos) {
        pi = star + 1;
        si = ++mark;
      } else {
        return false;
      }
    } else if (pi < p.size() && (p[pi] == '?' || p[pi] == s[si])) {
      ++pi;
      ++si;
    } else if (star != std::string_view::npos) {
      pi = star + 1;
      si = ++mark;
    } else {
      return false;
    }
  }
  while (pi < p.size() && p[pi] == '*') ++pi;
  return pi == p.size();
}

std::vector<std::string_view> split(std::string_view s) {
  std::vector<std::string_view> out;
  while (!s.empty()) {
    size_t slash = s.find('/');
    std::string_view seg = s.substr(0, slash);
    if (!seg.empty()) out.push_back(seg);
    if (slash == std::string_view::npos) break;
    s.remove_prefix(slash + 1);
  }
  return out;
}

bool match_parts(const std::vector<std::string_view>& p, size_t pi, const std::vector<std::string_view>& s, size_t si) {
  if (pi == p.size()) return si == s.size();
  if (p[pi] == "**") {
    for (size_t k = si; k <= s.size(); ++k)
      if (match_parts(p, pi + 1, s, k)) return true;
    return false;
  }
  if (si == s.size()) return false;
  return match_segment(p[pi], s[si]) && match_parts(p, pi + 1, s, si + 1);
}

}  // namespace

std::optional<std::string> parse_docs_url(std::string_view url, std::string* why) {
  auto no = [&](std::string msg) -> std::optional<std::string> {
    if (why) *why = std::move(msg);
    return std::nullopt;
  };
  std::string lower(url);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  size_t rest = 0;
  if (lower.starts_with("https://")) rest = 8;
  else if (lower.starts_with("http://")) rest = 7;
  else if (lower.starts_with("file://")) rest = 7;
  else
    return no(
        fmt::format("'{}' is not an http://, https:// or file:/// URL (the folder holding the rule pages, "
                    "e.g. \"https://example.org/rrflint/docs/rules/\")",
                    url));
  if (lower.starts_with("file://")) {
    if (url.size() <= rest || url[rest] != '/')
      return no(fmt::format("'{}': a file URL needs an absolute path, file:///path/to/docs/rules/", url));
  } else if (url.size() <= rest || url[rest] == '/') {
    return no(fmt::format("'{}' has no host", url));
  }
  for (unsigned char c : url)
    if (c <= 0x20 || c == 0x7F || c == '"' || c == '<' || c == '>' || c == '\\')
      return no(fmt::format("'{}' contains a blank or a character a URL cannot hold (percent-encode it)", url));
  if (url.find_first_of("?#") != std::string_view::npos)
    return no(fmt::format("'{}' has a query or fragment: rrflint appends <rule-name>.md to it", url));
  std::string out(url);
  if (!out.ends_with('/')) out += '/';
  return out;
}

bool rule_selector_known(std::string_view v) {
  if (to_lower(v) == "all" || builtin_rules().find(v)) return true;
  if (v.size() < 4 || !to_lower(v).starts_with("rrf")) return false;
  for (const Rule* r : builtin_rules().all())
    if (to_lower(r->meta.code).starts_with(to_lower(v))) return true;
  return false;
}

std::string unknown_rule_hint(std::string_view v) {
  const std::string hint = near_miss_hint(v, builtin_rules());
  return hint.empty() ? " (see `rrflint rule --all`)" : hint;
}

std::vector<std::string> selector_codes(const std::vector<std::string>& selectors) {
  std::vector<std::string> codes;
  for (const Rule* r : builtin_rules().all()) {
    bool hit = false;
    for (const std::string& s : selectors) {
      const Rule* exact = builtin_rules().find(s);
      hit = hit || to_lower(s) == "all" || exact == r ||
            (!exact && to_lower(s).starts_with("rrf") && to_lower(r->meta.code).starts_with(to_lower(s)));
    }
    if (hit) codes.emplace_back(r->meta.code);
  }
  return codes;
}

std::string Origin::str() const {
  switch (kind) {
    case Kind::Default: return "default";
    case Kind::CommandLine: return "command line";
    case Kind::File: return line ? fmt::format("{}:{}", show_path(file), line) : show_path(file);
  }
  return "?";
}

std::string ConfigError::str() const {
  if (line == 0) return fmt::format("{}: {}", show_path(file), message);
  return fmt::format("{}:{}:{}: {}", show_path(file), line, column, message);
}

std::optional<Config> load_config(const fs::path& file, ConfigError* err) {
  Config cfg;
  ConfigError local;
  Loader l{cfg, err ? *err : local, {}};
  if (!l.load(file, nullptr, {})) return std::nullopt;
  return cfg;
}

std::optional<fs::path> find_config(const fs::path& start) {
  std::error_code ec;
  fs::path dir = fs::absolute(start, ec).lexically_normal();
  if (!dir.has_filename() && dir.has_parent_path() && dir != dir.root_path()) dir = dir.parent_path();
  for (int guard = 0; guard < 256; ++guard) {
    fs::path candidate = dir / kConfigFileName;
    if (fs::is_regular_file(candidate, ec)) return candidate;
    if (fs::exists(dir / ".git", ec)) break;  // the repository root: look no further
    if (dir == dir.root_path() || !dir.has_parent_path()) break;
    fs::path parent = dir.parent_path();
    if (parent == dir) break;
    dir = parent;
  }
  return std::nullopt;
}

bool glob_match(std::string_view pattern, std::string_view path) {
  return match_parts(split(pattern), 0, split(path), 0);
}

bool pattern_applies(std::string_view glob, std::string_view rel) {
  std::string_view g = glob;
  bool anchored = false;
  if (g.starts_with("./")) g.remove_prefix(2), anchored = true;
  if (g.starts_with("/")) g.remove_prefix(1), anchored = true;
  while (g.ends_with("/")) g.remove_suffix(1);
  if (g.empty()) return false;
  anchored = anchored || g.find('/') != std::string_view::npos;
  const std::vector<std::string_view> parts = split(rel);
  if (!anchored) {
    for (std::string_view seg : parts)
      if (match_segment(g, seg)) return true;
    return false;
  }
  const std::vector<std::string_view> pp = split(g);
  // The path itself or any folder above it.
  for (size_t n = parts.size(); n >= 1; --n) {
    std::vector<std::string_view> prefix(parts.begin(), parts.begin() + static_cast<std::ptrdiff_t>(n));
    if (match_parts(pp, 0, prefix, 0)) return true;
  }
  return false;
}

std::optional<std::string> relative_below(const fs::path& abs, const fs::path& base) {
  std::error_code ec;
  fs::path a = fs::absolute(abs, ec).lexically_normal();
  fs::path b = fs::absolute(base, ec).lexically_normal();
  fs::path rel = a.lexically_relative(b);
  if (rel.empty()) return std::nullopt;
  std::string r = rel.generic_string();
  if (r == "..") return std::nullopt;
  if (r.starts_with("../")) return std::nullopt;
  if (r == ".") return std::string();
  return r;
}

}  // namespace rrflint
