#include <set>

#include "render.h"

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

Range range_of(const SourceManager& sm, const Location& loc) {
  if (loc.file == kNoFile) return {};
  const SourceFile& f = sm.get(loc.file);
  return Range{f.position(loc.span.begin), f.position(loc.span.end)};
}

std::string sanitize(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  size_t i = 0;
  while (i < s.size()) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    size_t len = 1;
    if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c >= 0xE0 && c <= 0xEF) len = 3;
    else if (c >= 0xF0 && c <= 0xF4) len = 4;
    else if (c >= 0x80) len = 0;  // invalid lead byte
    bool ok = len > 0 && i + len <= s.size();
    for (size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
    if (!ok) {
      out += "\xEF\xBF\xBD";
      ++i;
      continue;
    }
    if (len == 1 && (c < 0x20 || c == 0x7F) && c != '\t') {
      out += "\xEF\xBF\xBD";
    } else {
      out.append(s.substr(i, len));
    }
    i += len;
  }
  return out;
}

}  // namespace rrflint
