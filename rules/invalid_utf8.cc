// RRF119 invalid-utf8: bytes that are not UTF-8 (a Latin-1 '°', a Windows-1252 quote), once per file.
#include <fmt/format.h>

#include <cstdint>
#include <cstring>

#include "lint/engine/rule.h"

namespace rrflint {
namespace {

constexpr RuleMeta kMeta{
    .code = "RRF119",
    .name = "invalid-utf8",
    .severity = Severity::Warning,
    .summary = "The file holds bytes that are not valid UTF-8, usually text saved as Latin-1 or Windows-1252.",
    .docs = R"md(
## What it does
Reports a file that is not valid UTF-8, once, at its first bad byte; the message says how many lines hold such
bytes and whether they are all in comments. Typical causes are a `°` or `ä` saved by an old editor as Latin-1 or
Windows-1252 (one byte, 0xB0 or 0xE4), or "smart quotes" pasted from a word processor. Valid multi-byte UTF-8
(`M550 P"Drucker ä"`) is fine and not reported.

## Why is this bad?
RepRapFirmware does not convert text: it stores the bytes of a string as they are. Messages, names and file
names made from them (`M291`, `M117`, `M550`, `echo`) then show garbage, and Duet Web Control, which expects
UTF-8 in the object model and in files, may show replacement characters or fail to show the message at all. In
comments the bytes are harmless to RRF, but the editor in DWC shows them garbled and may save them back changed.

## Example
A config.g saved as Latin-1 by an old editor: the `°` in `M291 P"Bed at 60°C" S1` is the single byte 0xB0
there, which is not UTF-8.

## Use instead
Save the file as UTF-8 (`°` is then the two bytes C2 B0), or keep strings to ASCII:
```gcode
M291 P"Bed at 60 C" S1
```

## References
- rrflint: [Strings](../firmware-behaviour.md#strings)
- https://github.com/Duet3D/RepRapFirmware/blob/3.6-dev/src/GCodes/GCodeBuffer/StringParser.cpp
  (`InternalGetQuotedString()` copies each byte of a string as it is)
- https://docs.duet3d.com/User_manual/Reference/Gcodes (strings and encodings)
)md",
};

// The length of the valid UTF-8 sequence at `p`, or 0 when the byte there starts none (overlong forms,
// surrogates and code points above U+10FFFF are invalid).
size_t utf8_length(std::string_view t, size_t p) {
  const auto b = [&](size_t k) { return p + k < t.size() ? static_cast<unsigned char>(t[p + k]) : 0u; };
  const unsigned c = b(0);
  const auto cont = [&](size_t k) { return (b(k) & 0xC0) == 0x80; };
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(1) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    const unsigned lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    return b(1) >= lo && b(1) <= hi && cont(2) ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    const unsigned lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    return b(1) >= lo && b(1) <= hi && cont(2) && cont(3) ? 4 : 0;
  }
  return 0;
}

// Is offset `k` of line `li` inside a comment (or on a comment-only line)? Lines map one to one to the parse's
// lines only without NUL bytes; otherwise the answer is no.
bool in_comment(const FileContext& cx, uint32_t li, uint32_t k) {
  const ParsedFile& pf = cx.parsed();
  if (cx.source().any_nul() || li >= pf.lines.size()) return false;
  const Line& line = pf.lines[li];
  if (line.kind == LineKind::Comment || (line.kind == LineKind::Blank && !line.comment.empty())) return true;
  return !line.comment.empty() && k >= line.comment.begin;
}

void check(const FileContext& cx, Sink& out) {
  const SourceFile& src = cx.source();
  if (!src.any_high()) return;  // ASCII only
  const std::string_view t = src.text();
  uint32_t first = UINT32_MAX, lines = 0, last_line = UINT32_MAX;
  bool only_comments = true;
  for (size_t p = 0; p < t.size();) {
    if (static_cast<unsigned char>(t[p]) < 0x80) {
      ++p;
      // Runs of ASCII eight bytes at a time (the file is mostly ASCII; a byte at a time took 70 ms for 100 MB).
      for (uint64_t w; p + 8 <= t.size(); p += 8) {
        std::memcpy(&w, t.data() + p, 8);
        if (w & 0x8080808080808080ull) break;
      }
      continue;
    }
    const size_t n = utf8_length(t, p);
    if (n) {
      p += n;
      continue;
    }
    const auto k = static_cast<uint32_t>(p);
    const uint32_t li = src.line_of(k);
    if (first == UINT32_MAX) first = k;
    if (li != last_line) {
      ++lines;
      last_line = li;
      only_comments = only_comments && in_comment(cx, li, k);
    }
    ++p;
  }
  if (first == UINT32_MAX) return;
  out.report(kMeta, cx.at(Span{first, first + 1}),
             fmt::format("byte 0x{:02X} is not valid UTF-8 ({} line{} of the file hold{} such bytes{}): RRF stores the "
                         "bytes as they are, so strings and messages show garbage and DWC may fail to show them; save "
                         "the file as UTF-8",
                         static_cast<unsigned char>(t[first]), lines, lines == 1 ? "" : "s", lines == 1 ? "s" : "",
                         only_comments ? ", all in comments" : ""));
}

}  // namespace

extern const Rule invalid_utf8{.meta = kMeta, .check_file = check};

}  // namespace rrflint
