#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <set>

#include "lint/base/bytes8.h"
#include "lint/render/render.h"

namespace rrflint {

Counts count(const std::vector<Diagnostic>& diags) {
  Counts c;
  std::set<FileId> files;
  for (const Diagnostic& d : diags) {
    files.insert(d.loc.file);
    if (d.severity == Severity::Error) ++c.errors;
    else if (d.severity == Severity::Warning) ++c.warnings;
    else ++c.infos;
    if (d.fix && d.fix->applicability == Applicability::Safe) ++c.fixable;
    if (d.fix && d.fix->applicability == Applicability::Unsafe) ++c.unsafe_fixable;
  }
  c.files = files.size();
  return c;
}

namespace {
std::string plural(size_t n, std::string_view w) { return fmt::format("{} {}{}", n, w, n == 1 ? "" : "s"); }
}  // namespace

std::string summary_line(const Counts& c) {
  return fmt::format("{}, {}, {} in {}", plural(c.errors, "error"), plural(c.warnings, "warning"),
                     plural(c.infos, "info"), plural(c.files, "file"));
}

std::string no_problems_line(size_t files_checked) {
  return files_checked ? fmt::format("No problems found in {}", plural(files_checked, "file")) : "No problems found";
}

void render_report_as(std::string_view format, std::ostream& os, const SourceManager& sm,
                      const std::vector<Diagnostic>& diags, const RenderOptions& o) {
  if (format == "json") render_json(os, sm, diags, o);
  else if (format == "json-lines") render_json_lines(os, sm, diags, o);
  else if (format == "sarif") render_sarif(os, sm, diags, o);
  else if (format == "github") render_github(os, sm, diags, o);
  else if (format == "gitlab") render_gitlab(os, sm, diags, o);
  else if (format == "concise") render_concise(os, sm, diags, o);
  else render_text(os, sm, diags, o);
}

Range range_of(const SourceManager& sm, const Location& loc) {
  if (loc.file == kNoFile) return {};
  const SourceFile& f = sm.get(loc.file);
  return Range{f.position(loc.span.begin), f.position(std::max(loc.span.begin, loc.span.end), true)};
}

namespace {

// Do the 8 bytes at p hold printable ASCII only (0x20-0x7E)? Most of every message and path does, so they are
// copied as they are, a word at a time.
bool plain_ascii8(const char* p) {
  const uint64_t x = bytes8::load(p);
  return !bytes8::any_high(x) && !bytes8::any_below(x, 0x20) && !bytes8::any_equal(x, 0x7F);
}

std::string replace_invalid(std::string_view s, bool keep_controls) {
  std::string out;
  out.reserve(s.size());
  size_t run = 0;  // the bytes [run, i) are copied as they are
  size_t i = 0;
  while (i < s.size()) {
    if (i + 8 <= s.size() && plain_ascii8(s.data() + i)) {
      i += 8;
      continue;
    }
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7F) {
      ++i;
      continue;
    }
    size_t len = 1;
    if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c >= 0xE0 && c <= 0xEF) len = 3;
    else if (c >= 0xF0 && c <= 0xF4) len = 4;
    else if (c >= 0x80) len = 0;  // invalid lead byte
    bool ok = len > 0 && i + len <= s.size();
    for (size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
    if (ok && len > 2) {  // no overlong forms, surrogates or code points above U+10FFFF: strictly valid UTF-8
      const unsigned char c1 = static_cast<unsigned char>(s[i + 1]);
      ok = !(c == 0xE0 && c1 < 0xA0) && !(c == 0xED && c1 > 0x9F) && !(c == 0xF0 && c1 < 0x90) &&
           !(c == 0xF4 && c1 > 0x8F);
    }
    // An invalid byte, and a control byte other than a tab unless kept, become U+FFFD, one byte at a time.
    if (ok && !(len == 1 && c != '\t' && !keep_controls)) {
      i += len;
      continue;
    }
    out.append(s, run, i - run);
    out += "\xEF\xBF\xBD";
    run = ++i;
  }
  out.append(s, run, s.size() - run);
  return out;
}

}  // namespace

std::string sanitize(std::string_view s) { return replace_invalid(s, false); }
std::string valid_utf8(std::string_view s) { return replace_invalid(s, true); }

std::string rule_url(std::string_view docs_base, std::string_view name) {
  std::string url = docs_base.empty() ? std::string("docs/rules/") : std::string(docs_base);
  if (!url.ends_with('/')) url += '/';
  return url + std::string(name) + ".md";
}

bool is_web_url(std::string_view url) {
  auto lower = [&](size_t n) {
    std::string s(url.substr(0, n));
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  return lower(7) == "http://" || lower(8) == "https://";
}

std::optional<FixPreview> fix_preview(const SourceManager& sm, const Fix& fix) {
  if (fix.edits.empty() || fix.edits.front().loc.file == kNoFile) return std::nullopt;
  const FileId file = fix.edits.front().loc.file;
  std::vector<Edit> edits;
  for (const Edit& e : fix.edits)
    if (e.loc.file == file) edits.push_back(e);
  std::sort(edits.begin(), edits.end(),
            [](const Edit& a, const Edit& b) { return a.loc.span.begin < b.loc.span.begin; });
  const SourceFile& f = sm.get(file);
  if (f.line_count() == 0) return std::nullopt;
  const uint32_t line0 = f.line_of(std::min(edits.front().loc.span.begin, f.size()));
  const Span ls = f.line_span(line0);
  // The line with its terminator, plus the whole lines (with their terminators) that the edits starting on it, or on
  // a line taken in so far, reach into: an insertion at the next line's start takes in that line.
  auto through_line_of = [&](uint32_t off) {
    const uint32_t l = f.line_of(std::min(off, f.size()));
    return f.line_span(l).end + static_cast<uint32_t>(f.terminator(l).size());
  };
  uint32_t end = ls.end + static_cast<uint32_t>(f.terminator(line0).size());
  for (const Edit& e : edits) {
    const Span s = e.loc.span;
    if (s.begin > end || s.end < s.begin) continue;
    end = std::max(end, through_line_of(s.end > s.begin ? s.end - 1 : s.begin));
  }
  std::string region(f.text().substr(ls.begin, end - ls.begin));
  // Apply back to front so earlier offsets stay valid.
  for (auto it = edits.rbegin(); it != edits.rend(); ++it) {
    const Span s = it->loc.span;
    if (s.begin < ls.begin || s.begin > end || s.end > end || s.end < s.begin) continue;
    region.replace(s.begin - ls.begin, s.end - s.begin, it->replacement);
  }
  FixPreview p;
  p.line = line0 + 1;
  if (region.empty()) {
    p.removed = true;
    return p;
  }
  // Split at LF, CRLF and lone CR; the piece after the region's last terminator is not a line.
  size_t at = 0;
  while (at < region.size()) {
    const size_t nl = region.find_first_of("\r\n", at);
    p.lines.push_back(region.substr(at, nl == std::string::npos ? std::string::npos : nl - at));
    if (nl == std::string::npos) break;
    at = nl + (region[nl] == '\r' && nl + 1 < region.size() && region[nl + 1] == '\n' ? 2 : 1);
  }
  return p;
}

}  // namespace rrflint
