// Small string helpers shared by every stage.
#pragma once

#include <string>
#include <string_view>

namespace rrflint {

/// ASCII lower case (RRF names, codes and SD paths are compared case-insensitively).
std::string to_lower(std::string_view s);

/// ASCII case-insensitive equality and prefix test, without the copies of to_lower (they run per rule, per
/// suppression comment and per lint).
inline char ascii_lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; }
inline bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (ascii_lower(a[i]) != ascii_lower(b[i])) return false;
  return true;
}
inline bool istarts_with(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && iequals(s.substr(0, prefix.size()), prefix);
}

/// The first `n` bytes of `s`, fewer when byte n is inside a UTF-8 character: a text cut for a message never ends
/// in part of a character (which JSON could not carry, and a terminal shows as garbage).
std::string_view utf8_prefix(std::string_view s, size_t n);

/// `at`, or the start of the UTF-8 character that byte `at` of `s` continues (at most 3 bytes back, never before
/// `floor`): a text quoted from a byte position (where a parse stopped) never starts in part of a character.
size_t utf8_start(std::string_view s, size_t at, size_t floor = 0);

/// `s` for a message: at most `n` bytes of it, cut at a character, with "…" when it was cut. A user's text quoted
/// in a finding (a 50,000-byte word is still one word) stays short.
std::string clip(std::string_view s, size_t n = 40);

}  // namespace rrflint
