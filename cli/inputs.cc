// Command-line paths -> jobs, one per machine. A folder is walked for SD roots (a folder whose sys/ holds
// config.g, or a sys folder), lone .g files and extensionless macros under macros/; .gitignore and the config
// file's `exclude` are honoured while walking, and for explicitly named files only with --force-exclude.
#include <fmt/format.h>
#include <sys/stat.h>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <iostream>
#include <unordered_map>

#include "cli/cli.h"
#include "frontend/platform.h"

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

// What the plan learns of each folder, found once per folder (files share their folders): its listing, the
// path with symbolic links resolved, the card its files belong to.
class Folders {
 public:
  // The entries of a folder (absolute, normal), listed once.
  const std::vector<DirEntry>& entries(const std::string& dir) { return dirs_->get(dir).entries; }
  // Why a folder could not be listed; empty when it was.
  const std::string& list_error(const std::string& dir) { return dirs_->get(dir).error; }
  // The listings, for the readers of the cards.
  const std::shared_ptr<DirCache>& dirs() const { return dirs_; }

  // An absolute, normal path with its symbolic links resolved, as fs::weakly_canonical gives it.
  const std::string& real_path(const std::string& abs) {
    if (auto it = real_.find(abs); it != real_.end()) return it->second;
    std::string r = abs;  // a root is its own
    struct stat st;
    if (!is_root(abs)) {
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
  // The card of a file (absolute, normal) and its SD path there: its folder's and its name. A symbolic link is a
  // file of the card it lies in, wherever it points (the card as laid out; --fix never writes through it to a file
  // outside the card).
  Place place(const std::string& file) {
    auto [it, fresh] = folders_.try_emplace(parent_of(file));
    Folder& f = it->second;
    if (fresh && (f.card = card_for(it->first))) f.sd = sd_of(*f.card, real_path(it->first));
    Place p;
    if (!f.card) return p;
    p.card = &*f.card;
    if (f.sd) p.sd = join_path(*f.sd, name_of(file));
    return p;
  }

  // The nearest folder at or above `dir` (absolute, normal) whose sys/ holds config.g: a real SD root.
  const std::optional<CardLocation>& sd_root_above(const std::string& dir) {
    if (auto it = roots_.find(dir); it != roots_.end()) return it->second;
    std::optional<CardLocation> result;
    if (!is_root(dir)) {
      if (auto sys = child_dir(dir, "sys"); sys && has_config(entries(sys->string()))) result = CardLocation{dir, *sys};
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
        return CardLocation{root, child_dir(root.string(), "sys").value_or(root / "sys")};
      }
    }
    // Only the file's own folder: a config.g further up (a stray ~/config.g) says nothing about this file.
    if (has_config(entries(start))) return CardLocation{parent_of(start), start};
    return std::nullopt;
  }

  // The SD path of a file on disk (links resolved) in a card: below its sys folder, else below its root.
  std::optional<std::string> sd_of(const CardLocation& card, const std::string& real) {
    for (const auto& [base, prefix] : {std::pair{&card.sys_dir, "/sys/"}, std::pair{&card.root, "/"}}) {
      auto rel = path_below(real, real_path(base->string()));
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

std::optional<FilePlace> place_file(const std::string& abs) {
  Folders folders;
  const Folders::Place at = folders.place(abs);
  if (!at.card || !at.sd || !machine_path(*at.sd)) return std::nullopt;
  return FilePlace{CardLocation{absolute_normal(at.card->root), absolute_normal(at.card->sys_dir)}, *at.sd};
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
      auto b = read_text(job_.standalone.string(), &err);
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

namespace {

// The current folder, absolute and normal.
std::string current_folder() {
  std::error_code ec;
  return absolute_normal(fs::current_path(ec));
}

// The jobs of one plan, as the command-line paths add them.
struct Planner {
  const PlanOptions& po;
  Settings& settings;
  GitIgnore& gitignore;
  std::vector<Job>& jobs;
  bool& io_error;
  PlanStats& stats;
  const std::string cwd = current_folder();
  std::map<std::string, size_t> by_root;                 // canonical sys folder -> job
  std::unordered_map<std::string, size_t> by_sys;        // sys folder as the card gave it -> job
  std::unordered_map<std::string, size_t> lone_by_real;  // a lone file's real path -> job
  Folders folders;
  // Files met in a walk (absolute, normal).
  std::vector<std::string> found;
  bool walk_excludes = true;  // apply `exclude` in this walk (off for a folder named on purpose, see add_folder)

  std::string show(const std::string& abs) const {
    auto rel = path_below(abs, cwd);
    return rel ? (rel->empty() ? std::string(".") : *rel) : abs;
  }

  Job& job_for_card(const CardLocation& card, const std::string& title) {
    if (auto it = by_sys.find(card.sys_dir.string()); it != by_sys.end()) return jobs[it->second];
    CardLocation c{absolute_normal(card.root), absolute_normal(card.sys_dir)};
    const std::string key = folders.real_path(c.sys_dir.string());
    auto [it, fresh] = by_root.try_emplace(key, jobs.size());
    if (fresh) {
      Job j;
      j.card = c;
      j.title = title;
      j.dirs = folders.dirs();
      jobs.push_back(j);
    }
    by_sys.emplace(card.sys_dir.string(), it->second);
    return jobs[it->second];
  }

  // A lone file, once however often and by whatever path it is named (x.g ./x.g, or named and also walked).
  void lone(const fs::path& file, const std::string& title, bool explicit_path) {
    const auto [it, fresh] = lone_by_real.try_emplace(folders.real_path(absolute_normal(file)), jobs.size());
    if (!fresh) {
      jobs[it->second].explicit_path = jobs[it->second].explicit_path || explicit_path;
      return;
    }
    Job j;
    j.standalone = file;
    j.title = title;
    j.explicit_path = explicit_path;
    jobs.push_back(j);
  }

  void walk(const std::string& dir, int depth, bool below_macros) {
    // A folder that cannot be listed may hold a card: an error, never a pass over what it holds (unless
    // .gitignore leaves it out anyway).
    if (const std::string& why = folders.list_error(dir);
        !why.empty() && !(po.respect_gitignore && gitignore.ignored(join_path(dir, kAnyChild)))) {
      error(fmt::format("{}: cannot list the folder: {}", show(dir), why));
      io_error = true;
      return;
    }
    for (const DirEntry& e : folders.entries(dir)) {
      std::string path = join_path(dir, e.name);
      if (e.kind == DirEntry::Kind::Dir) {
        if (depth > 12 || e.name.starts_with(".") || e.link) continue;
        if (walk_excludes && settings.excluded(join_path(path, kAnyChild))) {
          ++stats.excluded;
          continue;
        }
        walk(path, depth + 1, below_macros || to_lower(e.name) == "macros");
      } else if (e.kind == DirEntry::Kind::File && candidate(e.name, below_macros)) {
        found.push_back(std::move(path));
      }
    }
  }

  // `-`: standard input, as --stdin-filename places it.
  void add_stdin() {
    if (!po.stdin_filename.empty() && !fs::path(po.stdin_filename).has_filename()) {
      error(fmt::format("--stdin-filename {}: that names a folder; give the name of a file (sys/config.g)",
                        po.stdin_filename));
      io_error = true;
      return;
    }
    // Redirected from a large file: mapped, as a large file named on the command line is (no copy).
    std::optional<TextBuffer> mapped = map_standard_input();
    // Otherwise read in blocks: a character at a time through std::cin took half a second for 30 MB.
    std::string read;
    // Redirected from a file: its size is known, so the string does not grow (and copy) on the way.
    if (struct stat st; !mapped && ::fstat(0, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0)
      read.reserve(static_cast<size_t>(st.st_size));
    std::vector<char> block(mapped ? 0 : size_t{1} << 16);
    if (!mapped)
      for (size_t n; (n = std::fread(block.data(), 1, block.size(), stdin)) > 0;) read.append(block.data(), n);
    TextBuffer bytes = mapped ? std::move(*mapped) : TextBuffer(std::move(read));
    if (!mapped && std::ferror(stdin)) {
      // A read error (standard input a folder, a closed descriptor): not linted as if it were empty.
      error(fmt::format("-: cannot read standard input: {}", std::strerror(errno)));
      io_error = true;
      return;
    }
    fs::path name = po.stdin_filename.empty() ? fs::path("stdin.g") : fs::path(po.stdin_filename);
    // Standard input linted on its own, or (excluded) only echoed back by --fix.
    auto lone_stdin = [&](bool excluded) {
      Job j;
      j.standalone = name;
      j.stdin_bytes = std::move(bytes);
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
        return;
      }
      if (auto at = folders.place(abs); at.card && at.sd && machine_path(*at.sd)) {
        Job& j = job_for_card(*at.card, po.stdin_filename);
        j.only.insert(to_lower(*at.sd));
        j.named.emplace(to_lower(*at.sd), po.stdin_filename);  // not linted (not G-code): says why
        j.stdin_bytes = std::move(bytes);
        j.stdin_sd_path = *at.sd;
        j.explicit_path = true;
        return;
      }
    }
    lone_stdin(false);
  }

  // A folder named on the command line (`p`; `abs`: absolute, normal). False on a config error.
  bool add_folder(const std::string& p, const fs::path& path, const std::string& abs) {
    std::error_code ec;
    // A folder named on purpose is linted even when `exclude` or .gitignore leaves it out (as an explicit file
    // is), unless --force-exclude; what is excluded below it stays excluded.
    const bool folder_excluded = settings.excluded(join_path(abs, kAnyChild));
    const bool folder_ignored = po.respect_gitignore && gitignore.ignored(join_path(abs, kAnyChild));
    if (po.force_exclude && (folder_excluded || folder_ignored)) {
      ++stats.force_excluded;
      return true;
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
        return true;
      }
    }
    return walk_folder(p, path, abs, folder_excluded, folder_ignored);
  }

  // Walks a folder named on the command line: candidate files (`*.g`, and files without extension below a
  // macros/ folder, which may be the walked folder or one above it as the path names it), minus .gitignore and
  // `exclude`. False on a config error.
  bool walk_folder(const std::string& p, const fs::path& path, const std::string& abs, bool folder_excluded,
                   bool folder_ignored) {
    bool below_macros = false;
    for (const fs::path& part : path) below_macros = below_macros || to_lower(part.string()) == "macros";
    found.clear();
    walk_excludes = !folder_excluded;
    const size_t folders_before = stats.excluded;
    walk(abs, 0, below_macros);
    const size_t folders_left_out = stats.excluded - folders_before;
    walk_excludes = true;
    if (settings.config_error()) return false;
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
      const Folders::Place at = folders.place(f);
      if (!at.card || !at.sd || !machine_path(*at.sd)) {
        lone(show(f), show(f), false);  // shown and read by the path from here, as a named file is
        continue;
      }
      Job& j = job_for_card(*at.card, show(at.card->root.string()));
      if (path_below(at.card->root.string(), abs)) j.report_all = true;  // the walk covers the whole card
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
    return true;
  }

  // An explicit file: linted even when excluded, unless --force-exclude.
  void add_file(const std::string& p, const fs::path& path, const std::string& abs) {
    if (po.force_exclude && (settings.excluded(abs) || (po.respect_gitignore && gitignore.ignored(abs)))) {
      ++stats.force_excluded;
      return;
    }
    std::string err;
    if (!probe_file(p, &err)) {
      error(fmt::format("{}: {}", p, err));
      io_error = true;
      return;
    }
    if (auto at = folders.place(abs); at.card && at.sd && machine_path(*at.sd)) {
      stats.roots.emplace_back(absolute_normal(at.card->root));
      Job& j = job_for_card(*at.card, p);
      j.only.insert(to_lower(*at.sd));
      j.named.emplace(to_lower(*at.sd), p);
      j.explicit_path = true;
      return;
    }
    stats.roots.emplace_back(fs::path(abs).parent_path());
    lone(path, p, true);
  }
};

}  // namespace

void plan(const std::vector<std::string>& paths, const PlanOptions& po, Settings& settings, GitIgnore& gitignore,
          std::vector<Job>& jobs, bool& io_error, PlanStats* stats_out) {
  PlanStats own;
  PlanStats& stats = stats_out ? *stats_out : own;
  std::error_code ec;
  Planner planner{po, settings, gitignore, jobs, io_error, stats};
  for (const std::string& p : paths) {
    ++stats.named;
    if (p == "-") {
      planner.add_stdin();
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
      stats.roots.emplace_back(abs);
      if (!planner.add_folder(p, path, abs)) return;
      continue;
    }
    planner.add_file(p, path, abs);
  }
}

}  // namespace rrflint::cli
