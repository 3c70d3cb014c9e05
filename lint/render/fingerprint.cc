#include "lint/render/fingerprint.h"

#include <fmt/format.h>

#include <algorithm>

namespace fs = std::filesystem;

namespace rrflint {

RepoPaths::RepoPaths(const RenderOptions& o) {
  std::error_code ec;
  cwd_ = o.cwd.empty() ? fs::current_path(ec) : o.cwd;
  base_ = (o.uri_base.empty() ? cwd_ : o.uri_base).lexically_normal();
}

const RepoPath& RepoPaths::of(const SourceManager& sm, FileId file) {
  auto [it, fresh] = cache_.try_emplace(file);
  RepoPath& p = it->second;
  if (!fresh || file == kNoFile) return p;
  const fs::path display(sm.get(file).display_path());
  p.abs = (display.is_absolute() ? display : cwd_ / display).lexically_normal();
  const fs::path rel = p.abs.lexically_relative(base_);
  const std::string r = rel.generic_string();
  p.in_base = !rel.empty() && !r.starts_with("..");
  p.path = p.in_base ? r : p.abs.generic_string();
  return p;
}

uint64_t fnv1a(std::string_view s, uint64_t h) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string Fingerprints::operator()(const SourceManager& sm, const Diagnostic& d, std::string_view path) {
  const std::string hex = fmt::format("{:016x}", hash(sm, d));
  const int n = ++seen_[path.empty() ? fmt::format("f{}\x1f{}", d.loc.file, hex) : fmt::format("p{}\x1f{}", path, hex)];
  return fmt::format("{}:{}", hex, n);
}

uint64_t Fingerprints::hash(const SourceManager& sm, const Diagnostic& d) {
  uint64_t h = fnv1a("\x1f", fnv1a(d.code));
  if (d.loc.file == kNoFile) return h;
  const SourceFile& f = sm.get(d.loc.file);
  if (f.line_count() == 0) return h;
  const uint32_t line0 = f.line_of(std::min(d.loc.span.begin, f.size()));
  if (d.loc.file != file_ || line0 != line0_) {
    file_ = d.loc.file;
    line0_ = line0;
    by_rule_.clear();
  }
  if (auto it = by_rule_.find(d.code); it != by_rule_.end()) return it->second;
  std::string_view line = f.slice(f.line_span(line0));
  while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
  while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
  h = fnv1a(line, h);
  by_rule_.emplace(d.code, h);
  return h;
}

}  // namespace rrflint
