// Private to the parser's .cc files and the hottest rule pre-filters: the byte classes of the hot loops and the SSE2
// helpers that test 16 bytes at a time. They are inlined where they are used (the lexer, the line parser and the fast
// paths), so they live here.
#pragma once

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "lint/syntax/records.h"  // RRFLINT_ALWAYS_INLINE

namespace rrflint {

// Byte classes for the hot loops: a value runs over "plain" bytes without a second look; the code-end scan
// stops only at bytes that can end the code or change quoting.
struct ByteClasses {
  bool value_stop[256] = {};  // '"', '{', '(', letters, '\'', ':'
  bool code_stop[256] = {};   // '"', '{', '}', ';', '*', '('
  bool number[256] = {};      // digits, '.', '-', '+'
  bool rich[256] = {};        // not a letter, digit, blank, '.', '-', '+' or ':' (ParsedFile::rich_lines)
  constexpr ByteClasses() {
    for (int c = 0; c < 256; ++c)
      rich[c] = !((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == ' ' || c == '\t' ||
                  c == '.' || c == '-' || c == '+' || c == ':');
    for (int c = '0'; c <= '9'; ++c) number[c] = true;
    for (unsigned char c : {'.', '-', '+'}) number[c] = true;
    for (int c = 'A'; c <= 'Z'; ++c) value_stop[c] = value_stop[c + 32] = true;
    for (unsigned char c : {'"', '{', '(', '\'', ':'}) value_stop[c] = true;
    for (unsigned char c : {'"', '{', '}', ';', '*', '('}) code_stop[c] = true;
  }
};
inline constexpr ByteClasses kBytes;

// The first position in [p, e) whose byte is in a class, or e. With SSE2, 16 bytes are tested at a time wherever
// 16 bytes of the buffer (size n) remain; the bits past e are masked off. `Sse` maps 16 bytes to a bit mask.
template <class Sse>
RRFLINT_ALWAYS_INLINE inline uint32_t find_class(const char* s, uint32_t n, uint32_t p, uint32_t e, const bool* table,
                                                 [[maybe_unused]] Sse sse) {
#if defined(__SSE2__)
  while (p < e && p + 16 <= n) {
    auto m = static_cast<unsigned>(_mm_movemask_epi8(sse(_mm_loadu_si128(reinterpret_cast<const __m128i*>(s + p)))));
    if (e - p < 16) m &= (1u << (e - p)) - 1;
    if (m) return p + static_cast<unsigned>(__builtin_ctz(m));
    p += 16;
  }
  if (p >= e) return e;
#endif
  while (p < e && !table[static_cast<unsigned char>(s[p])]) ++p;
  return p;
}

#if defined(__SSE2__)
RRFLINT_ALWAYS_INLINE inline __m128i any_of(__m128i v, char a, char b) {
  return _mm_or_si128(_mm_cmpeq_epi8(v, _mm_set1_epi8(a)), _mm_cmpeq_epi8(v, _mm_set1_epi8(b)));
}
// ASCII letters: (v | 0x20) - 'a' < 26, compared unsigned by flipping the sign bits.
RRFLINT_ALWAYS_INLINE inline __m128i letters(__m128i v) {
  const __m128i off = _mm_sub_epi8(_mm_or_si128(v, _mm_set1_epi8(0x20)), _mm_set1_epi8('a'));
  return _mm_cmplt_epi8(_mm_xor_si128(off, _mm_set1_epi8(static_cast<char>(0x80))),
                        _mm_set1_epi8(static_cast<char>(0x80 + 26)));
}
// ASCII digits, the same way.
RRFLINT_ALWAYS_INLINE inline __m128i digits(__m128i v) {
  return _mm_cmplt_epi8(_mm_xor_si128(_mm_sub_epi8(v, _mm_set1_epi8('0')), _mm_set1_epi8(static_cast<char>(0x80))),
                        _mm_set1_epi8(static_cast<char>(0x80 + 10)));
}
// The bytes that are not kBytes.rich: letters, digits, blanks, '.', '-', '+' and ':'.
RRFLINT_ALWAYS_INLINE inline __m128i plain(__m128i v, __m128i letter, __m128i digit, __m128i blank) {
  return _mm_or_si128(_mm_or_si128(_mm_or_si128(letter, digit), blank),
                      _mm_or_si128(any_of(v, '.', '-'), any_of(v, '+', ':')));
}
#endif

// The next byte that ends a value (kBytes.value_stop), or e.
RRFLINT_ALWAYS_INLINE inline uint32_t next_value_stop(const char* s, uint32_t n, uint32_t p, uint32_t e) {
#if defined(__SSE2__)
  return find_class(s, n, p, e, kBytes.value_stop, [](__m128i v) {
    return _mm_or_si128(_mm_or_si128(letters(v), any_of(v, '"', '{')),
                        _mm_or_si128(any_of(v, '(', '\''), _mm_cmpeq_epi8(v, _mm_set1_epi8(':'))));
  });
#else
  return find_class(s, n, p, e, kBytes.value_stop, 0);
#endif
}

// The next byte that can end the code or change quoting (kBytes.code_stop), or e.
RRFLINT_ALWAYS_INLINE inline uint32_t next_code_stop(const char* s, uint32_t n, uint32_t p, uint32_t e) {
#if defined(__SSE2__)
  return find_class(s, n, p, e, kBytes.code_stop, [](__m128i v) {
    return _mm_or_si128(_mm_or_si128(any_of(v, '"', '{'), any_of(v, '}', ';')), any_of(v, '*', '('));
  });
#else
  return find_class(s, n, p, e, kBytes.code_stop, 0);
#endif
}

// Does [p, e) hold a byte of kBytes.rich?
RRFLINT_ALWAYS_INLINE inline bool any_rich(const char* s, uint32_t n, uint32_t p, uint32_t e) {
#if defined(__SSE2__)
  return find_class(s, n, p, e, kBytes.rich, [](__m128i v) {
           return _mm_xor_si128(plain(v, letters(v), digits(v), any_of(v, ' ', '\t')), _mm_set1_epi8(-1));
         }) < e;
#else
  return find_class(s, n, p, e, kBytes.rich, 0) < e;
#endif
}

}  // namespace rrflint
