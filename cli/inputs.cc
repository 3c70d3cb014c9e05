// Command-line paths -> jobs, one per machine. A folder is walked for SD roots (a folder whose sys/ holds
// config.g, or a sys folder), lone .g files and extensionless macros under macros/; .gitignore and the config
// file's `exclude` are honoured while walking, and for explicitly named files only with --force-exclude.
#include <algorithm>
#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sys/wait.h>

#include "cli.h"

namespace rrflint::cli {
namespace {

// Stands for "anything inside this folder": a pattern that matches the folder excludes its contents.
constexpr const char* kAnyChild = "\x01rrflint-any-child";

bool has_g_extension(const fs::path& p) { return to_lower(p.extension().string()) == ".g"; }

// A file rrflint lints when it meets it in a walk: `*.g`, or a file without extension below a macros/ folder.
bool candidate(const fs::path& p) {
  const std::string name = p.filename().string();
  if (name.empty() || name.front() == '.') return false;
  if (has_g_extension(p)) return true;
  if (name.find('.') != std::string::npos) return false;
  for (fs::path d = p.parent_path(); d.has_filename(); d = d.parent_path())
    if (to_lower(d.filename().string()) == "macros") return true;
  return false;
}

// The folder called `name` (any case) inside `dir`, if there is one.
std::optional<fs::path> child_ci(const fs::path& dir, const std::string& name) {
  std::error_code ec;
  if (fs::is_directory(dir / name, ec)) return dir / name;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (to_lower(it->path().filename().string()) == name && it->is_directory(ec)) return it->path();
  return std::nullopt;
}

// The nearest folder at or above `dir` whose sys/ holds config.g: a real SD root.
std::optional<CardLocation> sd_root_above(fs::path dir) {
  // Memoised per folder: a repository walk asks this for every file, and files share their folders.
  static std::map<std::string, std::optional<CardLocation>> memo;
  std::error_code ec;
  dir = fs::absolute(dir, ec).lexically_normal();
  auto [hit, fresh] = memo.try_emplace(dir.string());
  if (!fresh) return hit->second;
  std::optional<CardLocation> result;
  for (fs::path d = dir; !result && d.has_filename(); d = d.parent_path())
    if (auto sys = child_ci(d, "sys"); sys && has_config(*sys)) result = CardLocation{d, *sys};
  hit->second = result;
  return result;
}

// The SD card a file belongs to. A real SD root above it comes first, so folders inside sys/ that hold their
// own config.g (modules, tool-changer sub-folders) stay part of their card. Else the parent of a sys/, macros/
// or filaments/ folder above it (a card without config.g), else the file's own folder when it holds config.g
// (a sys folder under another name).
std::optional<CardLocation> card_for(const fs::path& file) {
  std::error_code ec;
  const fs::path start = fs::absolute(file, ec).parent_path();
  if (auto c = sd_root_above(start)) return c;
  fs::path dir = start;
  for (int i = 0; i < 8 && dir.has_filename(); ++i, dir = dir.parent_path()) {
    const std::string n = to_lower(dir.filename().string());
    if (n == "sys") return CardLocation{dir.parent_path(), dir};
    if (n == "macros" || n == "filaments") {
      const fs::path root = dir.parent_path();
      return CardLocation{root, child_ci(root, "sys").value_or(root / "sys")};
    }
  }
  // Only the file's own folder: a config.g further up (a stray ~/config.g) says nothing about this file.
  if (has_config(start)) return CardLocation{start.parent_path(), start};
  return std::nullopt;
}

// Is `sd` a path the machine loads (under /sys, /macros or /filaments)?
bool machine_path(const std::string& sd) {
  const std::string l = to_lower(sd);
  return l.starts_with("/sys/") || l.starts_with("/macros/") || l.starts_with("/filaments/");
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

bool is_ancestor(const fs::path& a, const fs::path& b) {  // a is b or above it
  auto rel = relative_below(b, a);
  return rel.has_value();
}

}  // namespace

std::optional<fs::path> repo_root(const fs::path& start) {
  static std::map<std::string, std::optional<fs::path>> memo;  // per folder: files share their folders
  std::error_code ec;
  fs::path dir = fs::absolute(start, ec).lexically_normal();
  if (!dir.has_filename() && dir != dir.root_path()) dir = dir.parent_path();
  auto [hit, fresh] = memo.try_emplace(dir.string());
  if (!fresh) return hit->second;
  std::optional<fs::path> result;
  for (int guard = 0; guard < 256; ++guard) {
    if (fs::exists(dir / ".git", ec)) {
      result = dir;
      break;
    }
    if (dir == dir.root_path() || !dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
  hit->second = result;
  return result;
}

void GitIgnore::prefetch(const std::vector<fs::path>& files) {
  std::map<std::string, std::vector<fs::path>> by_repo;
  for (const fs::path& f : files) {
    if (cache_.count(f.string())) continue;
    if (auto root = repo_root(f.parent_path())) by_repo[root->string()].push_back(f);
  }
  for (auto& [root, list] : by_repo) {
    char tmpl[] = "/tmp/rrflint-ignore-XXXXXX";
    int fd = mkstemp(tmpl);
    if (fd < 0) continue;
    std::string input;
    for (const fs::path& f : list) {
      auto rel = relative_below(f, root);
      input += rel ? *rel : f.string();
      input += '\0';
    }
    bool ok = ::write(fd, input.data(), input.size()) == static_cast<ssize_t>(input.size());
    ::close(fd);
    if (!ok) {
      ::unlink(tmpl);
      continue;
    }
    const std::string cmd = fmt::format("git -C {} check-ignore -z --stdin < {} 2>/dev/null", shell_quote(root),
                                        shell_quote(tmpl));
    std::string out;
    int status = -1;
    if (FILE* p = ::popen(cmd.c_str(), "r")) {
      char buf[4096];
      size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
      status = ::pclose(p);
    }
    ::unlink(tmpl);
    const int code = status >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code != 0 && code != 1) continue;  // no git, or not a work tree: the fallback matcher answers later
    std::set<std::string> ignored;
    for (size_t b = 0; b < out.size();) {
      size_t e = out.find('\0', b);
      if (e == std::string::npos) e = out.size();
      ignored.insert((fs::path(root) / out.substr(b, e - b)).lexically_normal().string());
      b = e + 1;
    }
    for (const fs::path& f : list) cache_[f.string()] = ignored.count(f.lexically_normal().string()) > 0;
  }
}

bool GitIgnore::ignored(const fs::path& abs) {
  if (auto it = cache_.find(abs.string()); it != cache_.end()) return it->second;
  prefetch({abs});
  if (auto it = cache_.find(abs.string()); it != cache_.end()) return it->second;
  bool r = fallback_ignored(abs);
  cache_[abs.string()] = r;
  return r;
}

// Without git: the .gitignore files from the repository root (or the file-system root) down to the file.
// Supports comments, `!` negation, a trailing `/` (folders only), anchoring by `/`, `*`, `?`, `**`, `[…]`.
bool GitIgnore::fallback_ignored(const fs::path& abs) {
  std::error_code ec;
  std::vector<fs::path> dirs;  // from the top down
  for (fs::path d = abs.parent_path();; d = d.parent_path()) {
    dirs.insert(dirs.begin(), d);
    if (fs::exists(d / ".git", ec) || d == d.root_path() || !d.has_parent_path() || d.parent_path() == d) break;
  }
  auto load = [&](const fs::path& d) -> const std::vector<std::pair<std::string, bool>>& {
    auto it = patterns_.find(d.string());
    if (it != patterns_.end()) return it->second;
    std::vector<std::pair<std::string, bool>> pats;
    std::ifstream in(d / ".gitignore");
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      while (!line.empty() && line.back() == ' ') line.pop_back();
      if (line.empty() || line.front() == '#') continue;
      bool neg = line.front() == '!';
      if (neg) line.erase(0, 1);
      if (line.starts_with("\\")) line.erase(0, 1);
      if (!line.empty()) pats.emplace_back(line, neg);
    }
    return patterns_.emplace(d.string(), std::move(pats)).first->second;
  };
  // The verdict for one path (a folder or the file), from every .gitignore above it; the last match wins.
  auto verdict = [&](const fs::path& p, bool is_dir) {
    std::optional<bool> result;
    for (const fs::path& d : dirs) {
      auto rel = relative_below(p, d);
      if (!rel || rel->empty()) continue;
      for (const auto& [pat, neg] : load(d)) {
        std::string g = pat;
        bool dir_only = g.ends_with("/");
        while (g.ends_with("/")) g.pop_back();
        if (g.empty() || (dir_only && !is_dir)) continue;
        bool anchored = g.find('/') != std::string::npos;
        if (g.starts_with("/")) g.erase(0, 1);
        const std::string base = fs::path(*rel).filename().string();
        if (anchored ? glob_match(g, *rel) : glob_match(g, base)) result = !neg;
      }
    }
    return result.value_or(false);
  };
  // The usual case: no .gitignore anywhere above the file.
  if (std::all_of(dirs.begin(), dirs.end(), [&](const fs::path& d) { return load(d).empty(); })) return false;
  // A folder that is ignored hides everything below it (folder verdicts are cached: many files share them).
  for (size_t i = 1; i < dirs.size(); ++i) {
    auto [it, fresh] = dir_cache_.try_emplace(dirs[i].string(), false);
    if (fresh) it->second = verdict(dirs[i], true);
    if (it->second) return true;
  }
  return verdict(abs, false);
}

JobReader::JobReader(const Job& job) : job_(job) {
  std::error_code ec;
  if (job.card) {
    disk_ = std::make_unique<DiskReader>(job.card->root, job.card->sys_dir, fs::current_path(ec));
    if (job.stdin_bytes) disk_->overlay(job.stdin_sd_path, *job.stdin_bytes);
    return;
  }
  std::string name = job.standalone.filename().string();
  if (name.empty()) name = "stdin.g";
  lone_sd_ = to_lower(name) == "config.g" ? "/sys/config.g" : "/sys/" + name;
  lone_display_ = job.standalone.empty() ? name : job.standalone.string();
}

ReadResult JobReader::read(std::string_view sd_path) {
  ReadResult r;
  if (disk_) {
    r = disk_->read(sd_path);
  } else if (to_lower(sd_path) == to_lower(lone_sd_)) {
    r.display = lone_display_;
    r.sd_path = lone_sd_;
    if (job_.stdin_bytes) {
      r.bytes = *job_.stdin_bytes;
    } else {
      // Read afresh (a lint reads each file once): keeping a copy here would double the memory for the file.
      std::string err;
      auto b = read_file(job_.standalone, &err);
      if (!b) {
        r.status = ReadResult::Status::Error;
        r.error = err;
        return r;
      }
      r.bytes = std::move(*b);
    }
    r.status = ReadResult::Status::Ok;
  } else {
    return r;  // a lone file has no neighbours
  }
  if (r.status == ReadResult::Status::Ok) {
    const std::string key = to_lower(r.sd_path.empty() ? std::string(sd_path) : r.sd_path);
    if (auto it = overlay_.find(key); it != overlay_.end()) r.bytes = it->second;
  }
  return r;
}

std::vector<std::string> JobReader::list(std::string_view sd_dir) {
  if (disk_) return disk_->list(sd_dir);
  std::string prefix = to_lower(sd_dir);
  if (!prefix.ends_with("/")) prefix += '/';
  if (to_lower(lone_sd_).starts_with(prefix)) return {lone_sd_};
  return {};
}

std::optional<fs::path> JobReader::disk_path(std::string_view sd_path) const {
  if (disk_) {
    if (job_.stdin_bytes && to_lower(sd_path) == to_lower(job_.stdin_sd_path)) return std::nullopt;
    return disk_->locate(sd_path);
  }
  if (job_.stdin_bytes || to_lower(sd_path) != to_lower(lone_sd_)) return std::nullopt;
  return job_.standalone;
}

void plan(const std::vector<std::string>& paths, const PlanOptions& po, Settings& settings, std::vector<Job>& jobs,
          bool& io_error) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  std::map<std::string, size_t> by_root;
  GitIgnore gitignore;
  auto show = [&](const fs::path& p) {
    auto rel = relative_below(p, cwd);
    return rel ? (rel->empty() ? std::string(".") : *rel) : p.string();
  };
  auto job_for_card = [&](CardLocation c, const std::string& title) -> Job& {
    c.root = fs::absolute(c.root, ec).lexically_normal();
    c.sys_dir = fs::absolute(c.sys_dir, ec).lexically_normal();
    if (!c.root.has_filename() && c.root != c.root.root_path()) c.root = c.root.parent_path();
    if (!c.sys_dir.has_filename() && c.sys_dir != c.sys_dir.root_path()) c.sys_dir = c.sys_dir.parent_path();
    std::string key = fs::weakly_canonical(c.sys_dir, ec).string();
    if (auto it = by_root.find(key); it != by_root.end()) return jobs[it->second];
    Job j;
    j.card = c;
    j.title = title;
    jobs.push_back(j);
    by_root[key] = jobs.size() - 1;
    return jobs.back();
  };
  auto sd_of = [&](const CardLocation& c, const fs::path& file) -> std::optional<std::string> {
    DiskReader probe(c.root, c.sys_dir, cwd);
    return probe.sd_path_of(fs::absolute(file, ec));
  };
  auto lone = [&](const fs::path& file, const std::string& title, bool explicit_path) {
    Job j;
    j.standalone = file;
    j.title = title;
    j.explicit_path = explicit_path;
    jobs.push_back(j);
  };

  for (const std::string& p : paths) {
    if (p == "-") {
      std::string bytes((std::istreambuf_iterator<char>(std::cin)), {});
      fs::path name = po.stdin_filename.empty() ? fs::path("stdin.g") : fs::path(po.stdin_filename);
      if (!po.stdin_filename.empty()) {
        const fs::path abs = fs::absolute(name, ec).lexically_normal();
        if (po.force_exclude && (settings.excluded(abs) || (po.respect_gitignore && gitignore.ignored(abs)))) {
          Job j;
          j.standalone = name;
          j.stdin_bytes = bytes;
          j.title = name.string();
          j.excluded = true;
          jobs.push_back(j);
          continue;
        }
        if (auto card = card_for(abs)) {
          if (auto sd = sd_of(*card, abs); sd && machine_path(*sd)) {
            Job& j = job_for_card(*card, po.stdin_filename);
            j.only.insert(to_lower(*sd));
            j.stdin_bytes = bytes;
            j.stdin_sd_path = *sd;
            j.explicit_path = true;
            continue;
          }
        }
      }
      Job j;
      j.standalone = name;
      j.stdin_bytes = bytes;
      j.title = name.string();
      j.explicit_path = true;
      jobs.push_back(j);
      continue;
    }
    const fs::path path(p);
    if (!fs::exists(path, ec)) {
      error(fmt::format("{}: no such file or directory", p));
      io_error = true;
      continue;
    }
    const fs::path abs = fs::absolute(path, ec).lexically_normal();
    if (fs::is_directory(path, ec)) {
      if (po.force_exclude && settings.excluded(abs / kAnyChild)) continue;
      if (auto card = card_at(path)) {
        // A folder holding config.g inside a card's sys/ (a module folder) is walked as part of that card.
        auto outer = sd_root_above(abs);
        const bool nested = outer && fs::equivalent(card->sys_dir, abs, ec) && !fs::equivalent(outer->sys_dir, abs, ec);
        if (!nested) {
          job_for_card(*card, p).report_all = true;
          continue;
        }
      }
      // Walk the folder: candidate files, minus .gitignore and `exclude`.
      std::vector<fs::path> found;
      for (fs::recursive_directory_iterator it(path, fs::directory_options::skip_permission_denied, ec), end;
           !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (it->is_directory(ec)) {
          if (it.depth() > 12 || name.starts_with(".") || settings.excluded(fs::absolute(it->path(), ec) / kAnyChild))
            it.disable_recursion_pending();
          continue;
        }
        if (!it->is_regular_file(ec) || !candidate(it->path())) continue;
        found.push_back(fs::absolute(it->path(), ec).lexically_normal());
      }
      if (settings.config_error()) return;
      if (po.respect_gitignore) gitignore.prefetch(found);
      for (const fs::path& f : found) {
        if (settings.excluded(f) || (po.respect_gitignore && gitignore.ignored(f))) continue;
        auto card = card_for(f);
        std::optional<std::string> sd = card ? sd_of(*card, f) : std::nullopt;
        if (!card || !sd || !machine_path(*sd)) {
          lone(f, show(f), false);
          continue;
        }
        Job& j = job_for_card(*card, show(card->root));
        if (is_ancestor(abs, card->root)) j.report_all = true;  // the walk covers the whole card
        else j.only.insert(to_lower(*sd));
      }
      continue;
    }
    // An explicit file: linted even when excluded, unless --force-exclude.
    if (po.force_exclude && (settings.excluded(abs) || (po.respect_gitignore && gitignore.ignored(abs)))) continue;
    std::string err;
    if (!read_file(path, &err)) {
      error(fmt::format("{}: {}", p, err));
      io_error = true;
      continue;
    }
    if (auto card = card_for(abs)) {
      if (auto sd = sd_of(*card, abs); sd && machine_path(*sd)) {
        Job& j = job_for_card(*card, p);
        j.only.insert(to_lower(*sd));
        j.explicit_path = true;
        continue;
      }
    }
    lone(path, p, true);
  }
}

}  // namespace rrflint::cli
