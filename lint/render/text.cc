// `text`: file:line:col, severity, code and name, message; the source line with carets; notes with their
// own location and snippet; a help line for the fix; a summary and links to the rules seen.
#include <fmt/format.h>

#include <map>

#include "lint/engine/rule.h"
#include "lint/render/render.h"

namespace rrflint {
namespace {

struct Style {
  bool on;
  std::string operator()(std::string_view s, std::string_view code) const {
    return on ? fmt::format("\x1b[{}m{}\x1b[0m", code, s) : std::string(s);
  }
};

std::string_view sev_color(Severity s) {
  switch (s) {
    case Severity::Error: return "1;31";
    case Severity::Warning: return "1;33";
    case Severity::Info: return "1;36";
  }
  return "0";
}

// Renders one source line with a marker run under [col_begin, col_end) (1-based code points).
void snippet(std::ostream& os, const SourceManager& sm, const Location& loc, char mark, const Style& st,
             std::string_view color, const std::string& label = "") {
  if (loc.file == kNoFile) return;
  const SourceFile& f = sm.get(loc.file);
  // An empty file has nothing to show (also the stand-in of a file that could not be read).
  if (f.line_count() == 0 || f.size() == 0) return;
  const uint32_t line0 = f.line_of(std::min(loc.span.begin, f.size()));
  const Span ls = f.line_span(line0);
  // Display text: tabs become one blank each so the carets line up; other controls become U+FFFD.
  std::string_view raw = f.slice(ls);
  uint32_t b = std::min(loc.span.begin, ls.end) - ls.begin;
  uint32_t e = std::min(std::max(loc.span.end, loc.span.begin), ls.end) - ls.begin;
  // A span that starts or ends inside a character marks the whole character (its bytes shown apart would each be
  // a U+FFFD), as its columns do (SourceFile::position).
  b = static_cast<uint32_t>(code_point_floor(raw, b));
  e = static_cast<uint32_t>(code_point_ceil(raw, e));
  // Window very long lines around the span.
  uint32_t wb = 0, we = static_cast<uint32_t>(raw.size());
  if (raw.size() > 200) {
    wb = b > 60 ? b - 60 : 0;
    while (wb > 0 && (static_cast<unsigned char>(raw[wb]) & 0xC0) == 0x80) --wb;
    we = std::min<uint32_t>(static_cast<uint32_t>(raw.size()), std::max(e, b + 1) + 60);
    while (we < raw.size() && (static_cast<unsigned char>(raw[we]) & 0xC0) == 0x80) ++we;
    e = std::min(e, we);
  }
  auto display = [&](std::string_view s) {
    std::string t = sanitize(s);
    for (char& c : t)
      if (c == '\t') c = ' ';
    return t;
  };
  std::string prefix = wb > 0 ? "…" : "";
  std::string before = prefix + display(raw.substr(wb, b - wb));
  std::string marked = display(raw.substr(b, e - b));
  std::string text = before + marked + display(raw.substr(e, we - e)) + (we < raw.size() ? "…" : "");
  const std::string num = std::to_string(line0 + 1);
  const std::string pad(num.size(), ' ');
  os << " " << st(num + " |", "1;34") << " " << text << "\n";
  uint32_t lead = count_code_points(before);
  uint32_t width = std::max<uint32_t>(1, count_code_points(marked));
  os << " " << st(pad + " |", "1;34") << " " << std::string(lead, ' ')
     << st(std::string(width, mark) + (label.empty() ? "" : " " + label), color) << "\n";
}

}  // namespace

void render_text(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                 const RenderOptions& o) {
  Style st{o.color};
  std::map<std::string_view, std::string_view> seen;  // code -> name
  for (const Diagnostic& d : diags) {
    const Range r = range_of(sm, d.loc);
    const std::string path = d.loc.file == kNoFile ? "-" : sanitize(sm.get(d.loc.file).display_path());
    os << st(fmt::format("{}:{}:{}:", path, r.start.line, r.start.column), "1") << " "
       << st(severity_name(d.severity), sev_color(d.severity)) << " " << st(fmt::format("{} {}", d.code, d.name), "1")
       << ": " << sanitize(d.message)
       << (d.fix && d.fix->applicability == Applicability::Safe ? st(" [*]", "1;32") : "") << "\n";
    snippet(os, sm, d.loc, '^', st, sev_color(d.severity));
    for (const Note& n : d.notes) {
      if (n.loc.file == kNoFile) {
        os << "  " << st("note:", "1;36") << " " << sanitize(n.message) << "\n";
        continue;
      }
      const Range nr = range_of(sm, n.loc);
      os << "  " << st("note:", "1;36") << " "
         << fmt::format("{}:{}:{}: ", sanitize(sm.get(n.loc.file).display_path()), nr.start.line, nr.start.column)
         << sanitize(n.message) << "\n";
      snippet(os, sm, n.loc, '-', st, "1;36");
    }
    if (d.fix) {
      os << "  " << st("help:", "1;32") << " " << sanitize(d.fix->title)
         << (d.fix->applicability == Applicability::Unsafe ? " (unsafe fix: --unsafe-fixes)" : " (--fix)") << "\n";
      // A preview of the fixed line, diff-style: `+` the line (or the lines it is split into) after the fix, `-` a
      // line it removes. At most kShown lines, then how many more.
      if (auto p = fix_preview(sm, *d.fix)) {
        const SourceFile& f = sm.get(d.fix->edits.front().loc.file);
        std::vector<std::string> shown = p->lines;
        if (p->removed) shown = {std::string(f.slice(f.line_span(p->line - 1)))};
        constexpr size_t kShown = 4;
        for (size_t i = 0; i < shown.size() && i < kShown; ++i) {
          std::string t = sanitize(shown[i]);
          for (char& c : t)
            if (c == '\t') c = ' ';
          if (t.size() > 200) {
            size_t cut = 200;
            while (cut > 0 && (static_cast<unsigned char>(t[cut]) & 0xC0) == 0x80) --cut;
            t = t.substr(0, cut) + "…";
          }
          if (i + 1 == kShown && shown.size() > kShown) t = fmt::format("… ({} more lines)", shown.size() - i);
          os << " " << st(std::to_string(p->line + i) + (p->removed ? " -" : " +"), p->removed ? "1;31" : "1;32") << " "
             << st(t, p->removed ? "31" : "32") << "\n";
        }
      }
    }
    os << "\n";
    seen.emplace(d.code, d.name);
  }
  const Counts c = count(diags);
  if (o.fixed) os << st(fmt::format("Fixed {} finding{}.", o.fixed, o.fixed == 1 ? "" : "s"), "1;32") << "\n";
  if (diags.empty()) {
    os << st(no_problems_line(o.files_checked), "1;32") << ".\n";
    return;
  }
  std::string summary = summary_line(c);
  if (c.fixable) summary += fmt::format(" ({} fixable with --fix)", c.fixable);
  else if (c.unsafe_fixable && o.show_fix_hint)
    summary += fmt::format(" ({} fixable with --fix --unsafe-fixes)", c.unsafe_fixable);
  os << st(summary, "1") << "\n";
  for (const auto& [code, name] : seen)
    os << "  " << code << " " << name << ": " << rule_url(o.docs_base, name) << "\n";
}

void render_concise(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                    const RenderOptions&) {
  // gcc style. Only the words `error` and `warning` are used, so gcc problem matchers, errorformat and efm
  // pick up every line: an info finding prints as `warning` and says `info` in its tag.
  for (const Diagnostic& d : diags) {
    const Range r = range_of(sm, d.loc);
    const std::string path = d.loc.file == kNoFile ? "-" : sanitize(sm.get(d.loc.file).display_path());
    os << fmt::format("{}:{}:{}: {}: {} [{} {}{}]\n", path, r.start.line, r.start.column,
                      d.severity == Severity::Error ? "error" : "warning", sanitize(d.message), d.code, d.name,
                      d.severity == Severity::Info ? ", info" : "");
  }
}

}  // namespace rrflint
