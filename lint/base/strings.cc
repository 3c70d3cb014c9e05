#include "lint/base/strings.h"

namespace rrflint {

std::string to_lower(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c + 32);
  return r;
}

std::string_view utf8_prefix(std::string_view s, size_t n) {
  if (n >= s.size()) return s;
  while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;  // s[n] continues a character
  return s.substr(0, n);
}

size_t utf8_start(std::string_view s, size_t at, size_t floor) {
  for (int k = 0; k < 3 && at > floor && at < s.size() && (static_cast<unsigned char>(s[at]) & 0xC0) == 0x80; ++k) --at;
  return at;
}

std::string clip(std::string_view s, size_t n) {
  if (s.size() <= n) return std::string(s);
  return std::string(utf8_prefix(s, n)) + "…";
}

}  // namespace rrflint
