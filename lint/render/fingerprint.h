// What the code-scanning formats share (sarif.cc, gitlab.cc): each finding's file as a path relative to the
// repository, and a fingerprint of the finding that stays the same when lines move, so that a CI system can tell a
// new finding from one it reported before.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "lint/render/render.h"

namespace rrflint {

/// A file of a report, as the code-scanning formats name it.
struct RepoPath {
  std::string path;           // relative to the base, generic ('/'), when in_base; else the absolute path
  std::filesystem::path abs;  // absolute, normal
  bool in_base = false;
};

/// The files of a report relative to RenderOptions::uri_base (the git top-level, else the working directory),
/// display paths being relative to RenderOptions::cwd. Worked out once per file.
class RepoPaths {
 public:
  explicit RepoPaths(const RenderOptions& o);
  const std::filesystem::path& base() const { return base_; }
  /// kNoFile: an empty path, not in the base.
  const RepoPath& of(const SourceManager& sm, FileId file);

 private:
  std::filesystem::path base_, cwd_;
  std::map<FileId, RepoPath> cache_;
};

/// A stable fingerprint: the rule and the trimmed text of the finding's line, hashed (FNV-1a), plus the
/// occurrence of that hash in the file (GitHub's "hash:n" shape): "0123456789abcdef:1". It survives lines moving up
/// or down. The hashes of the line the last finding was on are kept by rule: findings come in order, and a long
/// line of many commands with a finding each would otherwise be hashed once per finding (the square of its length).
class Fingerprints {
 public:
  /// The occurrence is counted per file, or per `path` when one is given: a report that names files by path must
  /// count two files under one path (paths that differ only in invalid UTF-8, "a/./b" and "a/b") as one file.
  std::string operator()(const SourceManager& sm, const Diagnostic& d, std::string_view path = {});

 private:
  uint64_t hash(const SourceManager& sm, const Diagnostic& d);

  std::map<std::string, int> seen_;
  FileId file_ = kNoFile;
  uint32_t line0_ = 0;
  std::map<std::string, uint64_t, std::less<>> by_rule_;
};

/// FNV-1a, 64 bits, of `s`, continuing from `h`.
uint64_t fnv1a(std::string_view s, uint64_t h = 1469598103934665603ull);

}  // namespace rrflint
