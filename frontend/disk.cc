#include "frontend/disk.h"
#include "lint/base/trace.h"

#ifndef _WIN32
#include <dirent.h>
#endif

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <set>
#include <system_error>

#include "frontend/platform.h"
#include "lint/base/huge_pages.h"

namespace fs = std::filesystem;

namespace rrflint {
const DirEntry* find_entry(const std::vector<DirEntry>& entries, std::string_view name,
                           std::optional<DirEntry::Kind> kind) {
  auto wanted = [&](const DirEntry& e) { return !kind || e.kind == *kind; };
  for (const DirEntry& e : entries)
    if (e.name == name && wanted(e)) return &e;
  const std::string lower = to_lower(name);
  for (const DirEntry& e : entries)
    if (wanted(e) && to_lower(e.name) == lower) return &e;
  return nullptr;
}

bool has_config(const fs::path& dir) { return has_config(list_dir(dir.string())); }

bool has_config(const std::vector<DirEntry>& entries) {
  // Anything called config.g but a folder: a config.g that is a FIFO or a dangling link still makes a card, whose
  // config.g is then reported as unreadable (never silently skipped).
  const DirEntry* c = find_entry(entries, "config.g");
  return c && c->kind != DirEntry::Kind::Dir;
}

#ifdef _WIN32
// Windows: the folder through std::filesystem (the MSVC runtime has no dirent); its links are followed.
std::vector<DirEntry> list_dir(const std::string& dir, std::string* error) {
  std::vector<DirEntry> out;
  std::error_code ec;
  fs::directory_iterator it(fs::path(dir), ec);
  if (ec && error) *error = ec.message();
  for (fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
    DirEntry entry{it->path().filename().string(), DirEntry::Kind::Other, it->is_symlink(ec)};
    if (it->is_regular_file(ec)) entry.kind = DirEntry::Kind::File;
    else if (it->is_directory(ec)) entry.kind = DirEntry::Kind::Dir;
    out.push_back(std::move(entry));
  }
  return out;
}
#else
std::vector<DirEntry> list_dir(const std::string& dir, std::string* error) {
  std::vector<DirEntry> out;
  DIR* d = ::opendir(dir.c_str());
  if (!d) {
    if (error) *error = errno == EACCES ? "permission denied" : std::strerror(errno);
    return out;
  }
  while (const dirent* e = ::readdir(d)) {
    const std::string_view name(e->d_name);
    if (name == "." || name == "..") continue;
    DirEntry entry{std::string(name), DirEntry::Kind::Other, false};
    unsigned char type = e->d_type;
    struct stat st;
    if (type == DT_UNKNOWN && ::fstatat(::dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0)
      type = S_ISLNK(st.st_mode) ? DT_LNK : S_ISDIR(st.st_mode) ? DT_DIR : S_ISREG(st.st_mode) ? DT_REG : DT_UNKNOWN;
    if (type == DT_LNK) {
      entry.link = true;
      if (::fstatat(::dirfd(d), e->d_name, &st, 0) == 0)
        type = S_ISDIR(st.st_mode) ? DT_DIR : S_ISREG(st.st_mode) ? DT_REG : DT_UNKNOWN;
    }
    if (type == DT_REG) entry.kind = DirEntry::Kind::File;
    else if (type == DT_DIR) entry.kind = DirEntry::Kind::Dir;
    out.push_back(std::move(entry));
  }
  ::closedir(d);
  return out;
}
#endif

std::string join_path(const std::string& dir, std::string_view name) {
  std::string out;
  out.reserve(dir.size() + 1 + name.size());
  out = dir;
  if (!out.ends_with('/')) out += '/';
  out += name;
  return out;
}

namespace {
// A Windows drive, "C:" (the root is "C:/"); never on POSIX systems, where every absolute path starts with '/'.
bool is_drive(std::string_view s) {
  return s.size() == 2 && s[1] == ':' && std::isalpha(static_cast<unsigned char>(s[0]));
}
}  // namespace

bool is_root(std::string_view abs) {
  return abs == "/" || (abs.size() == 3 && is_drive(abs.substr(0, 2)) && abs[2] == '/');
}

std::string parent_of(std::string_view abs) {
  const size_t slash = abs.rfind('/');
  if (slash != std::string_view::npos && is_drive(abs.substr(0, slash))) return std::string(abs.substr(0, slash + 1));
  return slash == 0 || slash == std::string_view::npos ? std::string("/") : std::string(abs.substr(0, slash));
}

std::string_view name_of(std::string_view path) { return path.substr(path.rfind('/') + 1); }

std::optional<std::string> path_below(std::string_view abs, std::string_view base) {
  if (abs == base) return std::string();
  if (is_root(base)) return abs.starts_with(base) ? std::optional<std::string>(abs.substr(base.size())) : std::nullopt;
  if (abs.size() > base.size() && abs.starts_with(base) && abs[base.size()] == '/')
    return std::string(abs.substr(base.size() + 1));
  return std::nullopt;
}

namespace {

// What a file that is not a regular file is, for a message.
const char* kind_of(mode_t m) {
  if (S_ISDIR(m)) return "is a directory";
  if (S_ISFIFO(m)) return "is a FIFO (named pipe), not a regular file: not read";
  if (S_ISSOCK(m)) return "is a socket, not a regular file: not read";
  if (S_ISCHR(m) || S_ISBLK(m)) return "is a device, not a regular file: not read";
  return "is not a regular file: not read";
}

// Opens `path` for reading as read_file does; -1 with `error` set when it cannot, or when it is not a regular
// file. A FIFO or a device is never read: opening a FIFO blocks until a writer comes (O_NONBLOCK makes the open
// return at once, and the fstat then refuses it), and a device may never end.
int open_readable(const std::string& path, struct stat& st, std::string* error) {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return -1;
  };
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) {
    if (!error) return -1;
    if (::stat(path.c_str(), &st) != 0)
      return fail(errno == ELOOP ? "too many levels of symbolic links" : "no such file");
    if (!S_ISREG(st.st_mode)) return fail(kind_of(st.st_mode));
    return fail("permission denied");
  }
  const char* why = ::fstat(fd, &st) != 0 ? "read error" : !S_ISREG(st.st_mode) ? kind_of(st.st_mode) : nullptr;
  if (why) {
    ::close(fd);
    return fail(why);
  }
  return fd;
}

struct Closer {
  int fd;
  ~Closer() { ::close(fd); }
};

}  // namespace

bool probe_file(const std::string& path, std::string* error) {
  struct stat st;
  const int fd = open_readable(path, st, error);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

namespace {

std::atomic<bool> map_large{false};
constexpr size_t kMapFrom = size_t{4} << 20;

// read_file on an open file.
std::optional<std::string> read_open(int fd, const struct stat& st, std::string* error) {
  auto fail = [&](const char* why) -> std::optional<std::string> {
    if (error) *error = why;
    return std::nullopt;
  };
  // A file with a size: that many bytes (the file as it was when opened). Without one (empty, a pipe, /proc):
  // on to the end.
  const bool sized = S_ISREG(st.st_mode) && st.st_size > 0;
  std::string s;
  if (sized) {
    reserve_huge(s, static_cast<size_t>(st.st_size));
    s.resize(static_cast<size_t>(st.st_size));
  }
  size_t got = 0;
  char more[4096];
  while (!sized || got < s.size()) {
    const ssize_t n = sized ? ::read(fd, s.data() + got, s.size() - got) : ::read(fd, more, sizeof more);
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail("read error");
    }
    if (n == 0) break;
    if (sized) got += static_cast<size_t>(n);
    else s.append(more, static_cast<size_t>(n)), got = s.size();
  }
  s.resize(got);
  return s;
}

}  // namespace

void map_large_files(bool on) { map_large = on; }

std::optional<TextBuffer> map_standard_input() {
#if defined(__linux__)
  struct stat st;
  // Only at offset 0: a descriptor that was read from before (`(head -c 9; rrflint check -) < FILE`) goes on from
  // where it is, and a mapping starts at a page.
  if (!map_large || ::fstat(0, &st) != 0 || !S_ISREG(st.st_mode) || static_cast<size_t>(st.st_size) < kMapFrom ||
      ::lseek(0, 0, SEEK_CUR) != 0)
    return std::nullopt;
  if (const char* p = map_bytes(0, static_cast<size_t>(st.st_size))) {
    trace::mark("mapped standard input");
    return TextBuffer::mapped(p, static_cast<size_t>(st.st_size));
  }
#endif
  return std::nullopt;
}

std::optional<std::string> read_file(const std::string& path, std::string* error) {
  struct stat st;
  const int fd = open_readable(path, st, error);
  if (fd < 0) return std::nullopt;
  const Closer closer{fd};
  return read_open(fd, st, error);
}

std::optional<TextBuffer> read_text(const std::string& path, std::string* error) {
  struct stat st;
  const int fd = open_readable(path, st, error);
  if (fd < 0) return std::nullopt;
  const Closer closer{fd};
  if (map_large && S_ISREG(st.st_mode) && static_cast<size_t>(st.st_size) >= kMapFrom)
    if (const char* p = map_bytes(fd, static_cast<size_t>(st.st_size))) {
      trace::mark("mapped");
      return TextBuffer::mapped(p, static_cast<size_t>(st.st_size));
    }
  auto s = read_open(fd, st, error);
  trace::mark("read");
  if (!s) return std::nullopt;
  return TextBuffer(std::move(*s));
}

std::string absolute_normal(const fs::path& p) {
  std::error_code ec;
  std::string s = fs::absolute(p, ec).lexically_normal().generic_string();  // Windows too: '/', "C:/…"
  if (!is_root(s) && s.ends_with('/')) s.pop_back();
  return s;
}

const DirCache::Listing& DirCache::get(const std::string& dir) {
  // Readers of machines linted in parallel share the cache. A listing never changes once made, and the map's
  // nodes stay put, so the reference stays good after the lock is released.
  std::lock_guard<std::mutex> lock(mutex_);
  auto [it, fresh] = listings_.try_emplace(dir);
  if (fresh) {
    Listing& l = it->second;
    l.entries = list_dir(dir, &l.error);
    for (size_t i = 0; i < l.entries.size(); ++i) l.by_lower.try_emplace(to_lower(l.entries[i].name), i);
  }
  return it->second;
}

DiskReader::DiskReader(fs::path root, fs::path sys_dir, fs::path display_base, std::shared_ptr<DirCache> dirs)
    : root_(absolute_normal(root)),
      sys_(absolute_normal(sys_dir)),
      base_(absolute_normal(display_base)),
      dirs_(dirs ? std::move(dirs) : std::make_shared<DirCache>()) {}

fs::path DiskReader::disk_place(std::string_view sd_path) const {
  std::string d(sd_path);
  if (to_lower(d) == "/sys" || to_lower(d).starts_with("/sys/"))
    return fs::path(sys_) / d.substr(std::min<size_t>(d.size(), 5));
  return fs::path(root_) / (d.starts_with("/") ? d.substr(1) : d);
}

std::optional<std::string> DiskReader::locate(std::string_view sd_path, std::string* spelled) const {
  std::string cur, out;
  std::string_view rest;
  // "/sys" itself and everything below it live in the sys folder, whatever that folder is called on disk.
  const std::string head = to_lower(sd_path.substr(0, 5));
  if (head == "/sys/" || head == "/sys") {
    cur = sys_;
    rest = sd_path.substr(std::min<size_t>(sd_path.size(), 5));
    out = "/sys";
  } else {
    cur = root_;
    rest = sd_path.starts_with('/') ? sd_path.substr(1) : sd_path;
  }
  size_t start = 0;
  while (start <= rest.size()) {
    const size_t slash = rest.find('/', start);
    const std::string_view seg = rest.substr(start, slash == std::string_view::npos ? slash : slash - start);
    if (!seg.empty()) {
      const DirCache::Listing& l = dirs_->get(cur);
      auto hit = l.by_lower.find(to_lower(seg));
      if (hit == l.by_lower.end()) return std::nullopt;
      const std::string& name = l.entries[hit->second].name;
      cur = join_path(cur, name);
      out += '/';
      out += name;
    }
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  if (spelled) *spelled = out.empty() ? "/" : out;
  return cur;
}

ReadResult DiskReader::read(std::string_view sd_path) {
  ReadResult r;
  if (auto it = overlay_.find(to_lower(sd_path)); it != overlay_.end()) {
    r.status = ReadResult::Status::Ok;
    r.bytes = it->second.bytes;
    r.sd_path = std::string(sd_path);
    // A file not on disk yet (a new file in an editor or on stdin) is shown where it will be, in /sys or not.
    const auto where = locate(sd_path);
    r.display = (where ? fs::path(*where) : disk_place(it->second.sd_path)).lexically_relative(base_).generic_string();
    return r;
  }
  std::string spelled;
  auto where = locate(sd_path, &spelled);
  if (!where) return r;
  std::string err;
  auto bytes = read_text(*where, &err);
  auto rel = path_below(*where, base_);
  r.display = !rel || rel->starts_with("..") ? *where : rel->empty() ? std::string(".") : std::move(*rel);
  if (!bytes) {
    r.status = ReadResult::Status::Error;
    r.error = err;
    return r;
  }
  r.status = ReadResult::Status::Ok;
  r.bytes = std::move(*bytes);
  // The SD path with the real case of the file name.
  r.sd_path = std::move(spelled);
  return r;
}

void DiskReader::list_below(const std::string& dir, const std::string& sd_prefix, int depth,
                            std::vector<std::string>& out) const {
  for (const DirEntry& e : dirs_->get(dir).entries) {
    if (e.kind == DirEntry::Kind::File) out.push_back(sd_prefix + e.name);
    else if (e.kind == DirEntry::Kind::Dir && !e.link && depth < 8)  // at most 8 folders deep, as the SD card walk goes
      list_below(join_path(dir, e.name), sd_prefix + e.name + "/", depth + 1, out);
  }
}

std::vector<std::string> DiskReader::list(std::string_view sd_dir) {
  std::vector<std::string> out;
  auto dir = locate(sd_dir);
  struct stat st;
  std::string base(sd_dir);
  if (!base.ends_with("/")) base += '/';
  // The folder may not exist on disk: a buffer from stdin or an editor placed in a card that is not there yet.
  if (dir && ::stat(dir->c_str(), &st) == 0 && S_ISDIR(st.st_mode)) list_below(*dir, base, 0, out);
  // A file both on disk and overlaid is listed once, as the disk spells it; one not on disk as it was given.
  std::set<std::string> listed;
  for (const std::string& f : out) listed.insert(to_lower(f));
  for (const auto& [key, file] : overlay_)
    if (key.starts_with(to_lower(base)) && !listed.count(key)) out.push_back(file.sd_path);
  std::sort(out.begin(), out.end());
  return out;
}

std::optional<CardLocation> card_at(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return std::nullopt;
  const std::vector<DirEntry> entries = list_dir(dir.string());
  if (const DirEntry* sys = find_entry(entries, "sys"); sys && has_config(dir / sys->name))
    return CardLocation{dir, dir / sys->name};
  if (has_config(dir)) {
    fs::path abs = fs::absolute(dir, ec);
    if (abs.filename().empty()) abs = abs.parent_path();
    return CardLocation{abs.parent_path(), abs};
  }
  return std::nullopt;
}

}  // namespace rrflint
