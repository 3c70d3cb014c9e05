// Renderers: one format per file. Each takes the diagnostics of a run and the sources they point into.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "../diagnostic.h"
#include "../source.h"

namespace rrflint {

struct RenderOptions {
  bool color = false;
  bool show_fix_hint = true;        // the "N fixable with --fix" part of the summary
  bool unsafe_fixes_enabled = false;
  std::string docs_base = "https://github.com/rrflint/rrflint/blob/main/docs/rules/";
  size_t files_checked = 0;
};

struct Counts {
  size_t errors = 0, warnings = 0, infos = 0, fixable = 0, unsafe_fixable = 0, files = 0;
};
Counts count(const std::vector<Diagnostic>& diags);

/// 1-based line/column (code points) of a location, and of its exclusive end.
struct Range {
  LineCol start, end;
};
Range range_of(const SourceManager& sm, const Location& loc);

void render_text(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags, const RenderOptions& o);
void render_concise(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags, const RenderOptions& o);
void render_json(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags, const RenderOptions& o);
/// Text with invalid UTF-8 replaced by U+FFFD and control characters escaped, safe for terminals and JSON.
std::string sanitize(std::string_view s);

}  // namespace rrflint
