// Text positions as LSP counts them, and file URIs (text.h).
#include "cli/server/text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace rrflint::server {

size_t utf8_step(std::string_view s, size_t i, uint32_t& units) {
  const auto c = static_cast<unsigned char>(s[i]);
  units = 1;
  size_t len = 1;
  uint32_t min = 0;
  if (c >= 0xC2 && c <= 0xDF) len = 2, min = 0x80;
  else if (c >= 0xE0 && c <= 0xEF) len = 3, min = 0x800;
  else if (c >= 0xF0 && c <= 0xF4) len = 4, min = 0x10000;
  else return 1;  // ASCII, or a byte that starts no sequence
  if (i + len > s.size()) return 1;
  uint32_t cp = c & (0x7F >> len);
  for (size_t k = 1; k < len; ++k) {
    const auto b = static_cast<unsigned char>(s[i + k]);
    if ((b & 0xC0) != 0x80) return 1;
    cp = (cp << 6) | (b & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 1;
  units = cp >= 0x10000 ? 2 : 1;
  return len;
}

uint32_t utf16_length(std::string_view s) { return utf16_before(s, s.size(), false); }

namespace {
// Counts on from byte `i` of `s` (a character's start), `n` UTF-16 units before it, to byte `off`; leaves `i` where
// the count stopped (a character's start).
uint32_t utf16_count(std::string_view s, size_t& i, uint32_t n, size_t off, bool round_up) {
  uint32_t units = 0;
  while (i < off && i < s.size()) {
    const size_t len = utf8_step(s, i, units);
    if (i + len > off && !round_up) break;  // `off` falls inside this character: its start
    i += len;
    n += units;
  }
  return n;
}
}  // namespace

uint32_t utf16_before(std::string_view s, size_t off, bool round_up) {
  size_t i = 0;
  return utf16_count(s, i, 0, off, round_up);
}

nlohmann::json range_json(const SourceFile& f, Span s) {
  // A range that starts or ends inside a character covers it, so that it never comes out backwards.
  auto pos = [&](uint32_t off, bool round_up) {
    off = std::min(off, f.size());
    const uint32_t line = f.line_of(off);
    const Span text = f.line_span(line);
    // Past the line's text: after its whole terminator is the next line's start (at the end of a file that ends
    // with one, a line the line index does not hold: "X\n" ends at (1, 0), never (0, 2), which an editor would
    // take back to (0, 1) and so leave the newline out of an edit); between a CR and its LF, the end of the line.
    if (off > text.end) {
      if (off >= text.end + f.terminator(line).size()) return nlohmann::json{{"line", line + 1}, {"character", 0}};
      off = text.end;
    }
    // ASCII: a byte is a UTF-16 unit. Otherwise each thread counts on from where its last count on the same line
    // stopped (a long line of many findings is not walked once per finding), as SourceFile::position does.
    uint32_t ch = off - text.begin;
    if (f.any_high()) {
      thread_local struct {
        uint64_t serial = 0;
        uint32_t line = 0, byte = 0, units = 0;
      } last;
      size_t i = 0;
      uint32_t n = 0;
      if (last.serial == f.serial() && last.line == line && last.byte <= off - text.begin) {
        i = last.byte;
        n = last.units;
      }
      ch = utf16_count(f.slice(text), i, n, off - text.begin, round_up);
      last = {f.serial(), line, static_cast<uint32_t>(i), ch};
    }
    return nlohmann::json{{"line", line}, {"character", ch}};
  };
  return {{"start", pos(s.begin, false)}, {"end", pos(std::max(s.begin, s.end), true)}};
}

size_t offset_of(std::string_view text, Position p) {
  size_t i = 0;
  for (uint32_t line = 0; line < p.line; ++line) {
    const size_t e = text.find_first_of("\r\n", i);
    if (e == std::string_view::npos) return text.size();
    i = e + (text[e] == '\r' && e + 1 < text.size() && text[e + 1] == '\n' ? 2 : 1);
  }
  uint32_t col = 0, units = 0;
  while (i < text.size() && col < p.character && text[i] != '\n' && text[i] != '\r') {
    const size_t step = utf8_step(text, i, units);
    col += units;
    i += step;
  }
  return i;
}

void apply_change(std::string& text, Position start, Position end, std::string_view replacement) {
  const size_t b = offset_of(text, start);
  const size_t e = std::max(b, offset_of(text, end));
  text.replace(b, e - b, replacement);
}

std::optional<std::string> path_of_uri(std::string_view uri) {
  constexpr std::string_view kScheme = "file://";
  if (uri.size() < kScheme.size()) return std::nullopt;
  for (size_t k = 0; k < kScheme.size(); ++k)
    if (std::tolower(static_cast<unsigned char>(uri[k])) != kScheme[k]) return std::nullopt;
  uri.remove_prefix(kScheme.size());
  if (uri.starts_with("localhost/")) uri.remove_prefix(9);
  if (!uri.starts_with('/')) return std::nullopt;  // another host, or not absolute
  uri = uri.substr(0, uri.find_first_of("?#"));
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += static_cast<char>(std::stoi(std::string(uri.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  if (out.find('\0') != std::string::npos) return std::nullopt;
  return out;
}

std::string uri_of_path(std::string_view path) {
  std::string out = "file://";
  for (unsigned char c : path) {
    if (std::isalnum(c) || std::string_view("-._~/!$&'()*+,;=:@").find(static_cast<char>(c)) != std::string_view::npos)
      out += static_cast<char>(c);
    else out += fmt::format("%{:02X}", c);
  }
  return out;
}

}  // namespace rrflint::server
