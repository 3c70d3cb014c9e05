#include "lint/card/card.h"
#include "lint/base/trace.h"

#include <algorithm>
#include <cstring>

namespace rrflint {

ReadResult MemoryReader::read(std::string_view sd_path) {
  ReadResult r;
  r.display = std::string(sd_path.substr(sd_path.starts_with("/") ? 1 : 0));
  auto it = files_.find(std::string(sd_path));
  if (it == files_.end()) {
    const std::string want = to_lower(sd_path);
    it = std::find_if(files_.begin(), files_.end(), [&](const auto& kv) { return to_lower(kv.first) == want; });
  }
  if (it == files_.end()) return r;
  r.status = ReadResult::Status::Ok;
  r.bytes = it->second;
  r.sd_path = it->first;
  r.display = it->first.substr(1);
  return r;
}

std::vector<std::string> MemoryReader::list(std::string_view sd_dir) {
  std::string prefix(sd_dir);
  if (!prefix.ends_with("/")) prefix += '/';
  std::vector<std::string> out;
  for (const auto& [k, v] : files_)
    if (to_lower(k).starts_with(to_lower(prefix))) out.push_back(k);
  return out;
}

std::optional<std::string> resolve_sd_path(std::string_view dir, std::string_view name, bool* outside_root) {
  if (outside_root) *outside_root = false;
  std::string full;
  if (name.size() >= 2 && name[0] >= '0' && name[0] <= '9' && name[1] == ':') {
    if (name[0] != '0') return std::nullopt;  // another volume
    name.remove_prefix(2);
    full = name.starts_with("/") ? std::string(name) : "/" + std::string(name);
  } else if (name.starts_with("/")) {
    full = std::string(name);
  } else {
    full = std::string(dir);
    if (!full.ends_with("/")) full += '/';
    full += name;
  }
  // The usual case: nothing to fold (no '.' or '..' segment, no doubled or trailing slash).
  if (full.size() > 1 && full.find("//") == std::string::npos && full.find("/.") == std::string::npos &&
      full.back() != '/')
    return full;
  std::vector<std::string_view> parts;
  std::string_view rest = full;
  while (!rest.empty()) {
    size_t slash = rest.find('/');
    std::string_view seg = rest.substr(0, slash);
    rest = slash == std::string_view::npos ? std::string_view{} : rest.substr(slash + 1);
    if (seg.empty() || seg == ".") continue;
    if (seg == "..") {
      if (parts.empty()) {
        if (outside_root) *outside_root = true;
        return std::nullopt;
      }
      parts.pop_back();
      continue;
    }
    parts.push_back(seg);
  }
  std::string out;
  for (auto p : parts) {
    out += '/';
    out += p;
  }
  return out.empty() ? std::string("/") : out;
}

bool looks_binary(std::string_view bytes) {
  const size_t n = std::min<size_t>(bytes.size(), 8192);
  if (std::memchr(bytes.data(), '\0', n) == nullptr) return false;  // the usual case, found at memchr speed
  size_t nul = 0, ctrl = 0;
  for (size_t i = 0; i < n; ++i) {
    unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c == 0) ++nul;
    else if (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f') ++ctrl;
  }
  if (nul == 0) return false;
  // A stray NUL in a text file is a line end to RRF (and RRF100 reports it); many NULs or many other
  // control characters mean a binary file.
  return nul > 16 || (nul + ctrl) * 10 > n;
}

std::string binary_reason(std::string_view bytes) {
  const auto b = [&](size_t i) { return i < bytes.size() ? static_cast<unsigned char>(bytes[i]) : 0x100u; };
  // UTF-16: a byte-order mark, or ASCII text with every other byte NUL (a Windows editor's "Unicode").
  bool utf16 = (b(0) == 0xFF && b(1) == 0xFE) || (b(0) == 0xFE && b(1) == 0xFF);
  if (!utf16 && bytes.size() >= 8) {
    // One half of the bytes nearly all NUL, the other half nearly all printable ASCII or line ends.
    size_t zeros[2] = {0, 0}, text[2] = {0, 0};
    const size_t n = std::min<size_t>(bytes.size() & ~size_t{1}, 512);
    for (size_t i = 0; i < n; ++i) {
      const unsigned char c = static_cast<unsigned char>(bytes[i]);
      zeros[i % 2] += c == 0;
      text[i % 2] += (c >= 0x20 && c < 0x7F) || c == '\t' || c == '\n' || c == '\r';
    }
    for (int odd = 0; odd < 2; ++odd)
      utf16 = utf16 || (zeros[odd] * 10 >= n / 2 * 9 && text[1 - odd] * 10 >= n / 2 * 9);
  }
  if (utf16) return "UTF-16 text, which RRF reads as binary (NUL bytes): not linted; save the file as UTF-8";
  return "binary file (NUL bytes), not G-code: not linted";
}

void Machine::add_problem(std::string_view sd_path, const std::string& display, std::string message) {
  // An empty stand-in source, so that a finding can point at the file that could not be linted.
  const SourceFile& stand_in = sources_.add(display, std::string(sd_path), TextBuffer(std::string()));
  problems_.push_back({std::string(sd_path), display, std::move(message), stand_in.id()});
}

const FileUnit* Machine::load(std::string_view sd_path) {
  const std::string key = to_lower(sd_path);
  if (auto it = by_path_.find(key); it != by_path_.end()) return it->second < 0 ? nullptr : units_[it->second].get();
  ReadResult r = reader_.read(sd_path);
  if (r.status != ReadResult::Status::Ok) {
    by_path_[key] = -1;
    if (r.status == ReadResult::Status::Error) add_problem(sd_path, r.display, r.error);
    return nullptr;
  }
  if (looks_binary(r.bytes)) {
    by_path_[key] = -1;
    add_problem(sd_path, r.display, binary_reason(r.bytes));
    return nullptr;
  }
  if (r.bytes.size() >= UINT32_MAX - 1) {
    by_path_[key] = -1;
    add_problem(sd_path, r.display, "file larger than 4 GiB: not linted");
    return nullptr;
  }
  auto u = std::make_unique<FileUnit>();
  u->sd_path = r.sd_path.empty() ? std::string(sd_path) : r.sd_path;
  const unsigned threads = r.bytes.size() >= 2 * part_bytes_ && part_bytes_ > 0 ? threads_ : 1;
  u->source = &sources_.add(r.display, u->sd_path, std::move(r.bytes), threads);
  trace::mark("line index");
  u->parsed =
      parse(*u->source, ParseOptions{.threads = threads_, .part_bytes = part_bytes_, .no_prefilters = no_prefilters_});
  trace::mark("parsed");
  u->index = static_cast<uint32_t>(units_.size());
  by_path_[key] = static_cast<int32_t>(units_.size());
  units_.push_back(std::move(u));
  return units_.back().get();
}

void Machine::set_listing(const std::vector<std::string>& sd_paths) {
  for (const auto& p : sd_paths) listing_[to_lower(p)] = true;
}

bool Machine::has_dir(std::string_view sd_dir) const {
  std::string key = to_lower(sd_dir);
  if (!key.ends_with("/")) key += '/';
  auto it = listing_.lower_bound(key);
  if (it != listing_.end() && it->first.starts_with(key)) return true;
  // Only the paths under the folder: the map is sorted, so they follow lower_bound(key).
  for (auto p = by_path_.lower_bound(key); p != by_path_.end() && p->first.starts_with(key); ++p)
    if (p->second >= 0) return true;
  return false;
}

bool Machine::uses_code(char letter, int32_t number) const {
  // Remembered with the number of units it covers: a file loaded later is scanned when next asked.
  std::lock_guard lock(code_uses_mutex_);
  auto& [seen, used] = code_uses_[{letter, number}];
  for (; seen < units_.size() && !used; ++seen) {
    const ParsedFile& pf = units_[seen]->parsed;
    for (uint32_t i : pf.with_code(letter, number))
      if (pf.commands[i].is(letter, number)) {
        used = true;
        break;
      }
  }
  return used;
}

bool Machine::has_file(std::string_view sd_path) const {
  const std::string key = to_lower(sd_path);
  if (listing_.count(key)) return true;
  auto it = by_path_.find(key);
  return it != by_path_.end() && it->second >= 0;
}

}  // namespace rrflint
