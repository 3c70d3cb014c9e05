// Small string helpers shared by every stage.
#pragma once

#include <string>
#include <string_view>

namespace rrflint {

/// ASCII lower case (RRF names, codes and SD paths are compared case-insensitively).
std::string to_lower(std::string_view s);

/// The first `n` bytes of `s`, fewer when byte n is inside a UTF-8 character: a text cut for a message never ends
/// in part of a character (which JSON could not carry, and a terminal shows as garbage).
std::string_view utf8_prefix(std::string_view s, size_t n);

}  // namespace rrflint
