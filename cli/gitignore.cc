// GitIgnore: is a file ignored by git? One `git check-ignore` per repository for many files at once, and a
// fallback matcher that reads the .gitignore files itself where git gives no answer.
#include <fmt/format.h>

#ifndef _WIN32
#include <sys/wait.h>
#endif
#include <cstdio>
#include <unordered_map>

#include "cli/cli.h"
#include "frontend/platform.h"

namespace rrflint::cli {
namespace {

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
  else if (!is_root(dir)) result = repo_of(parent_of(dir));
  return memo.emplace(dir, std::move(result)).first->second;
}

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
#ifdef _WIN32
  // No POSIX shell to run `git check-ignore` through: the fallback matcher reads the .gitignore files.
  for (auto& entry : by_repo) no_git_.insert(entry.first);
  by_repo.clear();
#endif
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
    const std::string cmd =
        fmt::format("git -C {} check-ignore -z --stdin < {} 2>/dev/null", shell_quote(root), shell_quote(tmpl));
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
  if (!is_root(dir) && !(repo && *repo == dir)) {  // below the top: the folders above apply too
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

}  // namespace rrflint::cli
