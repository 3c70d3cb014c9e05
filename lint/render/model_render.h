#pragma once
#include <ostream>
#include <string>

#include "lint/engine/linter.h"

namespace rrflint {
void render_model_text(std::ostream& os, const SourceManager& sm, const MachineResult& r, const std::string& title);
void render_model_json(std::ostream& os, const SourceManager& sm, const MachineResult& r, const std::string& title);
}  // namespace rrflint
