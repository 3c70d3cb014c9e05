// `json-lines`: one diagnostic per line, the same objects as `json` prints in its "diagnostics" array (so a
// consumer can stream them). No summary line: an empty output means no findings.
#include "lint/render/render.h"

namespace rrflint {

void render_json_lines(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                       const RenderOptions& o) {
  write_diagnostics_json(os, sm, diags, o, 0, true);
}

}  // namespace rrflint
