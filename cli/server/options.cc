// The language server's settings from the editor (options.h).
#include "cli/server/options.h"

#include <fmt/format.h>

namespace rrflint::server {
namespace {

// A list of rule selectors: an array of strings, or one string (commas split it, as on the command line).
bool read_list(const json& v, const char* key, std::vector<std::string>& out, std::string& err) {
  out.clear();
  if (v.is_string()) {
    out.push_back(v.get<std::string>());
    return true;
  }
  if (v.is_array() && std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_string(); })) {
    for (const json& x : v) out.push_back(x.get<std::string>());
    return true;
  }
  err = fmt::format("'{}' must be a list of rule codes or names", key);
  return false;
}

}  // namespace

bool read_options(const json& settings, ServerOptions& out, std::string& err, std::string& warn) {
  const json* s = &settings;
  if (s->is_object())
    if (auto r = s->find("rrflint"); r != s->end()) s = &*r;
  if (s->is_null()) return true;
  if (!s->is_object()) {
    err = "the settings must be an object";
    return false;
  }
  auto get = [&](const char* key) -> const json* {
    auto it = s->find(key);
    return it == s->end() || it->is_null() ? nullptr : &*it;
  };
  ServerOptions next;
  cli::CliOptions& c = next.cli;
  if (const json* f = get("firmware")) {
    if (!f->is_string()) {
      err = "'firmware' must be a string such as \"3.5\"";
      return false;
    }
    c.firmware = f->get<std::string>();
  }
  if (const json* v = get("select"); v && !read_list(*v, "select", c.select, err)) return false;
  if (const json* v = get("ignore"); v && !read_list(*v, "ignore", c.ignore, err)) return false;
  if (const json* d = get("debounce")) {
    if (!d->is_number_integer() || d->get<int64_t>() < 0 || d->get<int64_t>() > kMaxDebounceMs) {
      err = fmt::format("'debounce' must be a whole number of milliseconds from 0 to {}", kMaxDebounceMs);
      return false;
    }
    next.debounce = std::chrono::milliseconds(d->get<int64_t>());
  }
  if (!cli::check_options(c, err, warn)) {
    if (err.starts_with("--")) err.erase(0, 2);  // "firmware: …", the key of the settings
    return false;
  }
  if (warn.starts_with("--")) warn.erase(0, 2);
  // Beneath the config files: moved out of the command line's fields.
  c.base_firmware = std::exchange(c.firmware, {});
  const Origin editor{};
  if (get("select")) c.base_selection.select = {std::exchange(c.select, {}), editor};
  if (get("ignore")) c.base_selection.ignore = {std::exchange(c.ignore, {}), editor};
  out = std::move(next);
  return true;
}

}  // namespace rrflint::server
