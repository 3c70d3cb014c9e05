// A machine's files: an SD-card tree read through an injected FileReader, each file loaded and parsed once.
//
// Paths inside a machine are SD paths ("/sys/config.g", "/macros/Park.g"). The FileReader maps them to
// whatever holds the bytes: a folder on disk for the CLI, a map in memory for tests and the language server.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lint/base/source.h"
#include "lint/base/strings.h"
#include "lint/syntax/parser.h"

namespace rrflint {

struct ReadResult {
  enum class Status { Ok, NotFound, Error } status = Status::NotFound;
  TextBuffer bytes;
  std::string error;    // for Status::Error: what went wrong (permission denied, is a directory, …)
  std::string display;  // how to show the path to a user
  std::string sd_path;  // the path as found (the SD card is case-insensitive, so this may differ in case)
};

class FileReader {
 public:
  virtual ~FileReader() = default;
  /// Reads a file by SD path. Looks the name up case-insensitively, as FAT does.
  virtual ReadResult read(std::string_view sd_path) = 0;
  /// Every file below an SD folder, recursively, as SD paths, sorted.
  virtual std::vector<std::string> list(std::string_view sd_dir) = 0;
};

/// A FileReader over a map of SD path -> content (tests, editors).
class MemoryReader : public FileReader {
 public:
  void add(std::string sd_path, std::string bytes) { files_[std::move(sd_path)] = std::move(bytes); }
  ReadResult read(std::string_view sd_path) override;
  std::vector<std::string> list(std::string_view sd_dir) override;

 private:
  std::map<std::string, std::string> files_;
};

/// Joins `name` to `dir` the way RRF's CombineName does: "0:/x" and "/x" are absolute, anything else is
/// relative to `dir`. "." and ".." segments are folded. Nullopt if the path climbs above the root or names
/// another volume ("1:/…").
std::optional<std::string> resolve_sd_path(std::string_view dir, std::string_view name, bool* outside_root = nullptr);

/// Is this byte string a binary (non-text) file? Only the first 8 KiB are looked at: it is binary when they hold
/// a NUL byte and either more than 16 NUL bytes or more than 10 % NUL and other control bytes (TAB, LF, CR and FF
/// do not count). A text file with a few stray NUL bytes is linted, and each NUL is a syntax error (RRF ends the
/// line there).
bool looks_binary(std::string_view bytes);
/// Why a file that looks_binary is not linted, for the message (names UTF-16).
std::string binary_reason(std::string_view bytes);

struct FileUnit {
  const SourceFile* source = nullptr;
  ParsedFile parsed;
  std::string sd_path;
  uint32_t index = 0;  // position in Machine's unit list
};

/// A file of the machine that exists but could not be linted (unreadable, binary, not a regular file, too large).
struct LoadProblem {
  std::string sd_path;
  std::string display;
  std::string message;
  FileId file = kNoFile;  // an empty stand-in source for the file, for findings about it
};

class Machine {
 public:
  Machine(SourceManager& sources, FileReader& reader) : sources_(sources), reader_(reader) {}

  /// Loads and parses a file once; nullptr if it does not exist or cannot be read (see problems()).
  const FileUnit* load(std::string_view sd_path);
  const FileUnit& unit(uint32_t i) const { return *units_[i]; }
  size_t unit_count() const { return units_.size(); }
  const std::vector<LoadProblem>& problems() const { return problems_; }
  FileReader& reader() { return reader_; }
  /// Threads a large file's parse may use, in parts of at least `part_bytes` (ParseOptions).
  void set_threads(unsigned n, size_t part_bytes) {
    threads_ = n;
    part_bytes_ = part_bytes;
  }
  /// Tests only: parse with every prefilter off (ParseOptions::no_prefilters).
  void set_no_prefilters(bool off) { no_prefilters_ = off; }
  /// Records the files the reader lists, so rules can ask whether a file exists without reading it.
  void set_listing(const std::vector<std::string>& sd_paths);
  /// Does the SD card hold this file (case-insensitive)? Looks in the listing and in what was loaded.
  bool has_file(std::string_view sd_path) const;
  /// Does the SD card hold any file below this folder? (A repository often keeps only sys/.)
  bool has_dir(std::string_view sd_dir) const;
  /// Does any loaded file use this code (no fraction)? Answered once per code for the machine.
  bool uses_code(char letter, int32_t number) const;

 private:
  SourceManager& sources_;
  FileReader& reader_;
  void add_problem(std::string_view sd_path, const std::string& display, std::string message);
  std::vector<std::unique_ptr<FileUnit>> units_;
  std::map<std::string, int32_t> by_path_;  // lower-cased SD path -> unit index, or -1 when missing
  std::vector<LoadProblem> problems_;
  unsigned threads_ = 1;
  size_t part_bytes_ = 0;
  bool no_prefilters_ = false;
  std::map<std::string, bool> listing_;                                            // lower-cased SD paths
  mutable std::map<std::pair<char, int32_t>, std::pair<size_t, bool>> code_uses_;  // code -> (units seen, used)
  mutable std::mutex code_uses_mutex_;  // file rules run on several threads (LintOptions::threads)
};

}  // namespace rrflint
