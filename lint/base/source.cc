#include "lint/base/source.h"

#include <algorithm>
#include <atomic>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "lint/base/huge_pages.h"
#include "lint/base/parallel.h"

namespace rrflint {

namespace {

// What a scan of the text met besides LFs.
enum : unsigned { kSawCr = 1, kSawNul = 2, kSawDel = 4, kSawHigh = 8 };

unsigned saw(char c) {
  return c == '\r'                               ? kSawCr
         : c == '\0'                             ? kSawNul
         : c == 0x7f                             ? kSawDel
         : static_cast<unsigned char>(c) >= 0x80 ? kSawHigh
                                                 : 0u;
}

// Appends the start of every line after an LF in [b, e) to `out`; returns the kSaw* bits of the other bytes met
// (one pass over the text for the line index and the parser's NUL and DEL tests).
unsigned index_lf(const char* base, size_t b, size_t e, std::vector<uint32_t>& out) {
  size_t i = b;
  unsigned seen = 0;
#if defined(__SSE2__)
  const __m128i nl = _mm_set1_epi8('\n'), cr = _mm_set1_epi8('\r'), nul = _mm_setzero_si128(),
                del = _mm_set1_epi8(0x7f);
  for (; i + 16 <= e; i += 16) {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(base + i));
    const __m128i other =
        _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(v, cr), _mm_cmpeq_epi8(v, nul)), _mm_cmpeq_epi8(v, del));
    if (_mm_movemask_epi8(other))
      for (size_t k = 0; k < 16; ++k) seen |= saw(base[i + k]);
    if (_mm_movemask_epi8(v)) seen |= kSawHigh;  // a byte of 0x80 or more
    for (auto mask = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, nl))); mask; mask &= mask - 1)
      out.push_back(static_cast<uint32_t>(i + static_cast<unsigned>(__builtin_ctz(mask)) + 1));
  }
#endif
  for (; i < e; ++i) {
    if (base[i] == '\n') out.push_back(static_cast<uint32_t>(i + 1));
    else seen |= saw(base[i]);
  }
  return seen;
}

}  // namespace

TextBuffer::TextBuffer(std::string s) : size_(s.size()) {
  if (s.empty()) return;
  auto owner = std::make_shared<const std::string>(std::move(s));
  bytes_ = std::shared_ptr<const char>(owner, owner->data());
}

TextBuffer TextBuffer::mapped(const char* data, size_t size) {
  TextBuffer b;
  b.bytes_ = std::shared_ptr<const char>(data, [size](const char* p) { unmap_bytes(p, size); });
  b.size_ = size;
  b.mapped_ = true;
  return b;
}

SourceFile::SourceFile(FileId id, std::string display, std::string sd_path, TextBuffer bytes, unsigned threads)
    : id_(id), display_(std::move(display)), sd_path_(std::move(sd_path)), bytes_(std::move(bytes)) {
  static std::atomic<uint64_t> serials{0};
  serial_ = ++serials;
  const char* base = bytes_.data();
  const size_t n = bytes_.size();
  reserve_huge(line_starts_, n / 16 + 1);  // untouched pages cost nothing; a reallocation would copy
  line_starts_.push_back(0);
  // LF only (the usual case): 16 bytes at a time (a memchr call per line costs more on ~30-byte lines); a large
  // file in parts on several threads, the later parts' starts appended in order. A CR met on the way sends the
  // file to the general scan below.
  const size_t parts = threads > 1 ? threads : 1;
  std::vector<std::vector<uint32_t>> later(parts - 1);
  std::vector<unsigned> seen(parts, 0);
  run_tasks(parts, static_cast<unsigned>(parts), [&](size_t j) {
    std::vector<uint32_t>& out = j == 0 ? line_starts_ : later[j - 1];
    if (j > 0) reserve_huge(out, n / parts / 16 + 1);
    seen[j] = index_lf(base, n * j / parts, n * (j + 1) / parts, out);
  });
  unsigned all = 0;
  for (unsigned s : seen) all |= s;
  any_nul_ = (all & kSawNul) != 0;
  any_del_ = (all & kSawDel) != 0;
  any_high_ = (all & kSawHigh) != 0;
  if (!(all & kSawCr)) {
    for (const std::vector<uint32_t>& v : later) line_starts_.insert(line_starts_.end(), v.begin(), v.end());
    endings_.lf = static_cast<uint32_t>(line_starts_.size() - 1);
  } else {
    line_starts_.resize(1);
    for (size_t i = 0; i < n; ++i) {
      const char c = base[i];
      if (c == '\n') {
        line_starts_.push_back(static_cast<uint32_t>(i + 1));
        ++endings_.lf;
      } else if (c == '\r') {
        if (i + 1 < n && base[i + 1] == '\n') {
          ++i;
          ++endings_.crlf;
        } else {
          ++endings_.cr;
        }
        line_starts_.push_back(static_cast<uint32_t>(i + 1));
      }
    }
  }
  // A final terminator does not start another (empty) line.
  if (line_starts_.size() > 1 && line_starts_.back() == n) line_starts_.pop_back();
}

uint32_t SourceFile::line_of(uint32_t offset) const {
  auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  return static_cast<uint32_t>(it - line_starts_.begin()) - 1;
}

std::string_view SourceFile::terminator(uint32_t line0) const {
  uint32_t e = line_end(line0);
  uint32_t next = line0 + 1 < line_starts_.size() ? line_starts_[line0 + 1] : size();
  return std::string_view(bytes_).substr(e, next - e);
}

std::string_view SourceFile::usual_ending() const {
  const LineEndings& e = endings_;
  if (e.crlf > e.lf && e.crlf >= e.cr) return "\r\n";
  if (e.cr > e.lf && e.cr > e.crlf) return "\r";
  return "\n";
}

std::string_view SourceFile::line_ending(uint32_t line0) const {
  const std::string_view t = terminator(line0);
  return t.empty() ? usual_ending() : t;
}

namespace {
size_t code_point_length(std::string_view s, size_t i);
}  // namespace

LineCol SourceFile::position(uint32_t offset, bool round_up) const {
  offset = std::min(offset, size());
  uint32_t line0 = line_of(offset);
  uint32_t start = line_starts_[line0];
  const uint32_t line_e = line_end(line0);
  uint32_t end = std::min(offset, line_e);
  uint32_t col = 1;
  if (!any_high_) {
    col += end - start;  // ASCII: one byte, one column
  } else {
    // Findings are rendered in order, many of them on one line (a long line of many commands): each thread
    // remembers where its last count on a line stopped and counts on from there, so that the columns of a line's
    // findings cost the line's length once, not once per finding.
    thread_local struct {
      uint64_t serial = 0;
      uint32_t line0 = 0, byte = 0, count = 0;  // `count` code points before `byte`, a code point's start
    } last;
    const std::string_view s = std::string_view(bytes_).substr(start, line_e - start);
    size_t i = 0;
    uint32_t count = 0;
    if (last.serial == serial_ && last.line0 == line0 && last.byte <= end - start) {
      i = last.byte;
      count = last.count;
    }
    const size_t off = end - start;
    while (i < off && i < s.size()) {
      const size_t len = code_point_length(s, i);
      if (i + len > off && !round_up) break;  // `off` falls inside this code point: its start
      i += len;
      ++count;
    }
    last = {serial_, line0, static_cast<uint32_t>(i), count};
    col += count;
  }
  if (offset > line_e) col += 1;  // inside the terminator: one past the line end
  return LineCol{line0 + 1, col};
}

namespace {
// The length of the code point that starts at s[i]: 1 for an ASCII byte or a byte that starts no whole sequence.
size_t code_point_length(std::string_view s, size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  size_t len = 1;
  if (c >= 0xC2 && c <= 0xDF) len = 2;
  else if (c >= 0xE0 && c <= 0xEF) len = 3;
  else if (c >= 0xF0 && c <= 0xF4) len = 4;
  if (len == 1 || i + len > s.size()) return 1;
  for (size_t k = 1; k < len; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 1;
  return len;
}
}  // namespace

size_t code_point_floor(std::string_view s, size_t off) {
  // Found near `off`, not by walking from the start (a snippet on a long line asks once per finding): every byte
  // that is not a continuation byte (10xxxxxx) starts a code point, and a code point is at most 4 bytes long, so
  // the walk starts at the nearest such byte at most 3 bytes back; with none there, `off` starts its own.
  if (off >= s.size()) return s.size();
  auto continuation = [&](size_t k) { return (static_cast<unsigned char>(s[k]) & 0xC0) == 0x80; };
  size_t i = off;
  while (i > 0 && off - i < 3 && continuation(i)) --i;
  if (continuation(i)) return off;
  while (true) {
    const size_t next = i + code_point_length(s, i);
    if (next > off) return i;
    i = next;
  }
}

size_t code_point_ceil(std::string_view s, size_t off) {
  const size_t f = code_point_floor(s, off);
  return f == off || f >= s.size() ? std::min(off, s.size()) : f + code_point_length(s, f);
}

uint32_t count_code_points(std::string_view s) { return code_points_before(s, s.size(), false); }

uint32_t code_points_before(std::string_view s, size_t off, bool round_up) {
  uint32_t count = 0;
  for (size_t i = 0; i < off && i < s.size();) {
    const size_t len = code_point_length(s, i);
    if (i + len > off && !round_up) break;  // `off` falls inside this code point: its start
    i += len;
    ++count;
  }
  return count;
}

FileId SourceManager::adopt(SourceManager& other) {
  const auto base = static_cast<FileId>(files_.size());
  for (auto& f : other.files_) {
    f->renumber(static_cast<FileId>(files_.size()));
    files_.push_back(std::move(f));
  }
  other.files_.clear();
  return base;
}

const SourceFile& SourceManager::add(std::string display, std::string sd_path, TextBuffer bytes, unsigned threads) {
  auto id = static_cast<FileId>(files_.size());
  files_.push_back(std::make_unique<SourceFile>(id, std::move(display), std::move(sd_path), std::move(bytes), threads));
  return *files_.back();
}

}  // namespace rrflint
