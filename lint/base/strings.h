// Small string helpers shared by every stage.
#pragma once

#include <string>
#include <string_view>

namespace rrflint {

/// ASCII lower case (RRF names, codes and SD paths are compared case-insensitively).
std::string to_lower(std::string_view s);

}  // namespace rrflint
