// Config files + command line -> the settings of each machine, and `rrflint config` which shows them with
// where each one came from.
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli/cli.h"
#include "frontend/platform.h"
#include "lint/engine/rule.h"
#include "rules/registry.h"

namespace rrflint::cli {
namespace {

std::string quoted_list(const std::vector<std::string>& v) {
  std::string out = "[";
  for (size_t i = 0; i < v.size(); ++i) out += fmt::format("{}\"{}\"", i ? ", " : "", v[i]);
  return out + "]";
}

std::vector<std::string> split_commas(const std::vector<std::string>& in) {
  std::vector<std::string> out;
  for (const auto& s : in) {
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
      if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace

bool check_options(CliOptions& c, std::string& err, std::string& warn) {
  if (!c.firmware.empty()) {
    auto v = parse_target_version(c.firmware, &warn, &err);
    if (!warn.empty()) warn = "--firmware: " + warn;
    if (!v) {
      err = "--firmware: " + err;
      return false;
    }
    c.firmware = v->str();  // what the rest of the run reads back with Version::parse
  }
  if (!c.board.empty() && !parse_board(c.board)) {
    err = fmt::format("--board: unknown board '{}' (duet2, duet3-6hc, duet3-mini, maestro)", c.board);
    return false;
  }
  for (auto* list : {&c.select, &c.extend_select, &c.ignore}) {
    *list = split_commas(*list);
    for (const std::string& n : *list)
      if (!rule_selector_known(n)) {
        err = fmt::format("unknown rule '{}'{}", n, unknown_rule_hint(n));
        return false;
      }
  }
  return true;
}

std::string conflicting_options(const CheckOptions& co) {
  if (co.add_suppressions && (co.fix || co.diff)) return "--add-suppressions cannot be combined with --fix or --diff";
  if (co.statistics && (co.diff || co.add_suppressions))
    return "--statistics counts the findings of a report: it cannot be combined with --diff or --add-suppressions";
  if (co.statistics && co.format_given && co.format != "text" && co.format != "concise" && co.format != "json")
    return fmt::format("--statistics prints text or json, not --format {}", co.format);
  return "";
}

void error(const std::string& msg) { std::cerr << "rrflint: error: " << msg << "\n"; }
void warning(const std::string& msg) { std::cerr << "rrflint: warning: " << msg << "\n"; }

bool flushed(std::ostream& os, std::string_view name, std::string_view what) {
  if (os.flush()) return true;
  error(fmt::format("{}: cannot write {}", name, what));
  return false;
}

std::shared_ptr<const Config> Settings::config_for(const std::string& dir) {
  if (cli_.isolated) return nullptr;
  // Memoised per folder as spelled (callers pass absolute, normal folders): files share their folders.
  auto [memo, fresh] = by_folder_.try_emplace(dir);
  if (!fresh) return memo->second;
  std::error_code ec;
  const std::optional<fs::path> file =
      cli_.config_path.empty() ? find_config(dir) : std::optional(fs::absolute(cli_.config_path, ec));
  if (!file) return nullptr;
  auto [it, unread] = loaded_.try_emplace(file->lexically_normal().string());
  if (unread) {
    ConfigError err;
    if (auto cfg = load_config(*file, &err)) {
      for (const std::string& w : cfg->warnings) warning(w);
      it->second = std::make_shared<const Config>(std::move(*cfg));
    } else if (!error_) error_ = err;
  }
  return memo->second = it->second;
}

std::vector<RuleDecision> decide_rules(const Config* cfg, const CliOptions& cli) {
  std::vector<RuleDecision> out;
  for (const Rule* r : builtin_rules().all()) out.push_back({r, r->meta.default_enabled, Origin{}, "default"});
  auto apply = [&](const SelectionLayer& layer) {
    if (layer.select.value) {
      const auto codes = selector_codes(*layer.select.value);
      for (RuleDecision& d : out) {
        d.on = std::find(codes.begin(), codes.end(), d.rule->meta.code) != codes.end();
        d.origin = layer.select.origin;
        d.why = d.on ? "select" : "not in select";
      }
    }
    if (layer.extend_select.value)
      for (const std::string& c : selector_codes(*layer.extend_select.value))
        for (RuleDecision& d : out)
          if (d.rule->meta.code == c) d = {d.rule, true, layer.extend_select.origin, "extend-select"};
    if (layer.ignore.value)
      for (const std::string& c : selector_codes(*layer.ignore.value))
        for (RuleDecision& d : out)
          if (d.rule->meta.code == c) d = {d.rule, false, layer.ignore.origin, "ignore"};
  };
  // Beneath the config files, as a file they extend would be; a key the config files set replaces the base's.
  SelectionLayer base = cli.base_selection;
  if (cfg && std::any_of(cfg->selection.begin(), cfg->selection.end(), [](auto& l) { return l.ignore.value; }))
    base.ignore = {};
  apply(base);
  if (cfg)
    for (const SelectionLayer& l : cfg->selection) apply(l);
  SelectionLayer cl;
  if (cli.select_given) cl.select = {cli.select, Origin::command_line()};
  if (cli.extend_select_given) cl.extend_select = {cli.extend_select, Origin::command_line()};
  if (cli.ignore_given) cl.ignore = {cli.ignore, Origin::command_line()};
  apply(cl);
  return out;
}

bool Settings::effective(const fs::path& dir, Effective& out) {
  std::shared_ptr<const Config> config = config_for(dir.string());
  if (error_) return false;
  // The settings depend only on the config file: worked out once for each.
  auto [memo, fresh] = effective_.try_emplace(config.get());
  if (fresh) resolve(std::move(config), memo->second);
  out = memo->second;
  return true;
}

void Settings::resolve(std::shared_ptr<const Config> config, Effective& out) {
  out.config = std::move(config);
  const Config* cfg = out.config.get();
  std::vector<std::string> on;
  bool as_default = true;  // exactly the rules on by default
  for (const RuleDecision& d : decide_rules(cfg, cli_)) {
    if (d.on) on.emplace_back(d.rule->meta.code);
    as_default = as_default && d.on == d.rule->meta.default_enabled;
  }
  if (on.empty()) {
    out.lint.select = {"ALL"};
    out.lint.ignore = {"ALL"};
  } else if (!as_default) {
    out.lint.select = on;  // the default set is left implicit (an empty select): no names for the core to look up
  }
  if (!cli_.firmware.empty()) out.lint.firmware = Version::parse(cli_.firmware);
  else if (cfg && cfg->firmware.value) out.lint.firmware = cfg->firmware.value;
  else if (!cli_.base_firmware.empty()) out.lint.firmware = Version::parse(cli_.base_firmware);
  if (!cli_.board.empty()) out.lint.board = parse_board(cli_.board);
  else if (cfg && cfg->board.value) out.lint.board = cfg->board.value;
  if (!cli_.fail_on.empty()) out.fail_on = *parse_severity(cli_.fail_on);
  else if (cfg && cfg->fail_on.value) out.fail_on = *cfg->fail_on.value;
  out.lint.tool_changer = cli_.tool_changer || (cfg && cfg->tool_changer.value && *cfg->tool_changer.value);
  if (cfg)
    for (const auto& [code, s] : cfg->severity) out.lint.severity[code] = *s.value;
  out.lint.inline_suppressions = !cli_.no_inline_suppressions;
  // Tests only: a lower node limit, to reach it without millions of nodes (docs/internals.md).
  if (const char* n = std::getenv("RRFLINT_MAX_NODES"); n && *n) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(n, &end, 10);
    if (*end == 0 && v > 0) out.lint.max_graph_nodes = static_cast<size_t>(v);
  }
  out.docs_base = cfg && cfg->docs_url.value ? *cfg->docs_url.value : default_docs_base();
  if (cfg && !cfg->per_file_ignores.empty()) {
    std::error_code ec;
    const fs::path cwd = fs::current_path(ec);
    std::shared_ptr<const Config> keep = out.config;
    out.lint.ignored_in_file = [keep, cwd](const SourceFile& f, std::string_view code) {
      const fs::path display(f.display_path());
      const fs::path abs = display.is_absolute() ? display : cwd / display;
      std::string sd = f.sd_path();
      if (sd.starts_with("/")) sd.erase(0, 1);
      for (const PathPattern& p : keep->per_file_ignores) {
        if (std::find(p.codes.begin(), p.codes.end(), code) == p.codes.end()) continue;
        auto rel = relative_below(abs, p.base);
        if ((rel && pattern_applies(p.glob, *rel)) || (!sd.empty() && pattern_applies(p.glob, sd))) return true;
      }
      return false;
    };
  }
}

bool Settings::excluded(const std::string& abs, std::string* why) {
  if (cli_.isolated) return false;  // no config file: nothing is excluded
  auto cfg = config_for(parent_of(abs));
  if (!cfg) return false;
  for (const PathPattern& p : cfg->exclude) {
    auto rel = relative_below(abs, p.base);
    if (rel && pattern_applies(p.glob, *rel)) {
      if (why) *why = fmt::format("'{}' ({})", p.glob, p.origin.str());
      return true;
    }
  }
  return false;
}

namespace {

void row(std::ostream& os, std::string_view key, const std::string& value, const std::string& origin) {
  os << fmt::format("{:<20} = {:<28} # {}\n", key, value, origin);
}

// Which file the settings come from, and what it extends.
void print_config_files(std::ostream& os, const CliOptions& cli, const std::string& path_arg, const Config* cfg,
                        const fs::path& dir) {
  os << fmt::format("# settings for {}\n", path_arg.empty() ? "." : path_arg);
  if (cli.isolated) os << "# config file: none (--isolated)\n";
  else if (!cfg) os << "# config file: none found (searched from " << dir.generic_string() << " upward)\n";
  else {
    os << "# config file: " << Origin{Origin::Kind::File, cfg->files.back(), 0}.str() << "\n";
    for (size_t i = cfg->files.size() - 1; i-- > 0;)
      os << "#   extends: " << Origin{Origin::Kind::File, cfg->files[i], 0}.str() << "\n";
  }
}

// Every setting with its value and where it came from.
void print_settings(std::ostream& os, const CliOptions& cli, const Effective& eff, const Config* cfg) {
  auto origin_of = [&](bool cli_given, auto& setting) {
    if (cli_given) return std::string("command line");
    if (cfg && setting.value) return setting.origin.str();
    return std::string("default");
  };
  Setting<Version> no_v;
  Setting<Board> no_b;
  Setting<Severity> no_s;
  Setting<bool> no_t;
  row(os, "firmware", eff.lint.firmware ? fmt::format("\"{}\"", eff.lint.firmware->str()) : "(inferred from the files)",
      origin_of(!cli.firmware.empty(), cfg ? cfg->firmware : no_v));
  row(os, "board", eff.lint.board ? fmt::format("\"{}\"", board_name(*eff.lint.board)) : "(inferred from the files)",
      origin_of(!cli.board.empty(), cfg ? cfg->board : no_b));
  row(os, "fail-on", fmt::format("\"{}\"", severity_name(eff.fail_on)),
      origin_of(!cli.fail_on.empty(), cfg ? cfg->fail_on : no_s));
  row(os, "machine.tool-changer", eff.lint.tool_changer ? "true" : "false",
      origin_of(cli.tool_changer, cfg ? cfg->tool_changer : no_t));
  row(os, "inline suppressions", eff.lint.inline_suppressions ? "on" : "off",
      cli.no_inline_suppressions ? "command line" : "default");
  Setting<std::string> no_d;
  row(os, "docs-url", fmt::format("\"{}\"", eff.docs_base), origin_of(false, cfg ? cfg->docs_url : no_d));
  if (cfg) {
    for (const SelectionLayer& l : cfg->selection) {
      if (l.select.value) row(os, "select", quoted_list(*l.select.value), l.select.origin.str());
      if (l.extend_select.value)
        row(os, "extend-select", quoted_list(*l.extend_select.value), l.extend_select.origin.str());
      if (l.ignore.value) row(os, "ignore", quoted_list(*l.ignore.value), l.ignore.origin.str());
    }
    for (const PathPattern& p : cfg->exclude) row(os, "exclude", fmt::format("\"{}\"", p.glob), p.origin.str());
    for (const PathPattern& p : cfg->per_file_ignores)
      row(os, fmt::format("per-file-ignores"), fmt::format("\"{}\" = {}", p.glob, quoted_list(p.codes)),
          p.origin.str());
    for (const auto& [code, s] : cfg->severity)
      row(os, fmt::format("severity.{}", code), fmt::format("\"{}\"", severity_name(*s.value)), s.origin.str());
  }
  if (cli.select_given) row(os, "select", quoted_list(cli.select), "command line");
  if (cli.extend_select_given) row(os, "extend-select", quoted_list(cli.extend_select), "command line");
  if (cli.ignore_given) row(os, "ignore", quoted_list(cli.ignore), "command line");
}

// For a file: whether it is excluded, and the per-file ignores that apply to it.
void print_file_notes(std::ostream& os, const fs::path& path, Settings& settings, const Config* cfg) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    std::string why;
    if (settings.excluded(path.string(), &why)) os << "# this file is excluded by " << why << "\n";
    if (cfg)
      for (const PathPattern& p : cfg->per_file_ignores) {
        auto rel = relative_below(path, p.base);
        if (rel && pattern_applies(p.glob, *rel))
          os << fmt::format("# per-file-ignores \"{}\" ({}) applies to this file: {}\n", p.glob, p.origin.str(),
                            quoted_list(p.codes));
      }
  }
}

// Every rule: on or off, its severity, and why.
void print_rules(std::ostream& os, const CliOptions& cli, const Config* cfg) {
  const auto decisions = decide_rules(cfg, cli);
  size_t n_on = 0;
  for (const RuleDecision& d : decisions) n_on += d.on;
  os << fmt::format("\n# rules: {} of {} enabled\n", n_on, decisions.size());
  for (const RuleDecision& d : decisions) {
    std::string sev(severity_name(d.rule->meta.severity));
    std::string sev_origin;
    if (cfg)
      if (auto it = cfg->severity.find(std::string(d.rule->meta.code)); it != cfg->severity.end()) {
        sev = std::string(severity_name(*it->second.value));
        sev_origin = fmt::format(", severity from {}", it->second.origin.str());
      }
    os << fmt::format("{:<7} {:<38} {:<4} {:<8} # {}{}{}\n", d.rule->meta.code, d.rule->meta.name, d.on ? "on" : "off",
                      sev, d.why, d.origin.kind == Origin::Kind::Default ? "" : " at " + d.origin.str(), sev_origin);
  }
}

}  // namespace

bool job_settings(const Job& job, Settings& settings, unsigned threads, Effective& eff) {
  std::error_code ec;
  fs::path dir = job.card ? job.card->sys_dir : job.standalone.parent_path();
  if (dir.empty()) dir = fs::current_path(ec);
  if (!settings.effective(dir, eff)) return false;
  eff.lint.threads = threads;
  return true;
}

unsigned default_threads() { return std::max(1u, std::min(8u, std::thread::hardware_concurrency())); }

bool use_color(const std::string& mode, int fd) {
  if (mode == "always") return true;
  if (mode == "never") return false;
  if (const char* f = std::getenv("FORCE_COLOR"); f && *f && std::string(f) != "0") return true;
  if (const char* n = std::getenv("NO_COLOR"); n && *n) return false;
  if (const char* t = std::getenv("TERM"); t && std::string(t) == "dumb") return false;
  return isatty(fd);
}

int run_config(const CliOptions& cli, const std::string& path_arg) {
  std::error_code ec;
  const fs::path path = fs::absolute(path_arg.empty() ? "." : path_arg, ec).lexically_normal();
  if (!fs::exists(path, ec)) {
    error(fmt::format("{}: no such file or directory", path_arg));
    return kExitError;
  }
  fs::path dir = fs::is_directory(path, ec) ? path : path.parent_path();
  if (auto card = card_at(dir)) dir = card->sys_dir;  // a machine's settings are found from its sys folder
  Settings settings(cli);
  Effective eff;
  if (!settings.effective(dir, eff)) {
    error(settings.config_error()->str());
    return kExitError;
  }
  const Config* cfg = eff.config.get();
  std::ostream& os = std::cout;
  print_config_files(os, cli, path_arg, cfg, dir);
  print_settings(os, cli, eff, cfg);
  print_file_notes(os, path, settings, cfg);
  print_rules(os, cli, cfg);
  return kExitClean;
}

}  // namespace rrflint::cli
