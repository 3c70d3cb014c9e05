#include "disk.h"

#include <algorithm>
#include <fstream>
#include <system_error>

namespace fs = std::filesystem;

namespace rrflint {
namespace {

std::optional<fs::path> find_ci(const fs::path& dir, const std::string& name) {
  std::error_code ec;
  fs::path exact = dir / name;
  if (fs::exists(exact, ec)) return exact;
  const std::string want = to_lower(name);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (to_lower(it->path().filename().string()) == want) return it->path();
  return std::nullopt;
}

}  // namespace

bool has_config(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return false;
  auto c = find_ci(dir, "config.g");
  return c && fs::is_regular_file(*c, ec);
}

std::optional<std::string> read_file(const fs::path& p, std::string* error) {
  std::error_code ec;
  if (fs::is_directory(p, ec)) {
    if (error) *error = "is a directory";
    return std::nullopt;
  }
  std::ifstream in(p, std::ios::binary);
  if (!in) {
    if (error) *error = fs::exists(p, ec) ? "permission denied or unreadable" : "no such file";
    return std::nullopt;
  }
  std::string s;
  in.seekg(0, std::ios::end);
  auto size = in.tellg();
  if (size > 0) {
    s.resize(static_cast<size_t>(size));
    in.seekg(0);
    in.read(s.data(), size);
  } else {
    s.assign(std::istreambuf_iterator<char>(in), {});
  }
  if (in.bad()) {
    if (error) *error = "read error";
    return std::nullopt;
  }
  return s;
}

DiskReader::DiskReader(fs::path root, fs::path sys_dir, fs::path display_base)
    : root_(std::move(root)), sys_(std::move(sys_dir)), base_(std::move(display_base)) {}

fs::path DiskReader::disk_dir(std::string_view sd_dir) const {
  std::string d(sd_dir);
  if (to_lower(d) == "/sys" || to_lower(d).starts_with("/sys/")) return sys_ / d.substr(std::min<size_t>(d.size(), 5));
  return root_ / (d.starts_with("/") ? d.substr(1) : d);
}

std::optional<fs::path> DiskReader::child(const fs::path& dir, const std::string& name) const {
  auto [it, fresh] = listings_.try_emplace(dir.string());
  if (fresh) {
    std::error_code ec;
    for (fs::directory_iterator d(dir, ec), end; !ec && d != end; d.increment(ec))
      it->second.emplace(to_lower(d->path().filename().string()), d->path());
  }
  auto hit = it->second.find(to_lower(name));
  if (hit == it->second.end()) return std::nullopt;
  return hit->second;
}

std::optional<fs::path> DiskReader::locate(std::string_view sd_path) const { return locate_spelled(sd_path, nullptr); }

std::optional<fs::path> DiskReader::locate_spelled(std::string_view sd_path, std::string* spelled) const {
  std::string p(sd_path);
  fs::path cur;
  std::string rest;
  std::string out;
  if (to_lower(p).starts_with("/sys/")) {
    cur = sys_;
    rest = p.substr(5);
    out = "/sys";
  } else {
    cur = root_;
    rest = p.starts_with("/") ? p.substr(1) : p;
  }
  size_t start = 0;
  while (start <= rest.size()) {
    size_t slash = rest.find('/', start);
    std::string seg = rest.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (!seg.empty()) {
      auto next = child(cur, seg);
      if (!next) return std::nullopt;
      cur = *next;
      out += "/" + cur.filename().string();
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  if (spelled) *spelled = out.empty() ? "/" : out;
  return cur;
}

std::optional<std::string> DiskReader::sd_path_of(const fs::path& p) const {
  std::error_code ec;
  fs::path abs = fs::weakly_canonical(p, ec);
  for (auto [base, prefix] : {std::pair{sys_, std::string("/sys")}, std::pair{root_, std::string("")}}) {
    fs::path b = fs::weakly_canonical(base, ec);
    auto rel = abs.lexically_relative(b);
    if (rel.empty() || rel.native().starts_with("..")) continue;
    std::string r = rel.generic_string();
    if (r == ".") r.clear();
    return prefix + "/" + r;
  }
  return std::nullopt;
}

ReadResult DiskReader::read(std::string_view sd_path) {
  ReadResult r;
  if (auto it = overlay_.find(to_lower(sd_path)); it != overlay_.end()) {
    r.status = ReadResult::Status::Ok;
    r.bytes = it->second;
    r.sd_path = std::string(sd_path);
    auto where = locate(sd_path);
    r.display = where ? where->lexically_relative(base_).generic_string() : std::string(sd_path);
    if (!where) r.display = (disk_dir("/sys") / std::string(sd_path).substr(5)).lexically_relative(base_).generic_string();
    return r;
  }
  std::string spelled;
  auto where = locate_spelled(sd_path, &spelled);
  if (!where) return r;
  std::string err;
  auto bytes = read_file(*where, &err);
  fs::path rel = where->lexically_relative(base_);
  r.display = (rel.empty() || rel.native().starts_with("..")) ? where->generic_string() : rel.generic_string();
  if (!bytes) {
    r.status = ReadResult::Status::Error;
    r.error = err;
    return r;
  }
  r.status = ReadResult::Status::Ok;
  r.bytes = std::move(*bytes);
  // The SD path with the real case of the file name.
  r.sd_path = spelled;
  return r;
}

std::vector<std::string> DiskReader::list(std::string_view sd_dir) {
  std::vector<std::string> out;
  auto dir = locate(sd_dir);
  std::error_code ec;
  if (!dir || !fs::is_directory(*dir, ec)) return out;
  for (fs::recursive_directory_iterator it(*dir, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    if (it.depth() > 8) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    fs::path rel = it->path().lexically_relative(*dir);
    std::string base(sd_dir);
    if (!base.ends_with("/")) base += '/';
    out.push_back(base + rel.generic_string());
  }
  for (const auto& [k, v] : overlay_)
    if (k.starts_with(to_lower(std::string(sd_dir)) + "/")) out.push_back(k);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::optional<CardLocation> card_at(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return std::nullopt;
  if (auto sys = find_ci(dir, "sys"); sys && has_config(*sys)) return CardLocation{dir, *sys};
  if (has_config(dir)) {
    fs::path abs = fs::absolute(dir, ec);
    if (abs.filename().empty()) abs = abs.parent_path();
    return CardLocation{abs.parent_path(), abs};
  }
  return std::nullopt;
}

}  // namespace rrflint
