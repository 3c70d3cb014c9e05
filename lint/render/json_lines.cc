// `json-lines`: one diagnostic per line, the same objects as `json` prints in its "diagnostics" array (so a
// consumer can stream them). No summary line: an empty output means no findings.
#include "lint/render/json_writer.h"
#include "lint/render/render.h"

namespace rrflint {

void render_json_lines(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                       const RenderOptions& o) {
  JsonPaths paths(sm);
  std::string line;
  for (const Diagnostic& d : diags) {
    line.clear();
    JsonWriter w(line, -1);
    write_diagnostic_json(w, paths, d, o.docs_base);
    os << line << "\n";
  }
}

}  // namespace rrflint
