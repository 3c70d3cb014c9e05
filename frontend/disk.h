// FileReaders over the real file system, used by the front ends (never by the core).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "lint/card/card.h"

namespace rrflint {

/// One entry of a folder listing. Symbolic links are followed to tell a file from a folder; walks descend only
/// into real folders (`Dir` and not `link`).
struct DirEntry {
  enum class Kind : uint8_t { File, Dir, Other };  // File: a regular file
  std::string name;
  Kind kind = Kind::Other;
  bool link = false;  // a symbolic link (to `kind`)
};
/// The entries of a folder (without "." and ".."), in the file system's order; empty when it cannot be read, and
/// then `error` (when given) says why ("Permission denied").
std::vector<DirEntry> list_dir(const std::string& dir, std::string* error = nullptr);
/// The entry called `name`: that exact name first, else the first that matches in any case (as FAT would);
/// `kind` restricts both to one kind of entry.
const DirEntry* find_entry(const std::vector<DirEntry>& entries, std::string_view name,
                           std::optional<DirEntry::Kind> kind = std::nullopt);
/// `dir` + "/" + `name`, without doubling the slash of the root folder.
std::string join_path(const std::string& dir, std::string_view name);
/// The absolute, lexically normal form of a path, without a trailing slash (but "/" for the root).
std::string absolute_normal(const std::filesystem::path& p);
/// An absolute, normal path that is a file-system root: "/", or on Windows a drive's "C:/".
bool is_root(std::string_view abs);
/// The folder above an absolute, normal path ("/" above "/a", "C:/" above "C:/a").
std::string parent_of(std::string_view abs);
/// The last part of a path.
std::string_view name_of(std::string_view path);
/// `abs` relative to `base` ("" when equal), if it lies at or below it. Both absolute and lexically normal.
std::optional<std::string> path_below(std::string_view abs, std::string_view base);

/// Folder listings, each folder read once. A run shares one between its walk and its readers (the walk has
/// listed the folders the readers look in); it never forgets, so it is not for a long-lived process.
class DirCache {
 public:
  struct Listing {
    std::vector<DirEntry> entries;
    std::string error;                                 // why the folder could not be listed (then `entries` is empty)
    std::unordered_map<std::string, size_t> by_lower;  // lower-cased name -> the first entry of that name
  };
  /// The listing of a folder (absolute, normal). Thread-safe.
  const Listing& get(const std::string& dir);

 private:
  std::mutex mutex_;
  std::unordered_map<std::string, Listing> listings_;
};

/// Maps SD paths onto a folder: "/sys/…" onto `sys_dir`, "/<other>/…" onto `root/<other>`.
/// Lookups fall back to a case-insensitive match, as the SD card's FAT file system would.
class DiskReader : public FileReader {
 public:
  /// `dirs`: listings to share with other readers of the same run (by default, the reader's own).
  DiskReader(std::filesystem::path root, std::filesystem::path sys_dir, std::filesystem::path display_base,
             std::shared_ptr<DirCache> dirs = nullptr);
  ReadResult read(std::string_view sd_path) override;
  std::vector<std::string> list(std::string_view sd_dir) override;
  /// The file on disk for an SD path (absolute and lexically normal), if it exists. `spelled` gets the SD path
  /// spelled as the files on disk are.
  std::optional<std::string> locate(std::string_view sd_path, std::string* spelled = nullptr) const;
  /// Replaces a file's content (stdin, editor buffers).
  void overlay(std::string sd_path, TextBuffer bytes) {
    std::string key = to_lower(sd_path);
    overlay_[std::move(key)] = Overlaid{std::move(sd_path), std::move(bytes)};
  }

 private:
  /// Where an SD path is, or would be, on disk (it need not exist): below the sys folder for /sys/…, else the root.
  std::filesystem::path disk_place(std::string_view sd_path) const;
  void list_below(const std::string& dir, const std::string& sd_prefix, int depth, std::vector<std::string>& out) const;
  std::string root_, sys_, base_;   // absolute and lexically normal
  std::shared_ptr<DirCache> dirs_;  // each folder listed once (a card asks for many missing tool macros)
  struct Overlaid {
    std::string sd_path;  // as given: a file not on disk yet keeps its name's case
    TextBuffer bytes;
  };
  std::map<std::string, Overlaid> overlay_;  // by lower-case SD path
};

/// Reads a whole file; nullopt with `error` set on failure.
std::optional<std::string> read_file(const std::string& path, std::string* error);

/// Reads a whole file as read_file does, but maps a large regular file (4 MB or more) instead of copying it,
/// once map_large_files(true) was called. A mapped file that another program cuts short while it is read raises
/// SIGBUS, so only a program that handles SIGBUS should turn this on (the CLI does: cli/main.cc).
std::optional<TextBuffer> read_text(const std::string& path, std::string* error);
void map_large_files(bool on);

/// Standard input redirected from a large regular file (`rrflint check - < FILE`) and not read yet, mapped as
/// read_text maps a file (same conditions); nullopt otherwise (a pipe, a terminal, a small file): then read it.
std::optional<TextBuffer> map_standard_input();

/// Whether read_file would open `path` (not a folder, readable); `error` set as read_file sets it when not. Reads
/// nothing, so a large file costs no more than a small one.
bool probe_file(const std::string& path, std::string* error);

/// Where an SD card starts for a path: a folder with sys/config.g, or a sys-like folder holding config.g.
struct CardLocation {
  std::filesystem::path root;     // SD root ("/" on the card)
  std::filesystem::path sys_dir;  // the folder that plays /sys
};
std::optional<CardLocation> card_at(const std::filesystem::path& dir);
/// Does this folder hold a config.g (any case)?
bool has_config(const std::filesystem::path& dir);
/// The same for a folder already listed.
bool has_config(const std::vector<DirEntry>& entries);

}  // namespace rrflint
