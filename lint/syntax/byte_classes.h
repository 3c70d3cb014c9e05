// Private to the parser's .cc files and the hottest rule pre-filters: the byte classes of the hot loops and the SSE2
// helpers that test 16 bytes at a time. They are inlined where they are used (the lexer, the line parser and the fast
// paths), so they live here.
#pragma once

#include <cstdint>
#include <string_view>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "lint/syntax/records.h"  // RRFLINT_ALWAYS_INLINE

namespace rrflint {

inline bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

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

// Can a value after the blanks that end at `q` (t[q - 1] is a blank) be one with no letter of its own? Not when the
// byte before the blanks is a letter: that letter takes the value (RRF's number reader skips leading blanks, so
// `X 10` is X10). An E or e right after a digit is an exponent, not a letter (`H0e 3`: the 3 has no letter). The
// blanks start at `lo` + 1 at the earliest. RRF120's full check and its quick test (may_hold_stray_value) share it.
inline bool blanks_after_non_letter(std::string_view t, uint32_t lo, uint32_t q) {
  uint32_t j = q - 1;  // the first blank of the run
  while (j > lo + 1 && is_blank(t[j - 1])) --j;
  const char c = t[j - 1];
  if (is_blank(c)) return false;
  if (!is_alpha(c)) return true;
  return (c == 'e' || c == 'E') && j >= lo + 2 && is_digit(t[j - 2]);
}

// Could a count of quotes go wrong in the code [s.begin, s.end)? A quote inside a CNC-mode comment (`( x"y )`) or
// a character literal (`{'"'}`, 3.5+) is no string's quote, so a quick test that pairs quotes passes such code as
// it is: the prefilters below, and RRF103's and RRF114's tests (fuzz_card found RRF103's missing
// `M950 H1 (x"y) S"b"cd`).
inline bool may_confuse_quotes(std::string_view t, Span s) {
  // Two searches for one byte each (memchr): find_first_of calls memchr on the set for every byte of the code.
  const std::string_view code(t.data() + s.begin, s.end - s.begin);
  return code.find('(') != std::string_view::npos || code.find('\'') != std::string_view::npos;
}

// Can a value start with this character (a number, a string or an expression)? RRF120's full check and its quick
// test share it.
inline bool starts_value(char c) { return is_digit(c) || c == '-' || c == '+' || c == '.' || c == '{' || c == '"'; }

// Could the code [s.begin, s.end) of a command line hold a value without a letter (RRF120's `G1 X10 20`)? A blank
// outside strings and expressions, followed by a value's first character (a digit, '-', '+', '.', '{' or '"'),
// where the last byte before the blanks is neither a blank nor a letter (`X 10` is X's value; an exponent's E is
// not a letter: blanks_after_non_letter). Cheap, and true for every command that rule reports
// (ParsedFile::Prefilters::stray_value_lines): with SSE2 it tests 16 blanks at a time, and walks the code byte by
// byte only after such a blank (`X{a + 1}` has one, inside the expression).
inline bool may_hold_stray_value(std::string_view t, Span s) {
  // Is the blank at q the end of a run of blanks that starts after such a byte?
  const auto stray_after = [&](uint32_t q) { return blanks_after_non_letter(t, s.begin, q + 1); };
  // The same test byte by byte, outside strings and expressions (code whose quotes may not pair passes as it is).
  const auto outside = [&] {
    if (may_confuse_quotes(t, s)) return true;
    bool quoted = false;
    uint32_t depth = 0;
    for (uint32_t k = s.begin; k + 1 < s.end; ++k) {
      const char c = t[k];
      if (c == '"') quoted = !quoted;
      else if (quoted) continue;
      else if (c == '{') ++depth;
      else if (c == '}') depth -= depth > 0;
      else if (depth == 0 && k > s.begin && is_blank(c) && starts_value(t[k + 1]) && stray_after(k)) return true;
    }
    return false;
  };
  uint32_t k = s.begin + 1;  // the blank's position; the value's is k + 1 < s.end
#if defined(__SSE2__)
  const char* p = t.data();
  while (k + 1 < s.end && k + 17 <= t.size()) {
    const __m128i here = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + k));
    const __m128i next = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + k + 1));
    const __m128i value = _mm_or_si128(_mm_or_si128(digits(next), any_of(next, '-', '+')),
                                       _mm_or_si128(any_of(next, '.', '{'), _mm_cmpeq_epi8(next, _mm_set1_epi8('"'))));
    auto m = static_cast<unsigned>(_mm_movemask_epi8(_mm_and_si128(any_of(here, ' ', '\t'), value)));
    if (s.end - 1 - k < 16) m &= (1u << (s.end - 1 - k)) - 1;
    for (; m != 0; m &= m - 1)
      if (stray_after(k + static_cast<uint32_t>(__builtin_ctz(m)))) return outside();
    k += 16;
  }
#endif
  for (; k + 1 < s.end; ++k)
    if (is_blank(t[k]) && starts_value(t[k + 1]) && stray_after(k)) return outside();
  return false;
}

// Could the code [s.begin, s.end) hold a closing quote with two letters right after it (RRF117's `S"abc"def`)?
// Quotes pair up from the start ("" inside a string closes and opens again). A character literal ('"', 3.5+) or a
// quote in a CNC-mode comment (`( "… )`) could throw the pairing off, so code with a quote and an apostrophe or a
// '(' passes as it is (ParsedFile::Prefilters::word_after_quote_lines).
inline bool may_have_word_after_quote(std::string_view t, Span s) {
  const std::string_view code(t.data() + s.begin, s.end - s.begin);
  if (code.find('"') == std::string_view::npos) return false;
  if (may_confuse_quotes(t, s)) return true;
  for (size_t open = code.find('"'); open != std::string_view::npos; open = code.find('"', open)) {
    const size_t close = code.find('"', open + 1);
    if (close == std::string_view::npos) return false;
    if (close + 2 < code.size() && is_alpha(code[close + 1]) && is_alpha(code[close + 2])) return true;
    open = close + 1;
  }
  return false;
}

}  // namespace rrflint
