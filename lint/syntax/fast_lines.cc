// The fast path: most lines in 16-byte steps (simple_line).

#include "lint/syntax/parse_internal.h"

namespace rrflint {

// The short path for most lines: a line of at most 64 bytes that starts with an upper-case G, M or T after
// indentation by spaces, and whose code (up to a ';') holds only letters, digits, blanks, '.', '-', '+' and ':' (no
// blank before a ':'). Such a line has no errors, no expression and no string; its bytes are classified 16 at a time
// into bit masks, and its parameters are the letters that are not an exponent (an E or e after a digit,
// docs/firmware-behaviour.md#parameters). The records written are those the full path writes (ParseOptions::fast_lines;
// the tests compare both). Returns false, having written nothing, for any other line.
bool LineParser::simple_line(uint32_t b, uint32_t e) {
#if defined(__SSE2__)
  const char* const s = lex_.t.data();
  const uint32_t len = e - b;
  if (len == 0 || len > 64 || lex_.t.size() - b < 64) return false;
  uint32_t lead = 0;  // indentation: spaces only (a tab counts otherwise)
  while (lead < len && s[b + lead] == ' ') ++lead;
  if (lead == len || (s[b + lead] != 'G' && s[b + lead] != 'M' && s[b + lead] != 'T')) return false;
  // The masks of the line's bytes, 16 at a time (bit i: byte b + i).
  uint64_t letter = 0, digit = 0, blank = 0, e_m = 0, semi = 0, colon = 0, allowed = 0;
  const auto chunk = [&](unsigned k) RRFLINT_ALWAYS_INLINE {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + b + 16 * k));
    const __m128i l = letters(v);
    const __m128i d = digits(v);
    const __m128i bl = any_of(v, ' ', '\t');
    const __m128i co = _mm_cmpeq_epi8(v, _mm_set1_epi8(':'));
    const __m128i ok = plain(v, l, d, bl);
    const auto mask = [k](__m128i m) { return uint64_t{static_cast<uint16_t>(_mm_movemask_epi8(m))} << (16 * k); };
    letter |= mask(l);
    digit |= mask(d);
    blank |= mask(bl);
    colon |= mask(co);
    allowed |= mask(ok);
    e_m |= mask(_mm_cmpeq_epi8(_mm_or_si128(v, _mm_set1_epi8(0x20)), _mm_set1_epi8('e')));
    semi |= mask(_mm_cmpeq_epi8(v, _mm_set1_epi8(';')));
  };
  chunk(0);
  if (len > 16) chunk(1);
  if (len > 32) chunk(2);
  if (len > 48) chunk(3);
  const auto below = [](uint32_t k) { return k >= 64 ? ~uint64_t{0} : (uint64_t{1} << k) - 1; };
  const uint64_t in_line = below(len);
  const uint32_t code_len = (semi & in_line) ? static_cast<uint32_t>(__builtin_ctzll(semi & in_line)) : len;
  const uint64_t code = below(code_len);
  if ((~allowed & code) || (colon & code & (blank << 1))) return false;
  const uint64_t solid = ~blank & code;                                // not empty: the line starts with a letter
  const auto ce = static_cast<uint32_t>(64 - __builtin_clzll(solid));  // the trimmed end of the code
  const uint64_t exponent = e_m & (digit << 1);
  const uint64_t param_letters = letter & ~exponent;

  struct Cmd {
    uint32_t begin, end, word_end;
    int32_t number;
    int8_t fraction;
    uint8_t bits, params;
  };
  Cmd cmds[33];
  uint32_t count = 0;
  for (uint32_t p = lead; p < ce;) {  // p: a command letter (relative to b)
    Cmd& c = cmds[count++];
    const char L = upper(s[b + p]);
    c.begin = p;
    uint32_t q = p + 1;
    const bool neg = q + 1 < ce && s[b + q] == '-' && is_digit(s[b + q + 1]);
    q += neg;
    const uint32_t db = q;
    int64_t n = 0;
    for (; q < ce && is_digit(s[b + q]); ++q)
      if (n < 100000000) n = n * 10 + (s[b + q] - '0');
    const bool has_number = q > db;
    if (!has_number && L != 'T') return false;  // an error: the full path reports it
    c.number = has_number ? static_cast<int32_t>(neg ? -n : n) : -1;
    c.fraction = -1;
    if (q + 1 < ce && s[b + q] == '.' && is_digit(s[b + q + 1])) {
      c.fraction = static_cast<int8_t>(s[b + q + 1] - '0');
      q += 2;
    }
    c.word_end = q;
    if (c.fraction < 0 && takes_rest_of_line(L, c.number)) return false;
    // Its parameters: from the word to the next G or M letter. The first byte after blanks must be a letter (text
    // there is an unlettered parameter), and a letter right after the word is a parameter, never an exponent.
    const uint64_t rest = code & ~below(q);
    if (const uint64_t first = solid & rest; first && !(letter & first & -first)) return false;
    // (A word may end at the line's 64th byte: then nothing follows it, and a shift by 64 would be undefined.)
    uint64_t params = (param_letters | (q < 64 ? letter & (uint64_t{1} << q) : 0)) & rest;
    uint32_t next = ce, seen = 0, np = 0;
    bool repeated = false;
    for (; params; params &= params - 1) {
      const auto j = static_cast<uint32_t>(__builtin_ctzll(params));
      const unsigned u = s[b + j] & 0xDFu;
      if (u == 'G' || u == 'M') {
        next = j;
        break;
      }
      const uint32_t bit = uint32_t{1} << (u - 'A');
      repeated = repeated || (seen & bit);
      seen |= bit;
      ++np;
    }
    uint32_t end = next;
    while (end > p && is_blank(s[b + end - 1])) --end;
    c.end = end;
    c.params = static_cast<uint8_t>(np);
    const bool exp = exponent & below(next) & ~below(q + 1);
    c.bits = static_cast<uint8_t>(detail::letter_bits(L) | (has_number ? detail::kHasNumber : 0) |
                                  (lex_.cnc ? detail::kCnc : 0) | (exp ? detail::kAnyExponent : 0) |
                                  (repeated ? detail::kAnyRepeat : 0));
    p = next;
  }
  // Nothing can fail from here: the records.
  const uint32_t line_index = next_line_;
  const auto first = static_cast<uint32_t>(out_.commands.recs_.size());
  for (uint32_t k = 0; k < count; ++k) {
    const Cmd& c = cmds[k];
    detail::CommandRec r;
    r.begin = b + c.begin;
    r.end = b + c.end;
    r.line = line_index;
    r.number = c.number;
    r.word_len = static_cast<uint8_t>(c.word_end - c.begin);
    r.fraction = c.fraction;
    r.bits = c.bits;
    r.param_count = c.params;
    out_.commands.push_rec(r);
    note_mode(detail::letter_of(c.bits), c.number, c.fraction);
  }
  if (colon & in_line & ~code) sets_->colon_comment_lines.insert(next_line_);  // a ':' in the comment
  // A value's first character after a blank that follows a byte other than a letter (may_hold_stray_value, which
  // walks back over a run of blanks: this takes any blank before the letter-less byte, a superset). An exponent's
  // E after a digit is not a letter there (`H0e 3`), so it counts as such a byte.
  // In the code every byte is allowed, so '.', '-' and '+' are the allowed bytes of no other class.
  const uint64_t value_start = (allowed & ~(letter | blank | colon)) & code;  // digits, '.', '-', '+'
  if (value_start & (blank << 1) & ~(param_letters << 2)) sets_->stray_value_lines.insert(next_line_);
  detail::LineRec& r = next_line_rec();
  r.code_begin = b + lead;
  r.code_end = b + ce;
  r.first = first;
  r.indent = static_cast<uint16_t>(lead);
  r.stored_length = static_cast<uint16_t>(code_len - lead);
  r.command_count = static_cast<uint16_t>(count);
  r.kind_meta = static_cast<uint8_t>(static_cast<unsigned>(LineKind::Commands) | (code_len < len ? 0x80 : 0));
  r.flags = lead ? detail::kIndentSpaces : 0;
  return true;
#else
  (void)b, (void)e;
  return false;
#endif
}

}  // namespace rrflint
