// Command-line paths -> jobs, one per machine. A folder is walked for SD roots (a folder whose sys/ holds
// config.g, or a sys folder), lone .g files and extensionless macros under macros/; .gitignore and the config
// file's `exclude` are honoured while walking, and for explicitly named files only with --force-exclude.
#include <algorithm>
#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unordered_map>

#include "cli/cli.h"

namespace rrflint::cli {
namespace {

// Stands for "anything inside this folder": a pattern that matches the folder excludes its contents.
constexpr const char* kAnyChild = "\x01rrflint-any-child";

// A file rrflint lints when it meets it in a walk: `*.g`, or a file without extension below a macros/ folder.
bool candidate(std::string_view name, bool below_macros) {
  if (name.empty() || name.front() == '.') return false;
  const size_t dot = name.rfind('.');
  if (dot == std::string_view::npos) return below_macros;
  return to_lower(name.substr(dot)) == ".g";
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

// The git top-level folder of an absolute, normal folder (memoised per folder: files share their folders).
const std::optional<std::string>& repo_of(const std::string& dir) {
  static std::unordered_map<std::string, std::optional<std::string>> memo;
  if (auto it = memo.find(dir); it != memo.end()) return it->second;
  std::optional<std::string> result;
  struct stat st;
  if (::stat(join_path(dir, ".git").c_str(), &st) == 0) result = dir;
  else if (dir != "/") result = repo_of(parent_of(dir));
  return memo.emplace(dir, std::move(result)).first->second;
}

// What the plan learns of each folder, found once per folder (files share their folders): its listing, the
// path with symbolic links resolved, the card its files belong to.
class Folders {
 public:
  // The entries of a folder (absolute, normal), listed once.
  const std::vector<DirEntry>& entries(const std::string& dir) { return dirs_->get(dir).entries; }
  // The listings, for the readers of the cards.
  const std::shared_ptr<DirCache>& dirs() const { return dirs_; }

  // An absolute, normal path with its symbolic links resolved, as fs::weakly_canonical gives it.
  const std::string& real_path(const std::string& abs) {
    if (auto it = real_.find(abs); it != real_.end()) return it->second;
    std::string r = "/";
    struct stat st;
    if (abs != "/") {
      if (::lstat(abs.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
        std::error_code ec;
        r = absolute_normal(fs::weakly_canonical(abs, ec));
      } else {
        r = join_path(real_path(parent_of(abs)), name_of(abs));
      }
    }
    return real_.emplace(abs, std::move(r)).first->second;
  }

  struct Place {
    const CardLocation* card = nullptr;
    std::optional<std::string> sd;
  };
  // The card of a file (absolute, normal) and its SD path there; `link`: the file may be a symbolic link (else
  // its SD path is its folder's and its name).
  Place place(const std::string& file, bool link) {
    auto [it, fresh] = folders_.try_emplace(parent_of(file));
    Folder& f = it->second;
    if (fresh && (f.card = card_for(it->first))) f.sd = sd_of(*f.card, real_path(it->first));
    Place p;
    if (!f.card) return p;
    p.card = &*f.card;
    if (link) p.sd = sd_of(*f.card, real_path(file));
    else if (f.sd) p.sd = join_path(*f.sd, name_of(file));
    return p;
  }

  // The nearest folder at or above `dir` (absolute, normal) whose sys/ holds config.g: a real SD root.
  const std::optional<CardLocation>& sd_root_above(const std::string& dir) {
    if (auto it = roots_.find(dir); it != roots_.end()) return it->second;
    std::optional<CardLocation> result;
    if (dir != "/") {
      if (auto sys = child_dir(dir, "sys"); sys && has_config(entries(sys->native()))) result = CardLocation{dir, *sys};
      else result = sd_root_above(parent_of(dir));
    }
    return roots_.emplace(dir, std::move(result)).first->second;
  }

 private:
  // The folder called `name` (any case) inside `dir`, if there is one.
  std::optional<fs::path> child_dir(const std::string& dir, std::string_view name) {
    if (const DirEntry* e = find_entry(entries(dir), name, DirEntry::Kind::Dir)) return join_path(dir, e->name);
    return std::nullopt;
  }

  // The SD card of the files in `start`. A real SD root above it comes first, so folders inside sys/ that hold
  // their own config.g (modules, tool-changer sub-folders) stay part of their card. Else the parent of a sys/,
  // macros/ or filaments/ folder above it (a card without config.g), else `start` itself when it holds config.g
  // (a sys folder under another name).
  std::optional<CardLocation> card_for(const std::string& start) {
    if (const auto& c = sd_root_above(start)) return c;
    fs::path dir = start;
    for (int i = 0; i < 8 && dir.has_filename(); ++i, dir = dir.parent_path()) {
      const std::string n = to_lower(dir.filename().string());
      if (n == "sys") return CardLocation{dir.parent_path(), dir};
      if (n == "macros" || n == "filaments") {
        const fs::path root = dir.parent_path();
        return CardLocation{root, child_dir(root, "sys").value_or(root / "sys")};
      }
    }
    // Only the file's own folder: a config.g further up (a stray ~/config.g) says nothing about this file.
    if (has_config(entries(start))) return CardLocation{parent_of(start), start};
    return std::nullopt;
  }

  // The SD path of a file on disk (links resolved) in a card: below its sys folder, else below its root.
  std::optional<std::string> sd_of(const CardLocation& card, const std::string& real) {
    for (const auto& [base, prefix] : {std::pair{&card.sys_dir, "/sys/"}, std::pair{&card.root, "/"}}) {
      auto rel = path_below(real, real_path(base->native()));
      if (rel && !rel->starts_with("..")) return prefix + *rel;
    }
    return std::nullopt;
  }

  std::shared_ptr<DirCache> dirs_ = std::make_shared<DirCache>();
  std::unordered_map<std::string, std::string> real_;
  struct Folder {
    std::optional<CardLocation> card;  // the card of its files
    std::optional<std::string> sd;     // its SD path in that card
  };
  std::unordered_map<std::string, Folder> folders_;
  std::unordered_map<std::string, std::optional<CardLocation>> roots_;  // folder -> sd_root_above
};

}  // namespace

std::optional<fs::path> repo_root(const fs::path& start) {
  const auto& root = repo_of(absolute_normal(start));
  if (!root) return std::nullopt;
  return fs::path(*root);
}

void GitIgnore::prefetch(const std::vector<std::string>& files) {
  std::map<std::string, std::vector<const std::string*>> by_repo;
  for (const std::string& f : files) {
    if (cache_.count(f)) continue;
    if (const auto& root = repo_of(parent_of(f)); root && !no_git_.count(*root)) by_repo[*root].push_back(&f);
  }
  for (auto& [root, list] : by_repo) {
    char tmpl[] = "/tmp/rrflint-ignore-XXXXXX";
    int fd = mkstemp(tmpl);
    if (fd < 0) continue;
    std::string input;
    for (const std::string* f : list) {
      auto rel = path_below(*f, root);
      input += rel ? *rel : *f;
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
    if (code != 0 && code != 1) {  // no git, or not a work tree: the fallback matcher answers
      no_git_.insert(root);
      continue;
    }
    std::set<std::string> ignored;
    for (size_t b = 0; b < out.size();) {
      size_t e = out.find('\0', b);
      if (e == std::string::npos) e = out.size();
      ignored.insert((fs::path(root) / out.substr(b, e - b)).lexically_normal().string());
      b = e + 1;
    }
    for (const std::string* f : list) cache_[*f] = ignored.count(*f) > 0;
  }
}

bool GitIgnore::ignored(const std::string& abs) {
  if (auto it = cache_.find(abs); it != cache_.end()) return it->second;
  const std::string dir = parent_of(abs);
  if (const auto& root = repo_of(dir); root && !no_git_.count(*root)) {
    prefetch({abs});
    if (auto it = cache_.find(abs); it != cache_.end()) return it->second;
  }
  // Without git: the .gitignore files from the repository top (or the file-system root) down to the file. A
  // folder that is ignored hides everything below it.
  const Folder& f = folder(dir);
  if (!f.patterns) return false;  // the usual case: no .gitignore anywhere above the file
  return f.ignored || verdict(abs, false, f.chain);
}

// A folder's .gitignore. Supports comments, `!` negation, a trailing `/` (folders only), anchoring by `/`, `*`,
// `?`, `**`, `[…]`.
const std::vector<GitIgnore::Pattern>& GitIgnore::patterns(const std::string& dir) {
  if (auto it = patterns_.find(dir); it != patterns_.end()) return it->second;
  std::vector<Pattern> pats;
  const std::string text = read_file(join_path(dir, ".gitignore"), nullptr).value_or(std::string());
  for (size_t b = 0; b < text.size();) {
    size_t e = text.find('\n', b);
    if (e == std::string::npos) e = text.size();
    std::string line = text.substr(b, e - b);
    b = e + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    while (!line.empty() && line.back() == ' ') line.pop_back();
    if (line.empty() || line.front() == '#') continue;
    Pattern p;
    p.negated = line.front() == '!';
    if (p.negated) line.erase(0, 1);
    if (line.starts_with("\\")) line.erase(0, 1);
    p.dir_only = line.ends_with("/");
    while (line.ends_with("/")) line.pop_back();
    if (line.empty()) continue;
    p.anchored = line.find('/') != std::string::npos;
    if (line.starts_with("/")) line.erase(0, 1);
    p.glob = std::move(line);
    pats.push_back(std::move(p));
  }
  return patterns_.emplace(dir, std::move(pats)).first->second;
}

const GitIgnore::Folder& GitIgnore::folder(const std::string& dir) {
  if (auto it = folders_.find(dir); it != folders_.end()) return it->second;
  Folder f;
  const auto& repo = repo_of(dir);
  if (dir != "/" && !(repo && *repo == dir)) {  // below the top: the folders above apply too
    const Folder& above = folder(parent_of(dir));
    f = above;
    f.ignored = above.ignored || (above.patterns && verdict(dir, true, above.chain));
  }
  f.chain.push_back(dir);
  f.patterns = f.patterns || !patterns(dir).empty();
  return folders_.emplace(dir, std::move(f)).first->second;
}

// The verdict for one path (a folder or a file) from the .gitignore files of `chain`; the last match wins.
bool GitIgnore::verdict(const std::string& path, bool is_dir, const std::vector<std::string>& chain) {
  std::optional<bool> result;
  for (const std::string& d : chain) {
    auto rel = path_below(path, d);
    if (!rel || rel->empty()) continue;
    const std::string_view base = name_of(*rel);
    for (const Pattern& p : patterns(d)) {
      if (p.dir_only && !is_dir) continue;
      if (p.anchored ? glob_match(p.glob, *rel) : glob_match(p.glob, base)) result = !p.negated;
    }
  }
  return result.value_or(false);
}

JobReader::JobReader(const Job& job) : job_(job) {
  std::error_code ec;
  if (job.card) {
    disk_ = std::make_unique<DiskReader>(job.card->root, job.card->sys_dir, fs::current_path(ec), job.dirs);
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
      auto b = read_text(job_.standalone, &err);
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

std::optional<std::string> JobReader::disk_path(std::string_view sd_path) const {
  if (disk_) {
    if (job_.stdin_bytes && to_lower(sd_path) == to_lower(job_.stdin_sd_path)) return std::nullopt;
    return disk_->locate(sd_path);
  }
  if (job_.stdin_bytes || to_lower(sd_path) != to_lower(lone_sd_)) return std::nullopt;
  return job_.standalone.string();
}

void plan(const std::vector<std::string>& paths, const PlanOptions& po, Settings& settings, GitIgnore& gitignore,
          std::vector<Job>& jobs, bool& io_error, PlanStats* stats_out) {
  PlanStats own;
  PlanStats& stats = stats_out ? *stats_out : own;
  std::error_code ec;
  const std::string cwd = absolute_normal(fs::current_path(ec));
  std::map<std::string, size_t> by_root;               // canonical sys folder -> job
  std::unordered_map<std::string, size_t> by_sys;      // sys folder as the card gave it -> job
  Folders folders;
  auto show = [&](const std::string& abs) {
    auto rel = path_below(abs, cwd);
    return rel ? (rel->empty() ? std::string(".") : *rel) : abs;
  };
  auto job_for_card = [&](const CardLocation& card, const std::string& title) -> Job& {
    if (auto it = by_sys.find(card.sys_dir.native()); it != by_sys.end()) return jobs[it->second];
    CardLocation c{absolute_normal(card.root), absolute_normal(card.sys_dir)};
    const std::string key = folders.real_path(c.sys_dir.native());
    auto [it, fresh] = by_root.try_emplace(key, jobs.size());
    if (fresh) {
      Job j;
      j.card = c;
      j.title = title;
      j.dirs = folders.dirs();
      jobs.push_back(j);
    }
    by_sys.emplace(card.sys_dir.native(), it->second);
    return jobs[it->second];
  };
  auto lone = [&](const fs::path& file, const std::string& title, bool explicit_path) {
    Job j;
    j.standalone = file;
    j.title = title;
    j.explicit_path = explicit_path;
    jobs.push_back(j);
  };
  // Files and folders met in a walk (absolute, normal); `link`: the file is a symbolic link.
  std::vector<std::string> found;
  std::vector<bool> link;
  bool walk_excludes = true;  // apply `exclude` in this walk (off for a folder named on purpose, see below)
  auto walk = [&](auto& self, const std::string& dir, int depth, bool below_macros) -> void {
    for (const DirEntry& e : folders.entries(dir)) {
      std::string path = join_path(dir, e.name);
      if (e.kind == DirEntry::Kind::Dir) {
        if (depth > 12 || e.name.starts_with(".") || e.link) continue;
        if (walk_excludes && settings.excluded(join_path(path, kAnyChild))) {
          ++stats.excluded;
          continue;
        }
        self(self, path, depth + 1, below_macros || to_lower(e.name) == "macros");
      } else if (e.kind == DirEntry::Kind::File && candidate(e.name, below_macros)) {
        found.push_back(std::move(path));
        link.push_back(e.link);
      }
    }
  };

  for (const std::string& p : paths) {
    ++stats.named;
    if (p == "-") {
      std::string bytes((std::istreambuf_iterator<char>(std::cin)), {});
      fs::path name = po.stdin_filename.empty() ? fs::path("stdin.g") : fs::path(po.stdin_filename);
      // Standard input linted on its own, or (excluded) only echoed back by --fix.
      auto lone_stdin = [&](bool excluded) {
        Job j;
        j.standalone = name;
        j.stdin_bytes = bytes;
        j.title = name.string();
        j.excluded = excluded;
        j.explicit_path = !excluded;
        jobs.push_back(std::move(j));
      };
      if (!po.stdin_filename.empty()) {
        const std::string abs = absolute_normal(name);
        if (po.force_exclude && (settings.excluded(abs) || (po.respect_gitignore && gitignore.ignored(abs)))) {
          ++stats.force_excluded;
          lone_stdin(true);
          continue;
        }
        if (auto at = folders.place(abs, true); at.card && at.sd && machine_path(*at.sd)) {
          Job& j = job_for_card(*at.card, po.stdin_filename);
          j.only.insert(to_lower(*at.sd));
          j.stdin_bytes = bytes;
          j.stdin_sd_path = *at.sd;
          j.explicit_path = true;
          continue;
        }
      }
      lone_stdin(false);
      continue;
    }
    const fs::path path(p);
    if (!fs::exists(path, ec)) {
      error(fmt::format("{}: no such file or directory", p));
      io_error = true;
      continue;
    }
    const std::string abs = absolute_normal(path);
    if (fs::is_directory(path, ec)) {
      // A folder named on purpose is linted even when `exclude` or .gitignore leaves it out (as an explicit file
      // is), unless --force-exclude; what is excluded below it stays excluded.
      const bool folder_excluded = settings.excluded(join_path(abs, kAnyChild));
      const bool folder_ignored = po.respect_gitignore && gitignore.ignored(join_path(abs, kAnyChild));
      if (po.force_exclude && (folder_excluded || folder_ignored)) {
        ++stats.force_excluded;
        continue;
      }
      if (auto card = card_at(path)) {
        // A folder holding config.g inside a card's sys/ (a module folder) is walked as part of that card.
        const auto& outer = folders.sd_root_above(abs);
        const bool nested = outer && fs::equivalent(card->sys_dir, abs, ec) && !fs::equivalent(outer->sys_dir, abs, ec);
        if (!nested) {
          Job& j = job_for_card(*card, p);
          j.report_all = true;
          // Named on purpose although `exclude` or .gitignore leaves the folder out: its files are reported.
          if (folder_excluded || folder_ignored) j.named_despite_exclusion = true;
          continue;
        }
      }
      // Walk the folder: candidate files (`*.g`, and files without extension below a macros/ folder, which may
      // be the walked folder or one above it as the path names it), minus .gitignore and `exclude`.
      bool below_macros = false;
      for (const fs::path& part : path) below_macros = below_macros || to_lower(part.string()) == "macros";
      found.clear();
      link.clear();
      walk_excludes = !folder_excluded;
      const size_t folders_before = stats.excluded;
      walk(walk, abs, 0, below_macros);
      const size_t folders_left_out = stats.excluded - folders_before;
      walk_excludes = true;
      if (settings.config_error()) return;
      const bool use_gitignore = po.respect_gitignore && !folder_ignored;
      if (use_gitignore) gitignore.prefetch(found);
      size_t placed = 0, left_out = 0;
      for (size_t i = 0; i < found.size(); ++i) {
        const std::string& f = found[i];
        if ((!folder_excluded && settings.excluded(f)) || (use_gitignore && gitignore.ignored(f))) {
          ++left_out;
          continue;
        }
        ++placed;
        const Folders::Place at = folders.place(f, link[i]);
        if (!at.card || !at.sd || !machine_path(*at.sd)) {
          lone(f, show(f), false);
          continue;
        }
        Job& j = job_for_card(*at.card, show(at.card->root));
        if (path_below(at.card->root.native(), abs)) j.report_all = true;  // the walk covers the whole card
        else j.only.insert(to_lower(*at.sd));
      }
      stats.excluded += left_out;
      if (placed == 0)
        stats.empty.push_back(
            left_out + folders_left_out
                ? fmt::format("{}: nothing to lint: everything below it is excluded ({} file{} and {} folder{} left "
                              "out by `exclude` or .gitignore)",
                              p, left_out, left_out == 1 ? "" : "s", folders_left_out, folders_left_out == 1 ? "" : "s")
                : fmt::format("{}: no G-code here (no sys/config.g, no *.g file, no macro)", p));
      continue;
    }
    // An explicit file: linted even when excluded, unless --force-exclude.
    if (po.force_exclude && (settings.excluded(abs) || (po.respect_gitignore && gitignore.ignored(abs)))) {
      ++stats.force_excluded;
      continue;
    }
    std::string err;
    if (!probe_file(p, &err)) {
      error(fmt::format("{}: {}", p, err));
      io_error = true;
      continue;
    }
    if (auto at = folders.place(abs, true); at.card && at.sd && machine_path(*at.sd)) {
      Job& j = job_for_card(*at.card, p);
      j.only.insert(to_lower(*at.sd));
      j.named.emplace(to_lower(*at.sd), p);
      j.explicit_path = true;
      continue;
    }
    lone(path, p, true);
  }
}

}  // namespace rrflint::cli
