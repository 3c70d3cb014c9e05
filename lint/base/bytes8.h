// Eight bytes at a time: tests on a 64-bit word for "does any of its bytes …", for the loops that copy plain text
// and walk byte by byte only around what needs work (the JSON writer, sanitize). Each test is exact for "any
// byte": a borrow only runs on from a byte that already matched, and a byte from 0x80 up matches none of them.
#pragma once

#include <cstdint>
#include <cstring>

namespace rrflint::bytes8 {

inline constexpr uint64_t kOnes = 0x0101010101010101ull, kHighs = 0x8080808080808080ull;

/// The 8 bytes at p, in memory order.
inline uint64_t load(const char* p) {
  uint64_t x;
  std::memcpy(&x, p, 8);
  return x;
}
/// Any byte below n (n <= 0x80)?
inline bool any_below(uint64_t x, uint8_t n) { return ((x - n * kOnes) & ~x & kHighs) != 0; }
/// Any byte equal to c (c < 0x80)?
inline bool any_equal(uint64_t x, char c) {
  const uint64_t y = x ^ (static_cast<uint8_t>(c) * kOnes);
  return ((y - kOnes) & ~y & kHighs) != 0;
}
/// Any byte from 0x80 up?
inline bool any_high(uint64_t x) { return (x & kHighs) != 0; }

}  // namespace rrflint::bytes8
