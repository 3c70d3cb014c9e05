// `json-lines`: one diagnostic per line, the same objects as `json` prints in its "diagnostics" array (so a
// consumer can stream them). No summary line: an empty output means no findings.
#include <nlohmann/json.hpp>

#include "lint/render/render.h"

namespace rrflint {

void render_json_lines(std::ostream& os, const SourceManager& sm, const std::vector<Diagnostic>& diags,
                       const RenderOptions& o) {
  using nlohmann::json;
  for (const Diagnostic& d : diags)
    os << diagnostic_json(sm, d, o.docs_base).dump(-1, ' ', false, json::error_handler_t::replace) << "\n";
}

}  // namespace rrflint
