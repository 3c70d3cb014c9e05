// FileReaders over the real file system, used by the front ends (never by the core).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "project.h"

namespace rrflint {

/// Maps SD paths onto a folder: "/sys/…" onto `sys_dir`, "/<other>/…" onto `root/<other>`.
/// Lookups fall back to a case-insensitive match, as the SD card's FAT file system would.
class DiskReader : public FileReader {
 public:
  DiskReader(std::filesystem::path root, std::filesystem::path sys_dir, std::filesystem::path display_base);
  ReadResult read(std::string_view sd_path) override;
  std::vector<std::string> list(std::string_view sd_dir) override;
  /// The file on disk for an SD path, if it exists.
  std::optional<std::filesystem::path> locate(std::string_view sd_path) const;
  /// The SD path of a file on disk, if it lies under this card.
  std::optional<std::string> sd_path_of(const std::filesystem::path& p) const;
  /// Replaces a file's content (stdin, editor buffers).
  void overlay(std::string sd_path, std::string bytes) { overlay_[to_lower(sd_path)] = std::move(bytes); }

 private:
  std::filesystem::path disk_dir(std::string_view sd_dir) const;
  // Case-insensitive child lookup, with each folder listed once (a card asks for many missing tool macros).
  std::optional<std::filesystem::path> child(const std::filesystem::path& dir, const std::string& name) const;
  // locate() that also returns the SD path spelled as the files on disk are.
  std::optional<std::filesystem::path> locate_spelled(std::string_view sd_path, std::string* spelled) const;
  mutable std::map<std::string, std::map<std::string, std::filesystem::path>> listings_;
  std::filesystem::path root_, sys_, base_;
  std::map<std::string, std::string> overlay_;
};

/// Reads a whole file; nullopt with `error` set on failure.
std::optional<std::string> read_file(const std::filesystem::path& p, std::string* error);

/// Where an SD card starts for a path: a folder with sys/config.g, or a sys-like folder holding config.g.
struct CardLocation {
  std::filesystem::path root;     // SD root ("/" on the card)
  std::filesystem::path sys_dir;  // the folder that plays /sys
};
std::optional<CardLocation> card_at(const std::filesystem::path& dir);
/// Does this folder hold a config.g (any case)?
bool has_config(const std::filesystem::path& dir);

}  // namespace rrflint
