// Source files: one immutable byte buffer per file, byte spans into it, and a line index built once.
//
// Everything downstream (tokens, parameters, diagnostics, fixes) holds Spans into a SourceFile's buffer.
// Line and column are computed only when something is rendered.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace rrflint {

using FileId = uint32_t;
inline constexpr FileId kNoFile = UINT32_MAX;

/// A half-open byte range [begin, end) into one file's buffer.
struct Span {
  uint32_t begin = 0;
  uint32_t end = 0;
  constexpr uint32_t size() const { return end - begin; }
  constexpr bool empty() const { return begin == end; }
  constexpr bool contains(uint32_t off) const { return off >= begin && off < end; }
  friend constexpr bool operator==(Span, Span) = default;
};

/// Does span `s` of `t` hold the byte `c`? Rules ask this of millions of short spans (a line's code, a command):
/// 16 bytes at a time inline, where a memchr call would cost more than the scan. Reads stay inside `t`.
inline bool span_has(std::string_view t, Span s, char c) {
#if defined(__SSE2__)
  const __m128i needle = _mm_set1_epi8(c);
  uint32_t k = s.begin;
  for (; k < s.end && size_t{k} + 16 <= t.size(); k += 16) {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(t.data() + k));
    auto mask = static_cast<uint32_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, needle)));
    if (s.end - k < 16) mask &= (1u << (s.end - k)) - 1;
    if (mask) return true;
  }
  for (; k < s.end; ++k)
    if (t[k] == c) return true;
  return false;
#else
  return t.substr(s.begin, s.size()).find(c) != std::string_view::npos;
#endif
}

/// 1-based line; 1-based column counted in Unicode code points (an invalid UTF-8 byte counts as one).
struct LineCol {
  uint32_t line = 1;
  uint32_t column = 1;
};

/// How the file ends its lines. RRF reads a file with only CR line endings as one line (3.4.6+/3.5.0b2+).
struct LineEndings {
  uint32_t lf = 0;    // bare "\n"
  uint32_t crlf = 0;  // "\r\n"
  uint32_t cr = 0;    // lone "\r"
  bool cr_only() const { return cr > 0 && lf == 0 && crlf == 0; }
};

/// A file's bytes: a string, or a read-only mapping of the file (large files, DiskReader). The bytes never change,
/// and copies share them.
class TextBuffer {
 public:
  TextBuffer() = default;
  TextBuffer(std::string s);                                 // NOLINT: implicit, as bytes were strings before
  TextBuffer(const char* s) : TextBuffer(std::string(s)) {}  // NOLINT
  /// Takes over `size` bytes mapped at `data`; unmapped when the last copy goes.
  static TextBuffer mapped(const char* data, size_t size);
  const char* data() const { return bytes_ ? bytes_.get() : ""; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  char operator[](size_t i) const { return data()[i]; }
  operator std::string_view() const { return {data(), size()}; }  // NOLINT
  bool is_mapped() const { return mapped_; }

 private:
  // Shared: a 100 MB standard input that the job, the reader's overlay and the source file all hold is in memory
  // once.
  std::shared_ptr<const char> bytes_;
  size_t size_ = 0;
  bool mapped_ = false;
};

class SourceFile {
 public:
  /// `display` is the path shown to users; `sd_path` the path on the SD card ("/sys/config.g"), or empty.
  /// `threads` > 1 builds the line index of a large file in that many parts at once.
  SourceFile(FileId id, std::string display, std::string sd_path, TextBuffer bytes, unsigned threads = 1);

  FileId id() const { return id_; }
  void renumber(FileId id) { id_ = id; }  // SourceManager::adopt only
  const std::string& display_path() const { return display_; }
  const std::string& sd_path() const { return sd_path_; }
  std::string_view text() const { return bytes_; }
  std::string_view slice(Span s) const { return std::string_view(bytes_).substr(s.begin, s.size()); }
  uint32_t size() const { return static_cast<uint32_t>(bytes_.size()); }

  /// Lines as an editor shows them: split at LF, CRLF and lone CR. Line spans exclude the terminator.
  uint32_t line_count() const { return static_cast<uint32_t>(line_starts_.size()); }
  Span line_span(uint32_t line0) const;
  uint32_t line_of(uint32_t offset) const;  // 0-based
  /// The 1-based line and column (in code points) of a byte offset. An offset inside a code point is that code
  /// point's column, or with `round_up` the next one (as the end of a range, so that the range covers it): a range
  /// that starts or ends inside a character never comes out backwards.
  LineCol position(uint32_t offset, bool round_up = false) const;
  const LineEndings& endings() const { return endings_; }
  /// Whether the buffer holds a NUL byte / a DEL (0x7f) byte: found by the line index's scan, so that the parser
  /// needs no pass of its own over the text.
  bool any_nul() const { return any_nul_; }
  bool any_del() const { return any_del_; }
  /// Whether the buffer holds a byte of 0x80 or more (anything but ASCII), found by the same scan.
  bool any_high() const { return any_high_; }
  /// Unique per file of the run: keys a per-thread memory of a count on one of its lines (position()'s).
  uint64_t serial() const { return serial_; }
  /// The terminator after line `line0` ("\n", "\r\n", "\r" or "" at end of file).
  std::string_view terminator(uint32_t line0) const;
  /// The line ending most of the file's lines have ("\n" on a tie with it, and in a file of one line): what "\n" in
  /// a fix's text becomes.
  std::string_view usual_ending() const;
  /// What a fix writes to start a line after line `line0`: its terminator, or where it has none (the last line) the
  /// usual ending.
  std::string_view line_ending(uint32_t line0) const;

 private:
  FileId id_;
  std::string display_;
  std::string sd_path_;
  TextBuffer bytes_;
  uint32_t line_end(uint32_t line0) const;  // from the next line's start: the index keeps starts only
  std::vector<uint32_t> line_starts_;
  LineEndings endings_;
  bool any_nul_ = false, any_del_ = false, any_high_ = false;
  uint64_t serial_;
};

inline uint32_t SourceFile::line_end(uint32_t line0) const {
  const uint32_t start = line_starts_[line0];
  // The next line's start, or the end of the file; then back over the terminator, if any.
  uint32_t e = line0 + 1 < line_starts_.size() ? line_starts_[line0 + 1] : size();
  if (e > start && bytes_[e - 1] == '\n') {
    --e;
    if (e > start && bytes_[e - 1] == '\r') --e;
  } else if (e > start && bytes_[e - 1] == '\r') {
    --e;
  }
  return e;
}

inline Span SourceFile::line_span(uint32_t line0) const { return Span{line_starts_[line0], line_end(line0)}; }

/// Counts code points in `s` the way columns are reported (invalid bytes count one each).
uint32_t count_code_points(std::string_view s);
/// The code points of `s` before byte `off`; one that `off` falls inside is counted only with `round_up`.
uint32_t code_points_before(std::string_view s, size_t off, bool round_up);
/// The start of the code point of `s` that byte `off` falls inside (`off` itself at a boundary), and its end.
size_t code_point_floor(std::string_view s, size_t off);
size_t code_point_ceil(std::string_view s, size_t off);

/// Owns every SourceFile of one run. FileIds index into it.
class SourceManager {
 public:
  const SourceFile& add(std::string display, std::string sd_path, TextBuffer bytes, unsigned threads = 1);
  const SourceFile& get(FileId id) const { return *files_[id]; }
  size_t size() const { return files_.size(); }
  /// Moves every file of `other` to the end of this manager (the SourceFile objects stay where they are) and
  /// returns how much their ids grew. Lets several machines be linted apart, each with its own manager.
  FileId adopt(SourceManager& other);

 private:
  std::vector<std::unique_ptr<SourceFile>> files_;
};

}  // namespace rrflint
