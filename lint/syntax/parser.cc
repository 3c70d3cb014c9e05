#include "lint/syntax/parser.h"
#include "lint/base/trace.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cstring>

#include <fmt/format.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "lint/base/huge_pages.h"
#include "lint/base/parallel.h"

namespace rrflint {
namespace {

bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_blank(char c) { return c == ' ' || c == '\t'; }
char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }
char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c + 32) : c; }

struct MetaWord {
  std::string_view word;
  MetaKind kind;
};
constexpr MetaWord kMetaWords[] = {
    {"if", MetaKind::If},         {"elif", MetaKind::Elif},   {"else", MetaKind::Else},     {"while", MetaKind::While},
    {"break", MetaKind::Break},   {"continue", MetaKind::Continue}, {"abort", MetaKind::Abort}, {"var", MetaKind::Var},
    {"global", MetaKind::Global}, {"set", MetaKind::Set},     {"echo", MetaKind::Echo},     {"skip", MetaKind::Skip},
};

// Byte classes for the hot loops: a value runs over "plain" bytes without a second look; the code-end scan
// stops only at bytes that can end the code or change quoting.
struct ByteClasses {
  bool value_stop[256] = {};  // '"', '{', '(', letters, '\'', ':'
  bool code_stop[256] = {};   // '"', '{', '}', ';', '*', '('
  bool number[256] = {};      // digits, '.', '-', '+'
  // For the parse-time parameter scan (LineParser::count_params): what a byte can do to a parameter list.
  enum : uint8_t { kPlain, kBlank, kLetter, kQuote, kBrace, kColon, kParen, kApostrophe };
  uint8_t param[256] = {};
  bool rich[256] = {};        // not a letter, digit, blank, '.', '-', '+' or ':' (ParsedFile::rich_lines)
  constexpr ByteClasses() {
    for (int c = 0; c < 256; ++c)
      rich[c] = !((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == ' ' || c == '\t' ||
                  c == '.' || c == '-' || c == '+' || c == ':');
    param[static_cast<unsigned char>(' ')] = param[static_cast<unsigned char>('\t')] = kBlank;
    for (int c = 'A'; c <= 'Z'; ++c) param[c] = param[c + 32] = kLetter;
    param[static_cast<unsigned char>('"')] = kQuote;
    param[static_cast<unsigned char>('{')] = kBrace;
    param[static_cast<unsigned char>(':')] = kColon;
    param[static_cast<unsigned char>('(')] = kParen;
    param[static_cast<unsigned char>('\'')] = kApostrophe;
    for (int c = '0'; c <= '9'; ++c) number[c] = true;
    for (unsigned char c : {'.', '-', '+'}) number[c] = true;
    for (int c = 'A'; c <= 'Z'; ++c) value_stop[c] = value_stop[c + 32] = true;
    for (unsigned char c : {'"', '{', '(', '\'', ':'}) value_stop[c] = true;
    for (unsigned char c : {'"', '{', '}', ';', '*', '('}) code_stop[c] = true;
  }
};
constexpr ByteClasses kBytes;

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

// A command whose one string argument needs no letter (M117 text); a fraction makes it another command.
bool unlettered_string(const Command& c) { return c.fraction < 0 && takes_unlettered_string(c.letter, c.number); }

// The syntax of an RRF expression, as ExpressionParser.cpp reads it, without evaluating anything: what RRF rejects
// whatever the values are (a missing operand, a bracket closed by the wrong one, text where an operator or the end
// should be). It accepts a little more than RRF (any number of function arguments, a '?' inside the middle operand),
// never less. Strings that are not closed or hold control characters, and very deep nesting, are left alone
// (`gave_up`): the lexer reports the first two itself.
class ExprSyntax {
 public:
  ExprSyntax(std::string_view t, uint32_t e) : t_(t), e_(e) {}
  /// One expression from `p`; `p` is left after it and any blanks. False on an error (`msg`, `at`) or when the
  /// check gave up (`gave_up`).
  bool expression(uint32_t& p) { return expr(p, 0); }
  /// A quoted string at `p` (on the '"'), the way RRF reads a string parameter.
  bool string(uint32_t& p) { return quoted(p); }
  uint32_t skip(uint32_t p) const {
    while (p < e_ && is_blank(t_[p])) ++p;
    return p;
  }
  char at_char(uint32_t p) const { return p < e_ ? t_[p] : '\0'; }
  bool fail(uint32_t p, const char* m) {
    msg = m;
    at = p;
    return false;
  }
  const char* msg = nullptr;  // RRF's own message
  uint32_t at = 0;
  bool gave_up = false;

 private:
  static constexpr int kMaxDepth = 64;
  bool give_up() {
    gave_up = true;
    return false;
  }
  static bool is_alnum(char c) { return is_alpha(c) || is_digit(c); }
  bool expr(uint32_t& p, int depth) {
    if (!operand(p, depth)) return false;
    for (;;) {  // binary operators, by the first character: "?^&|!=<>+-*/"
      p = skip(p);
      const char c = at_char(p);
      if (c == '\0' || !std::strchr("?^&|!=<>+-*/", c)) return true;
      ++p;
      if (c == '!') {
        if (at_char(p) != '=') return fail(p, "expected '='");
        ++p;
      } else if ((c == '<' || c == '>') && at_char(p) == '=') {
        ++p;
      } else if ((c == '=' || c == '&' || c == '|') && at_char(p) == c) {
        ++p;
      }
      if (c == '?') {
        if (!expr(p, depth + 1)) return false;
        if (at_char(p) != ':') return fail(p, "expected ':'");
        ++p;
        return expr(p, depth + 1);
      }
      if (!operand(p, depth + 1)) return false;
    }
  }
  // A bracketed expression's closing bracket (ParseExpectKet); `p` is after the expression.
  bool ket(uint32_t& p, char closer, int depth) {
    if (at_char(p) == closer) {
      ++p;
    } else if (closer == '}' && at_char(p) == ',') {  // an array literal {a, b, …}, a trailing ',' allowed
      do {
        p = skip(p + 1);
        if (at_char(p) == '}') break;
        if (!expr(p, depth + 1)) return false;
      } while (at_char(p) == ',');
      if (at_char(p) != '}') return fail(p, "expected '}'");
      ++p;
    } else {
      return fail(p, closer == ')' ? "expected ')'" : "expected '}'");
    }
    for (;;) {  // index expressions after the bracket
      const uint32_t q = skip(p);
      if (at_char(q) != '[') return true;
      p = q + 1;
      if (!expr(p, depth + 1)) return false;
      if (at_char(p) != ']') return fail(p, "expected ']'");
      ++p;
    }
  }
  bool operand(uint32_t& p, int depth) {
    if (depth > kMaxDepth) return give_up();
    p = skip(p);
    const char c = at_char(p);
    switch (c) {
      case '"':
        return quoted(p);
      case '\'':  // a character literal 'x'
        p += 2;
        if (p > e_ || at_char(p) != '\'') return fail(std::min(p, e_), "expected \"'\"");
        ++p;
        return true;
      case '-':
      case '+':
      case '!':
        ++p;
        return operand(p, depth + 1);
      case '#':
        p = skip(p + 1);
        return is_alpha(at_char(p)) ? identifier(p, depth + 1) : operand(p, depth + 1);
      case '{':
      case '(':
        ++p;
        if (!expr(p, depth + 1)) return false;
        return ket(p, c == '{' ? '}' : ')', depth);
      default:
        if (is_digit(c)) return number(p);
        if (is_alpha(c)) return identifier(p, depth);
        return fail(p, "expected an expression");
    }
  }
  bool quoted(uint32_t& p) {
    for (++p;;) {
      if (p >= e_) return give_up();
      const char c = t_[p++];
      if (static_cast<unsigned char>(c) < 0x20) return give_up();
      if (c == '"') {
        if (at_char(p) != '"') return true;
        ++p;
      } else if (c == '\'' && (is_alpha(at_char(p)) || at_char(p) == '\'')) {
        ++p;
      }
    }
  }
  bool number(uint32_t& p) {
    const char x = static_cast<char>(at_char(p + 1) | 0x20);
    if (t_[p] == '0' && (x == 'x' || x == 'b')) {  // 0x1F, 0b101
      p += 2;
      while (p < e_ && (x == 'x' ? std::isxdigit(static_cast<unsigned char>(t_[p])) != 0 : (t_[p] == '0' || t_[p] == '1')))
        ++p;
      return true;
    }
    bool point = false;
    for (; p < e_ && (is_digit(t_[p]) || (t_[p] == '.' && !point)); ++p) point = point || t_[p] == '.';
    if ((at_char(p) | 0x20) == 'e') {
      ++p;
      if (at_char(p) == '+' || at_char(p) == '-') ++p;
      while (p < e_ && is_digit(t_[p])) ++p;
    }
    return true;
  }
  // A name with dots and [index] parts (blanks may come before a '.' or '[' but not inside a name), then maybe a
  // function call's arguments.
  bool identifier(uint32_t& p, int depth) {
    const uint32_t begin = p;
    uint32_t name_end = p;
    char c = t_[p];
    bool ident = true;
    do {
      ++p;
      if (c == '[') {
        if (!expr(p, depth + 1)) return false;
        if (at_char(p) != ']') return fail(p, "expected ']'");
        ++p;
      }
      name_end = p;
      bool space = false;
      for (c = at_char(p); c == ' ' || c == '\t'; c = at_char(++p)) space = ident;
      ident = is_alnum(c) || c == '_';
      if (ident && space) break;
    } while (ident || c == '.' || c == '[');
    p = skip(p);
    if (at_char(p) != '(') return true;
    ++p;
    if (t_.substr(begin, name_end - begin) == "exists") {  // exists(name): a name straight after the '('
      if (!is_alpha(at_char(p))) return fail(p, "expected an identifier");
      if (!identifier(p, depth + 1)) return false;
    } else {
      if (!expr(p, depth + 1)) return false;
      while (at_char(p) == ',') {
        ++p;
        if (!expr(p, depth + 1)) return false;
      }
    }
    p = skip(p);
    if (at_char(p) != ')') return fail(p, "expected ')'");
    ++p;
    return true;
  }

  std::string_view t_;
  uint32_t e_;
};

// `s`, cut to 40 characters for a message.
std::string clip(std::string_view s) {
  return s.size() <= 40 ? std::string(s) : fmt::format("{}…", s.substr(0, 40));
}

// "'…'" or "the end": where an expression error is, for a message.
std::string error_place(std::string_view t, uint32_t at, uint32_t e) {
  if (at >= e) return "at the end";
  std::string_view rest = t.substr(at, e - at);
  if (rest.size() > 16) return fmt::format("at '{}…'", rest.substr(0, 16));
  return fmt::format("at '{}'", rest);
}

// Is the {…} group [b, e) (from its '{' to after its '}') a complete expression? `msg` and `at` say why not.
bool brace_expression_ok(std::string_view t, uint32_t b, uint32_t e, const char** msg, uint32_t* at) {
  ExprSyntax x(t, e);
  uint32_t p = b;
  if (x.expression(p) || x.gave_up) return true;
  *msg = x.msg;
  *at = x.at;
  return false;
}

}  // namespace

// The lexer of values and parameters. The parse pass runs it with `out` set (errors are recorded); ParamRange
// runs the same code quietly over one command to hand out its parameters again.
struct Lexer {
  std::string_view t;
  bool cnc = false;
  ParsedFile* out = nullptr;  // null: quiet (re-lexing a command that was parsed before)

  [[gnu::noinline, gnu::cold]] void error(uint32_t b, uint32_t e, std::string msg) const {
    if (out) out->errors.push_back({Span{b, e}, std::move(msg)});
  }
  uint32_t skip_blanks(uint32_t p, uint32_t e) const {
    const char* const s = t.data();
    for (;;) {
      while (p < e && is_blank(s[p])) ++p;
      if (cnc && p < e && s[p] == '(') {  // CNC-mode ( ) comment, treated as a blank
        while (p < e && s[p] != ')') ++p;
        if (p < e) ++p;
        continue;
      }
      return p;
    }
  }
  // Skips a quoted string starting at `p` (on the opening quote). Returns the position after it, or `e` and
  // records an error when the string is not closed.
  [[gnu::noinline]] uint32_t skip_string(uint32_t p, uint32_t e) const {
    const uint32_t start = p++;
    while (p < e) {
      const char c = t[p];
      if (c == '"') {
        if (p + 1 < e && t[p + 1] == '"') {
          p += 2;
          continue;
        }
        return p + 1;
      }
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') break;
      if (c == '\t') error(p, p + 1, "control character in string: a tab inside quotes is rejected by RRF");
      ++p;
    }
    error(start, e, "unterminated string: a quoted string must end with '\"' on the same line");
    return e;
  }
  // Did a ';' cut an open expression at `e`, the end of the code? Only when the comment after it holds the
  // `closer` the expression lacks: `X{a ; b}` is cut, `X{a ; note` just misses its '}'.
  bool cut_by_semicolon(uint32_t e, char closer) const {
    while (e < t.size() && is_blank(t[e])) ++e;
    if (e >= t.size() || t[e] != ';') return false;
    for (; e < t.size() && t[e] != '\n' && t[e] != '\r' && t[e] != '\0'; ++e)
      if (t[e] == closer) return true;
    return false;
  }
  // Skips a {…} expression starting at `p` (on '{'). Strings inside are skipped whole. With `check`, an
  // expression RRF cannot parse (`{1 + }`, `{(1 + 2}`) is an error; text RRF skips unread is not checked.
  [[gnu::noinline]] uint32_t skip_braces(uint32_t p, uint32_t e, bool check = true) const {
    const uint32_t start = p;
    int depth = 0;
    while (p < e) {
      const char c = t[p];
      if (c == '"') {
        p = skip_string(p, e);
        continue;
      }
      if (c == '{') ++depth;
      else if (c == '}' && --depth == 0) {
        const char* msg = nullptr;
        uint32_t at = 0;
        if (out && check && !brace_expression_ok(t, start, p + 1, &msg, &at))
          error(std::min(at, p), p + 1,
                fmt::format("{} in '{}', {}", msg, clip(t.substr(start, p + 1 - start)), error_place(t, at, p + 1)));
        return p + 1;
      }
      ++p;
    }
    // A ';' that cut the line is RRF113's finding (semicolon-in-expression), not a syntax error.
    if (out) {
      if (cut_by_semicolon(e, '}')) out->semicolon_cuts.push_back(Span{start, e});
      else error(start, e, "unterminated '{': the expression has no closing '}'");
    }
    return e;
  }
  uint32_t parse_value(uint32_t p, uint32_t e, Param& param) const;
  // The parameter that a T{…} or an unlettered string command starts with. False when there is none.
  bool first_param(const Command& c, uint32_t& p, uint32_t e, Param& param) const;
  // The lettered parameter at `p` (blanks skipped first). False at the end, or at the next command of the line.
  bool next_param(const Command& c, uint32_t& p, uint32_t e, Param& param) const;
};

uint32_t Lexer::parse_value(uint32_t p, uint32_t e, Param& param) const {
  // A value runs to the next parameter letter (or G/M command letter) outside quotes and braces.
  // An E or e straight after a digit is an exponent, not a parameter (docs/firmware-behaviour.md#parameters).
  const char* const s = t.data();
  const auto n = static_cast<uint32_t>(t.size());
  const uint32_t vb = skip_blanks(p, e);
  uint32_t q = vb;
  // Fast path, most values: a plain number ("10", "-0.5") ending at blanks, the next letter or the end. What the
  // loop below would decide differently (an exponent E, a list, a string …) takes the loop.
  while (q < e && kBytes.number[static_cast<unsigned char>(s[q])]) ++q;
  if (q > vb) {
    uint32_t r = q;
    while (r < e && is_blank(s[r])) ++r;
    const bool ends = r == e || (is_alpha(s[r]) && !(r == q && (s[r] == 'E' || s[r] == 'e') && is_digit(s[r - 1]))) ||
                      (s[r] == '\'' && r + 1 < e && is_alpha(s[r + 1])) || (cnc && s[r] == '(');
    if (ends) {
      param.value = Span{vb, q};
      param.has_expr = param.exponent_letter = param.blank_before_colon = false;
      param.kind = ValueKind::Number;
      return r;
    }
  }
  q = vb;
  bool colon = false, has_expr = false, exponent = false, blank_colon = false;
  for (;;) {
    q = next_value_stop(s, n, q, e);
    if (q >= e) break;
    const char c = s[q];
    if (is_alpha(c)) {
      if ((c == 'E' || c == 'e') && q > vb && is_digit(s[q - 1])) {
        exponent = true;
        ++q;
        if (q < e && (s[q] == '+' || s[q] == '-')) ++q;
        continue;
      }
      break;
    }
    if (c == '"') {
      q = skip_string(q, e);
      continue;
    }
    if (c == '{') {
      has_expr = true;
      q = skip_braces(q, e);
      continue;
    }
    if (c == '(') {
      if (cnc) break;
    } else if (c == '\'') {
      if (q + 1 < e && is_alpha(s[q + 1])) break;
    } else {  // ':'
      colon = true;
      if (q > vb && is_blank(s[q - 1])) blank_colon = true;
    }
    ++q;
  }
  uint32_t ve = q;
  while (ve > vb && is_blank(s[ve - 1])) --ve;
  param.value = Span{vb, ve};
  param.has_expr = has_expr;
  param.exponent_letter = exponent;
  param.blank_before_colon = blank_colon;
  if (vb == ve) {
    param.kind = ValueKind::None;
  } else {
    const char f = s[vb];
    if (colon) param.kind = ValueKind::List;
    else if (f == '"') param.kind = ValueKind::String;
    else if (f == '{') param.kind = ValueKind::Expression;
    else if (is_digit(f) || f == '-' || f == '+' || f == '.') param.kind = ValueKind::Number;
    else param.kind = ValueKind::Text;
  }
  return q;
}

bool Lexer::first_param(const Command& c, uint32_t& p, uint32_t e, Param& param) const {
  if (c.number_expr) {
    // T{expr} is T with a T parameter: the expression is that parameter.
    param = Param{};
    param.letter = 'T';
    param.span = param.value = Span{c.word.begin + 1, c.word.end};
    param.kind = ValueKind::Expression;
    param.has_expr = true;
    return true;
  }
  if (!unlettered_string(c)) return false;
  // Unprecedented string commands (M117 text, M23 file) take everything after the code as one string.
  const uint32_t q = skip_blanks(p, e);
  p = e;
  if (q >= e) return false;
  param = Param{};
  param.span = param.value = Span{q, e};
  param.kind = t[q] == '"' ? ValueKind::String : t[q] == '{' ? ValueKind::Expression : ValueKind::Text;
  if (param.kind == ValueKind::String) param.span = param.value = Span{q, skip_string(q, e)};
  else if (param.kind == ValueKind::Expression && out) (void)skip_braces(q, e);  // for its errors: RRF reads it
  return true;
}

bool Lexer::next_param(const Command& cmd, uint32_t& p, uint32_t e, Param& param) const {
  p = skip_blanks(p, e);
  if (p >= e) return false;
  const char c = t[p];
  if (c == 'G' || c == 'g' || c == 'M' || c == 'm') return false;  // the next command on this line
  param = Param{};
  const uint32_t pb = p;
  if (c == '\'' && p + 1 < e && is_alpha(t[p + 1])) {
    param.letter = lower(t[p + 1]);
    p += 2;
  } else if (is_alpha(c)) {
    param.letter = upper(c);
    ++p;
  } else {
    param.letter = 0;  // stray text before the first letter (RRF skips it): an unlettered parameter
  }
  if (param.letter == 'P' && p < e && t[p] != '"' && t[p] != '{' && cmd.fraction < 0 &&
      takes_rest_of_line(cmd.letter, cmd.number)) {
    param.value = Span{p, e};
    param.kind = ValueKind::Text;
    p = e;
  } else if (param.letter == 0) {
    uint32_t q = p;
    while (q < e && !is_alpha(t[q])) {
      if (t[q] == '"') q = skip_string(q, e);
      else if (t[q] == '{') q = skip_braces(q, e, false);  // RRF skips this text unread
      else ++q;
    }
    param.value = Span{p, q};
    while (param.value.end > param.value.begin && is_blank(t[param.value.end - 1])) --param.value.end;
    param.kind = ValueKind::Text;
    p = q;
  } else {
    p = parse_value(p, e, param);
  }
  param.span = Span{pb, param.value.empty() ? (param.letter >= 'a' ? pb + 2 : pb + 1) : param.value.end};
  return true;
}

void LineSet::insert(uint32_t i) {
  if (i / 64 >= words_.size()) words_.resize(i / 64 + 1, 0);  // only a parse on one thread (NUL bytes) gets here
  std::atomic_ref<uint64_t>(words_[i / 64]).fetch_or(uint64_t{1} << (i % 64), std::memory_order_relaxed);
}

void LineSet::clear(uint32_t from, uint32_t to) {
  for (uint32_t i = from; i < to && i / 64 < words_.size(); ++i) words_[i / 64] &= ~(uint64_t{1} << (i % 64));
}

// ---- Tables: records in, values out ----

namespace {

// Code keys: G0…G1023, then M0…M1023, then every T.
constexpr uint16_t kTKey = 2048, kNoKey = 2049;
uint16_t code_key(char letter, int32_t number) {
  if (letter == 'T') return kTKey;
  if (number < 0 || number >= 1024) return kNoKey;
  return static_cast<uint16_t>((letter == 'M' ? 1024 : 0) + number);
}

}  // namespace

// Appends a record and counts its code for index_codes, which then needs no sweep of its own to size the runs.
RRFLINT_ALWAYS_INLINE inline void CommandTable::push_rec(const detail::CommandRec& r) {
  if (key_counts_.empty()) key_counts_.assign(kNoKey + 1, 0);
  const uint16_t key = code_key(detail::letter_of(r.bits), r.number);
  ++key_counts_[key];
  if (r.fraction >= 0 && (fraction_keys_.empty() || fraction_keys_.back() != key)) fraction_keys_.push_back(key);
  all_bits_ |= r.bits;
  recs_.push_back(r);
}

void CommandTable::add(const Command& c) {
  detail::CommandRec r;
  const auto i = static_cast<uint32_t>(recs_.size());
  r.begin = c.span.begin;
  r.end = c.span.end;
  r.line = c.line;
  r.number = c.number;
  r.fraction = c.fraction;
  const uint32_t wl = c.word.end - c.word.begin;
  r.word_len = static_cast<uint8_t>(wl < 255 ? wl : 255);
  if (wl >= 255) long_words_[i] = c.word.end;
  r.param_count = static_cast<uint8_t>(c.param_count < 255 ? c.param_count : 255);
  if (c.param_count >= 255) big_counts_[i] = c.param_count;
  r.bits = static_cast<uint8_t>(detail::letter_bits(c.letter) | (c.number_expr ? detail::kNumberExpr : 0) |
                                (c.has_number ? detail::kHasNumber : 0) | (c.cnc ? detail::kCnc : 0) |
                                (c.any_exponent ? detail::kAnyExponent : 0) | (c.any_blank_before_colon ? detail::kAnyBlankColon : 0) |
                                (c.any_repeated_letter ? detail::kAnyRepeat : 0));
  push_rec(r);
}

std::vector<uint32_t> CommandTable::with_flag(Flag f) const {
  std::vector<uint32_t> out;
  const auto bit = static_cast<uint8_t>(f);
  each_rec([&](size_t i, const detail::CommandRec& r) {
    if (r.bits & bit) out.push_back(static_cast<uint32_t>(i));
  });
  return out;
}

const detail::CommandRec& CommandTable::tail_rec(size_t i) const {
  // The last tail that starts at or before i's block of 64K commands, then on to i's own (tails of a few
  // commands, in tests, may share a block).
  size_t t = block_tail_[i >> 16];
  while (t + 1 < tails_.size() && i >= tails_[t + 1].begin) ++t;
  return tails_[t].recs[i - tails_[t].begin];
}

void CommandTable::append(CommandTable&& part) {
  const auto base = static_cast<uint32_t>(size());
  for (const auto& [k, v] : part.long_words_) long_words_[k + base] = v;
  for (const auto& [k, v] : part.big_counts_) big_counts_[k + base] = v;
  tail_size_ += part.recs_.size();
  if (!part.key_counts_.empty()) {
    if (key_counts_.empty()) key_counts_.assign(part.key_counts_.size(), 0);
    for (size_t k = 0; k < key_counts_.size(); ++k) key_counts_[k] += part.key_counts_[k];
  }
  fraction_keys_.insert(fraction_keys_.end(), part.fraction_keys_.begin(), part.fraction_keys_.end());
  all_bits_ |= part.all_bits_;
  tails_.push_back(Tail{base, std::move(part.recs_)});
  part = CommandTable{};
  block_tail_.assign((size() >> 16) + 1, 0);
  uint32_t t = 0;
  for (size_t b = 0; b < block_tail_.size(); ++b) {
    while (t + 1 < tails_.size() && tails_[t + 1].begin <= b << 16) ++t;
    block_tail_[b] = t;
  }
}

uint32_t CommandTable::long_word_end(size_t i) const { return long_words_.at(static_cast<uint32_t>(i)); }
uint32_t CommandTable::big_count(size_t i) const { return big_counts_.at(static_cast<uint32_t>(i)); }

void LineTable::add(const Line& l) {
  recs_.emplace_back();
  put(recs_.back(), static_cast<uint32_t>(recs_.size() - 1), l);
}

void LineTable::put(detail::LineRec& r, uint32_t i, const Line& l) {
  r.code_begin = l.code.begin;
  r.code_end = l.code.end;
  if (l.kind == LineKind::Meta) {
    r.first = static_cast<uint32_t>(metas_.size());
    metas_.push_back({l.meta_arg, l.meta_name});
  } else {
    r.first = l.first_command;
  }
  r.indent = static_cast<uint16_t>(l.indent < 65535 ? l.indent : 65535);
  r.stored_length = static_cast<uint16_t>(l.stored_length < 65535 ? l.stored_length : 65535);
  if (l.indent >= 65535 || l.stored_length >= 65535) long_lines_[i] = {l.indent, l.stored_length};
  r.command_count = static_cast<uint16_t>(l.command_count < 65535 ? l.command_count : 65535);
  if (l.command_count >= 65535) big_counts_[i] = l.command_count;
  r.kind_meta = static_cast<uint8_t>(static_cast<unsigned>(l.kind) | (static_cast<unsigned>(l.meta) << 3) |
                                     (l.comment.empty() ? 0 : 0x80));
  r.flags = static_cast<uint8_t>((l.indent_tabs ? detail::kIndentTabs : 0) | (l.indent_spaces ? detail::kIndentSpaces : 0) |
                                 (l.line_number ? detail::kLineNumber : 0) | (l.checksum ? detail::kChecksum : 0) |
                                 (l.conditional ? detail::kConditional : 0) | (l.in_loop ? detail::kInLoop : 0) |
                                 (l.after_nul ? detail::kAfterNul : 0));
}

uint32_t LineTable::big_count(size_t i) const { return big_counts_.at(static_cast<uint32_t>(i)); }
uint32_t LineTable::long_indent(size_t i) const { return long_lines_.at(static_cast<uint32_t>(i)).first; }
uint32_t LineTable::long_length(size_t i) const { return long_lines_.at(static_cast<uint32_t>(i)).second; }

// ---- The line parser ----

class LineParser {
 public:
  /// Lines go to `out.lines`, or, when `in_place` is given, into `in_place[first_line…]` (a part of a file parsed
  /// in parts: `out` then takes the part's commands, meta-commands and errors, with commands indexed from 0).
  LineParser(ParsedFile& out, bool cnc, bool laser, detail::LineRec* in_place = nullptr, uint32_t first_line = 0)
      : out_(out), lex_{out.source->text(), cnc, &out}, in_place_(in_place), next_line_(first_line), laser_(laser) {}
  /// Parses the editor lines [from, to) of the file.
  void parse_lines(uint32_t from, uint32_t to, bool any_nul, bool any_del);
  /// Parses a file without NUL bytes in `parts` parts, one per thread.
  static void parse_in_parts(ParsedFile& pf, const ParseOptions& opts, unsigned parts, bool any_del);

  void parse_logical_line(uint32_t b, uint32_t e, bool after_nul, bool may_have_del);
  bool fast_lines = true;  // ParseOptions::fast_lines

 private:
  void error(uint32_t b, uint32_t e, std::string msg) { lex_.error(b, e, std::move(msg)); }
  bool simple_line(uint32_t b, uint32_t e);
  // Tracks the machine mode: M453 = CNC (`( )` comments), M452 = laser, M451 = FFF; it applies from the next line.
  void note_mode(char letter, int32_t number, int8_t fraction) {
    if (letter != 'M' || fraction >= 0 || number < 451 || number > 453) return;
    next_cnc_ = number == 453;
    next_laser_ = number == 452;
  }
  detail::LineRec& next_line_rec() {
    if (in_place_) return in_place_[next_line_++];
    ++next_line_;
    return out_.lines.recs_.emplace_back();
  }
  static void join_part(ParsedFile& pf, ParsedFile&& part, uint32_t first, uint32_t end);
  void parse_meta(Line& line, MetaKind kind, uint32_t after_kw, uint32_t e);
  void parse_commands(Line& line, uint32_t b, uint32_t e);
  bool count_params(Command& cmd, uint32_t& p, uint32_t e) const;
  void lex_params(Command& cmd, uint32_t& p, uint32_t e);
  // `what` names the expression in a message: "the '<kw>' <role>", or "the <role>" without a keyword (built only
  // for an error: most expressions are fine).
  /// False when it reported an error or a ';' cut the expression.
  bool check_expression(uint32_t b, uint32_t e, std::string_view kw, std::string_view role);
  /// The meta command's expressions as RRF's expression parser reads them (after check_expression passed).
  void check_meta_syntax(MetaKind kind, uint32_t b, uint32_t e);
  void add_line(const Line& line, bool cut_by_del) {
    if (!line.code.empty() && any_rich(lex_.t.data(), static_cast<uint32_t>(lex_.t.size()), line.code.begin, line.code.end)) {
      rich_->insert(next_line_);
      if (line.kind == LineKind::Commands && span_has(lex_.t, line.code, '(')) parens_->insert(next_line_);
      if (span_has(lex_.t, line.code, '\'')) apostrophes_->insert(next_line_);
    }
    if (span_has(lex_.t, line.comment, ':')) colon_comments_->insert(next_line_);
    detail::LineRec* r;
    if (in_place_) {
      r = &in_place_[next_line_];
      out_.lines.put(*r, next_line_, line);
    } else {
      out_.lines.add(line);
      r = &out_.lines.recs_.back();
    }
    if (cut_by_del) r->flags |= detail::kCutByDel;
    ++next_line_;
  }

  ParsedFile& out_;
  Lexer lex_;
  LineSet* rich_ = &out_.rich_lines;  // the file's set (a part of a file writes to the whole file's)
  LineSet* parens_ = &out_.paren_lines;  // likewise
  LineSet* apostrophes_ = &out_.apostrophe_lines;
  LineSet* colon_comments_ = &out_.colon_comment_lines;
  detail::LineRec* in_place_;
  uint32_t next_line_;     // the index of the next logical line
  bool next_cnc_ = false;  // the mode after this line (M453 / M451 / M452 take effect on the next line)
  bool laser_ = false;      // laser mode (M452): a line of axis words repeats the last move, as in CNC mode
  bool next_laser_ = false;
  friend ParsedFile parse(const SourceFile&, const ParseOptions&);
};

bool LineParser::check_expression(uint32_t b, uint32_t e, std::string_view kw, std::string_view role) {
  // Parsed just far enough to know it is an expression: balanced brackets and closed strings.
  const std::string_view t = lex_.t;
  auto what = [&] { return kw.empty() ? fmt::format("the {}", role) : fmt::format("the '{}' {}", kw, role); };
  const size_t errors = out_.errors.size();
  std::string stack;
  for (uint32_t p = b; p < e; ++p) {
    const char c = t[p];
    if (c == '"') {
      p = lex_.skip_string(p, e) - 1;
      continue;
    }
    if (c == '\'' && p + 2 < e && t[p + 2] == '\'') {  // character literal 'x' (3.5+)
      p += 2;
      continue;
    }
    if (c == '(' || c == '[' || c == '{') {
      stack.push_back(c);
    } else if (c == ')' || c == ']' || c == '}') {
      const char want = c == ')' ? '(' : c == ']' ? '[' : '{';
      if (stack.empty() || stack.back() != want) {
        error(p, p + 1, fmt::format("unbalanced '{}' in {}", c, what()));
        return false;
      }
      stack.pop_back();
    }
  }
  if (!stack.empty()) {
    const char closer = stack.back() == '(' ? ')' : stack.back() == '[' ? ']' : '}';
    if (lex_.cut_by_semicolon(e, closer)) out_.semicolon_cuts.push_back(Span{b, e});
    else error(b, e, fmt::format("unclosed '{}' in {}", stack.back(), what()));
    return false;
  }
  return out_.errors.size() == errors;
}

void LineParser::check_meta_syntax(MetaKind kind, uint32_t b, uint32_t e) {
  const std::string_view t = lex_.t;
  // In CNC mode RRF drops `( … )` outside braces before it reads the line: leave such a line alone.
  if (lex_.cnc && span_has(t, Span{b, e}, '(')) return;
  ExprSyntax x(t, e);
  const std::string_view kw = meta_keyword(kind);
  std::string_view what;
  uint32_t p = b;
  bool ok = true;
  std::string_view note;
  switch (kind) {
    case MetaKind::If:
    case MetaKind::Elif:
    case MetaKind::While:
      what = "condition";
      ok = x.expression(p) && (p >= e || x.fail(p, "Unexpected characters after expression"));
      break;
    case MetaKind::Echo:
      what = "arguments";
      if (x.at_char(p) == '>') {  // echo >"file", >>"file", >>>"file": a string straight after the '>'s
        for (int k = 0; k < 3 && x.at_char(p) == '>'; ++k) ++p;
        const char c = x.at_char(p);
        ok = c == '"' ? x.string(p) : c == '{' ? x.expression(p) : x.fail(p, "expected a string expression");
        if (is_blank(c)) note = " (standalone RRF wants the file name straight after '>'; DSF in SBC mode skips the blank)";
      }
      while (ok) {  // expressions separated by commas; a trailing comma is allowed
        p = x.skip(p);
        if (p >= e) break;
        ok = x.expression(p);
        if (ok && p < e) ok = x.at_char(p) == ',' ? (++p, true) : x.fail(p, "expected ','");
      }
      break;
    default:  // var, global, set: RRF reads one expression and ignores what follows it
      what = "value";
      ok = x.expression(p);
      break;
  }
  if (ok || x.gave_up) return;
  const std::string where = kw == "set" || kw == "var" || kw == "global" ? fmt::format("the {} of '{}'", what, kw)
                                                                          : fmt::format("the '{}' {}", kw, what);
  error(std::min(x.at, e > b ? e - 1 : b), e, fmt::format("{} in {}, {}{}", x.msg, where, error_place(t, x.at, e), note));
}

void LineParser::parse_logical_line(uint32_t b, uint32_t e, bool after_nul, bool may_have_del) {
  if (fast_lines && !after_nul && !may_have_del && simple_line(b, e)) return;
  const std::string_view t = lex_.t;
  Line line;
  line.span = Span{b, e};
  line.after_nul = after_nul;
  uint32_t p = b;
  // Indentation: a blank counts 1, a tab advances to the next multiple of 4.
  while (p < e && is_blank(t[p])) {
    if (t[p] == '\t') {
      line.indent = (line.indent + 4) & ~3u;
      line.indent_tabs = true;
    } else {
      ++line.indent;
      line.indent_spaces = true;
    }
    ++p;
  }
  // 0x7F (a serial-line error marker to RRF) discards the whole line: what came before it too.
  bool cut_by_del = false;
  if (may_have_del && p < e) {
    if (const void* del = std::memchr(t.data() + p, 0x7f, e - p)) {
      const auto k = static_cast<uint32_t>(static_cast<const char*>(del) - t.data());
      error(k, e, k > p ? "byte 0x7F: RRF discards the whole line, the text before this byte too"
                        : "byte 0x7F: RRF discards the whole line");
      e = p;
      cut_by_del = true;
    }
  }
  if (p >= e) {
    add_line(line, cut_by_del);
    return;
  }
  if (t[p] == ';') {
    line.comment = Span{p, e};
    line.kind = line.indent == 0 ? LineKind::Comment : LineKind::Blank;
    add_line(line, cut_by_del);
    return;
  }
  // Optional line number N<digits>.
  if ((t[p] == 'N' || t[p] == 'n') && p + 1 < e && is_digit(t[p + 1])) {
    line.line_number = true;
    ++p;
    while (p < e && is_digit(t[p])) ++p;
    while (p < e && is_blank(t[p])) ++p;
  }
  const uint32_t code_begin = p;
  // Find the end of the code: ';' outside quotes (braces do not protect it), '*' after N outside braces.
  uint32_t code_end = e;
  uint32_t paren_chars = 0;
  {
    int braces = 0;
    const char* const s = t.data();
    const auto n = static_cast<uint32_t>(t.size());
    for (uint32_t k = next_code_stop(s, n, p, e); k < e; k = next_code_stop(s, n, k + 1, e)) {
      const char c = s[k];
      if (c == '"') {  // on to the closing quote ("" re-enters at once: same result)
        const void* q = std::memchr(s + k + 1, '"', e - k - 1);
        if (!q) break;
        k = static_cast<uint32_t>(static_cast<const char*>(q) - s);
      } else if (c == '{') {
        ++braces;
      } else if (c == '}') {
        braces = braces > 0 ? braces - 1 : 0;
      } else if (c == ';') {
        code_end = k;
        line.comment = Span{k, e};
        break;
      } else if (c == '*' && line.line_number && braces == 0) {
        code_end = k;
        line.checksum = true;
        uint32_t q = k + 1;
        while (q < e && t[q] != ';') ++q;
        if (q < e) line.comment = Span{q, e};
        break;
      } else if (c == '(' && lex_.cnc && braces == 0) {
        uint32_t q = k;
        while (q < e && t[q] != ')') ++q;
        paren_chars += (q < e ? q + 1 : e) - k;
        k = q < e ? q : e - 1;
      }
    }
  }
  line.stored_length = code_end - code_begin - paren_chars;
  uint32_t ce = code_end;
  while (ce > code_begin && is_blank(t[ce - 1])) --ce;
  line.code = Span{code_begin, ce};
  if (ce == code_begin) {
    add_line(line, cut_by_del);
    return;
  }
  // Meta command: 2-8 lowercase letters followed by end, blank, '{', '"' or '('.
  if (t[code_begin] >= 'a' && t[code_begin] <= 'z') {
    uint32_t q = code_begin;
    while (q < ce && t[q] >= 'a' && t[q] <= 'z' && q - code_begin <= 8) ++q;
    const uint32_t len = q - code_begin;
    if (len >= 2 && len <= 8 && (q == ce || is_blank(t[q]) || t[q] == '{' || t[q] == '"' || t[q] == '(')) {
      const std::string_view word = t.substr(code_begin, len);
      for (const auto& mw : kMetaWords) {
        if (mw.word == word) {
          line.kind = LineKind::Meta;
          line.meta = mw.kind;
          parse_meta(line, mw.kind, q, ce);
          add_line(line, cut_by_del);
          return;
        }
      }
    }
  }
  parse_commands(line, code_begin, ce);
  add_line(line, cut_by_del);
}

// The short path for most lines: a line of at most 64 bytes that starts with an upper-case G, M or T after
// indentation by spaces, and whose code (up to a ';') holds only letters, digits, blanks, '.', '-', '+' and ':' (no blank before a ':').
// Such a line has no errors, no expression and no string; its bytes are classified 16 at a time into bit masks,
// and its parameters are the letters that are not an exponent (an E or e after a digit, firmware-behaviour.md#parameters). The
// records written are those the full path writes (ParseOptions::fast_lines; the tests compare both). Returns false,
// having written nothing, for any other line.
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
  const uint64_t solid = ~blank & code;  // not empty: the line starts with a letter
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
    uint64_t params = ((param_letters | (letter & (uint64_t{1} << q))) & rest);
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
  if (colon & in_line & ~code) colon_comments_->insert(next_line_);  // a ':' in the comment
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

void LineParser::parse_meta(Line& line, MetaKind kind, uint32_t p, uint32_t e) {
  const std::string_view t = lex_.t;
  p = lex_.skip_blanks(p, e);
  line.meta_arg = Span{p, e};
  const std::string_view kw = meta_keyword(kind);
  switch (kind) {
    case MetaKind::If:
    case MetaKind::Elif:
    case MetaKind::While:
      if (p >= e) error(line.code.begin, e, fmt::format("expected a condition after '{}'", kw));
      else if (check_expression(p, e, kw, "condition")) check_meta_syntax(kind, p, e);
      break;
    case MetaKind::Else:
      if (p < e) error(p, e, "unexpected characters after 'else' (use 'elif' for a condition)");
      break;
    case MetaKind::Var:
    case MetaKind::Global:
    case MetaKind::Set: {
      uint32_t q = p;
      if (kind == MetaKind::Set) {
        const std::string_view rest = t.substr(p, e - p);
        if (rest.starts_with("var.")) q += 4;
        else if (rest.starts_with("global.")) q += 7;
        else {
          error(p, e, "expected a global or local variable after 'set' ('var.name' or 'global.name')");
          return;
        }
      }
      const uint32_t name_begin = q;
      if (q < e && is_alpha(t[q])) {
        ++q;
        while (q < e && (is_alpha(t[q]) || is_digit(t[q]) || t[q] == '_')) ++q;
      }
      if (q == name_begin) {
        error(p, e, fmt::format("expected a {}variable name after '{}'", kind == MetaKind::Set ? "" : "new ", kw));
        return;
      }
      line.meta_name = Span{kind == MetaKind::Set ? p : name_begin, q};
      if (q - name_begin > 120) error(name_begin, q, "variable name longer than 120 characters");
      if (kind == MetaKind::Set) {  // optional indices [i]
        while (q < e && t[q] == '[') {
          uint32_t r = q;
          int d = 0;
          for (; r < e; ++r) {
            if (t[r] == '[') ++d;
            else if (t[r] == ']' && --d == 0) break;
          }
          if (r >= e) {
            error(q, e, "unclosed '[' in the variable index");
            return;
          }
          q = r + 1;
        }
      }
      q = lex_.skip_blanks(q, e);
      if (q >= e || t[q] != '=') {
        error(q < e ? q : e, e, "expected '='");
        return;
      }
      q = lex_.skip_blanks(q + 1, e);
      if (q >= e) {
        error(line.code.begin, e, "expected an expression after '='");
        return;
      }
      line.meta_arg = Span{q, e};
      if (check_expression(q, e, "", "expression")) check_meta_syntax(kind, q, e);
      break;
    }
    case MetaKind::Echo:
      if (p < e && check_expression(p, e, kw, "arguments")) check_meta_syntax(kind, p, e);
      break;
    case MetaKind::Abort:  // RRF aborts even when it cannot read the message: only brackets and strings matter
      if (p < e) check_expression(p, e, kw, "arguments");
      break;
    default:
      break;
  }
}

void LineParser::parse_commands(Line& line, uint32_t b, uint32_t e) {
  const std::string_view t = lex_.t;
  line.kind = LineKind::Commands;
  line.first_command = static_cast<uint32_t>(out_.commands.size());
  const uint32_t line_index = next_line_;
  uint32_t p = b;
  bool first = true;
  while (true) {
    p = lex_.skip_blanks(p, e);
    if (p >= e) break;
    Command cmd;
    cmd.line = line_index;
    cmd.cnc = lex_.cnc;
    const uint32_t cb = p;
    const char L = upper(t[p]);
    if (L != 'G' && L != 'M' && L != 'T') {
      // A line of axis words (`X5 F300`, `'a2`): in CNC and laser mode RRF repeats the last G0-G3 with them.
      const bool apostrophe = t[p] == '\'' && p + 1 < e && is_alpha(t[p + 1]);
      const char axis = apostrophe ? lower(t[p + 1]) : L;
      const uint32_t after = p + (apostrophe ? 2 : 1);
      const bool axis_words = first && (apostrophe || std::strchr("XYZUVWABCD", axis) != nullptr) && axis != '\0' &&
                              !(after < e && is_alpha(t[after]));
      if (axis_words && (lex_.cnc || laser_)) {  // its parameters run to the next G or M, as a command's do
        Command repeat;
        repeat.letter = 'G';
        repeat.number = 1;
        repeat.cnc = lex_.cnc;
        Param param;
        while (lex_.next_param(repeat, p, e, param)) {
        }
        first = false;
        continue;
      }
      if (first) {
        std::string_view text = t.substr(b, e - b);
        if (text.size() > 40) text = text.substr(0, 40);
        bool kw_case = false;
        for (const auto& mw : kMetaWords) {
          const std::string_view w = mw.word;
          if (e - b >= w.size()) {
            bool eq = true;
            for (size_t k = 0; k < w.size(); ++k) eq = eq && lower(t[b + k]) == w[k];
            if (eq && (e - b == w.size() || !is_alpha(t[b + w.size()]))) kw_case = true;
          }
        }
        error(b, e, kw_case ? fmt::format("Bad command: '{}': meta-command keywords must be lowercase", text)
                            : fmt::format("Bad command: '{}': a line must start with G, M or T{}", text,
                                          axis_words ? " (axis words alone repeat the last move only in CNC or "
                                                       "laser mode, after M453 or M452)"
                                                     : ""));
        out_.errors.back().axis_repeat = axis_words;
        line.kind = LineKind::Bad;
      }
      break;
    }
    first = false;
    cmd.letter = L;
    ++p;
    if (L == 'T' && p < e && t[p] == '{') {
      const uint32_t q = lex_.skip_braces(p, e);
      cmd.number_expr = true;
      cmd.word = Span{cb, q};
      p = q;
    } else {
      bool neg = false;
      if (p < e && t[p] == '-' && p + 1 < e && is_digit(t[p + 1])) {
        neg = true;
        ++p;
      }
      const uint32_t db = p;
      int64_t n = 0;
      while (p < e && is_digit(t[p])) {
        if (n < 100000000) n = n * 10 + (t[p] - '0');
        ++p;
      }
      if (p == db) {
        if (L != 'T') {
          error(cb, std::min(cb + 1, e), fmt::format("expected a number after '{}'", t[cb]));
          line.kind = LineKind::Bad;
          break;
        }
      } else {
        cmd.number = static_cast<int32_t>(neg ? -n : n);
        cmd.has_number = true;
      }
      if (p + 1 < e && t[p] == '.' && is_digit(t[p + 1])) {
        cmd.fraction = static_cast<int8_t>(t[p + 1] - '0');
        p += 2;
      }
      cmd.word = Span{cb, p};
    }
    // The parameters are lexed here for their errors and counted; ParamRange lexes them again on demand. Most
    // commands need no lexing for that: count_params counts them from the byte classes alone.
    if (!count_params(cmd, p, e)) lex_params(cmd, p, e);
    uint32_t end = p;
    while (end > cb && is_blank(t[end - 1])) --end;
    cmd.span = Span{cb, end};
    note_mode(cmd.letter, cmd.number, cmd.fraction);
    out_.commands.add(cmd);
    ++line.command_count;
  }
}

// The parameters of `cmd` from `p` (after its word) to the end of the command, counted with their flags, without
// making a Param: a value runs to the next letter outside quotes and braces, and an E or e after a digit is an
// exponent (docs/firmware-behaviour.md#parameters). At anything that the lexer reports or decides in a way this scan does not (an
// unclosed string or expression, a control character in a string, a blank before ':', a `'x` axis, a CNC comment,
// text before the first letter, a command that takes the rest of the line) it returns false and leaves `cmd` and
// `p` alone, and lex_params does the work. The tests hold both to the same counts and flags (tests/param_check.h,
// on every fixture, the corpus and the fuzz inputs).
bool LineParser::count_params(Command& cmd, uint32_t& pp, uint32_t e) const {
  if (cmd.number_expr || (cmd.fraction < 0 && takes_rest_of_line(cmd.letter, cmd.number))) return false;
  const auto* s = reinterpret_cast<const unsigned char*>(lex_.t.data());
  const uint8_t* const cls = kBytes.param;
  const char* const t = lex_.t.data();
  const auto n = static_cast<uint32_t>(lex_.t.size());
  // On the opening quote: the position after the closing one, or 0 when the lexer must see the string.
  auto skip_string = [&](uint32_t p) -> uint32_t {
    for (++p; p < e && s[p] != '"'; ++p)
      if (s[p] < 0x20) return 0;
    return p < e ? p + 1 : 0;
  };
  uint32_t p = pp, count = 0;
  uint32_t letters = 0;  // a bit per letter seen, 'A'..'Z'
  bool repeated = false, exponent = false;
  for (;;) {
    while (p < e && cls[s[p]] == ByteClasses::kBlank) ++p;
    if (p >= e) break;
    if (cls[s[p]] != ByteClasses::kLetter) return false;
    const unsigned u = s[p] & 0xDFu;  // upper case
    if (u == 'G' || u == 'M') break;    // the next command of the line
    const uint32_t bit = uint32_t{1} << (u - 'A');
    repeated = repeated || (letters & bit);
    letters |= bit;
    ++count;
    // The value.
    for (++p; (p = next_value_stop(t, n, p, e)) < e;) {
      switch (cls[s[p]]) {
        case ByteClasses::kPlain:
        case ByteClasses::kBlank:
          ++p;
          continue;
        case ByteClasses::kLetter:
          if ((s[p] | 0x20u) != 'e' || !is_digit(static_cast<char>(s[p - 1]))) break;
          exponent = true;
          ++p;
          continue;
        case ByteClasses::kQuote:
          if (!(p = skip_string(p))) return false;
          continue;
        case ByteClasses::kBrace: {
          const uint32_t open = p;
          int depth = 0;
          while (p < e && !(s[p] == '}' && --depth == 0)) {
            if (s[p] == '"') {
              if (!(p = skip_string(p))) return false;
              continue;
            }
            depth += s[p] == '{';
            ++p;
          }
          if (p >= e) return false;
          ++p;
          const char* msg = nullptr;
          uint32_t at = 0;
          if (!brace_expression_ok(lex_.t, open, p, &msg, &at)) return false;  // the lexer reports it
          continue;
        }
        case ByteClasses::kColon:
          if (is_blank(static_cast<char>(s[p - 1]))) return false;
          ++p;
          continue;
        case ByteClasses::kParen:
          if (lex_.cnc) return false;
          ++p;
          continue;
        default:  // kApostrophe
          if (p + 1 < e && is_alpha(static_cast<char>(s[p + 1]))) return false;
          ++p;
          continue;
      }
      break;  // a letter: the next parameter
    }
  }
  cmd.param_count = count;
  cmd.any_repeated_letter = repeated;
  cmd.any_exponent = exponent;
  pp = p;
  return true;
}

void LineParser::lex_params(Command& cmd, uint32_t& p, uint32_t e) {
  Param param;
    uint64_t letters = 0;  // a bit per letter seen: 'A'..'Z', then 'a'..'z'
    auto count = [&] {
      ++cmd.param_count;
      if (param.letter == 0) return;
      const uint64_t bit = uint64_t{1} << (param.letter >= 'a' ? param.letter - 'a' + 26 : param.letter - 'A');
      cmd.any_repeated_letter = cmd.any_repeated_letter || (letters & bit);
      letters |= bit;
    };
    if (lex_.first_param(cmd, p, e, param)) count();
    while (lex_.next_param(cmd, p, e, param)) {
      count();
      cmd.any_exponent = cmd.any_exponent || param.exponent_letter;
      cmd.any_blank_before_colon = cmd.any_blank_before_colon || param.blank_before_colon;
    }
}

void compute_blocks(ParsedFile& pf) {
  struct Open {
    uint32_t indent;
    MetaKind kind;  // what opened this block (If/Elif/Else/While, or None for a plain block)
    MetaKind last;  // meta kind of the last line at this level
  };
  std::vector<Open> stack{{0, MetaKind::None, MetaKind::None}};
  MetaKind prev_meta = MetaKind::None;
  bool saw_tabs = false, saw_spaces = false;
  for (size_t li = 0; li < pf.lines.recs_.size(); ++li) {
    detail::LineRec& line = pf.lines.recs_[li];
    const uint32_t indent = line.indent < 65535 ? line.indent : pf.lines.long_indent(li);
    const auto kind = static_cast<LineKind>(line.kind_meta & 7);
    const auto meta = static_cast<MetaKind>((line.kind_meta >> 3) & 15);
    if (line.flags & detail::kLineNumber) pf.any_line_number = true;
    if (kind != LineKind::Commands && kind != LineKind::Meta && kind != LineKind::Bad) continue;
    if (line.flags & detail::kIndentTabs) pf.any_tab_indent = true;
    while (stack.size() > 1 && indent < stack.back().indent) stack.pop_back();
    if (indent > stack.back().indent) {
      const bool opener = prev_meta == MetaKind::If || prev_meta == MetaKind::Elif || prev_meta == MetaKind::Else ||
                          prev_meta == MetaKind::While;
      stack.push_back({indent, opener ? prev_meta : MetaKind::None, MetaKind::None});
      if (line.flags & detail::kIndentTabs) saw_tabs = true;
      if (line.flags & detail::kIndentSpaces) saw_spaces = true;
    }
    for (size_t k = 1; k < stack.size(); ++k) {
      const MetaKind kk = stack[k].kind;
      if (kk == MetaKind::If || kk == MetaKind::Elif || kk == MetaKind::Else) line.flags |= detail::kConditional;
      if (kk == MetaKind::While) line.flags |= detail::kInLoop;
    }
    if ((line.flags & (detail::kConditional | detail::kInLoop)) && kind != LineKind::Meta) {
      const uint32_t count = line.command_count < 65535 ? line.command_count : pf.lines.big_count(li);
      auto& ranges = pf.block_commands;
      if (count > 0 && !ranges.empty() && ranges.back().second == line.first) ranges.back().second += count;
      else if (count > 0) ranges.emplace_back(line.first, line.first + count);
    }
    const Span code{line.code_begin, line.code_end};
    if (meta == MetaKind::Else || meta == MetaKind::Elif) {
      const MetaKind last = stack.back().last;
      if (last != MetaKind::If && last != MetaKind::Elif)
        pf.errors.push_back({code, fmt::format("'{}' did not follow 'if' at the same indentation", meta_keyword(meta))});
    }
    if ((meta == MetaKind::Break || meta == MetaKind::Continue) && !(line.flags & detail::kInLoop))
      pf.errors.push_back({code, fmt::format("'{}' was not inside a loop", meta_keyword(meta))});
    stack.back().last = meta;
    prev_meta = meta;
  }
  pf.mixed_indentation = saw_tabs && saw_spaces;
}

std::string_view meta_keyword(MetaKind k) {
  for (const auto& mw : kMetaWords)
    if (mw.kind == k) return mw.word;
  return "";
}

bool takes_unlettered_string(char letter, int32_t number) {
  if (letter != 'M') return false;
  switch (number) {
    case 23: case 28: case 30: case 32: case 36: case 117:  // unprecedented strings
      return true;
    default:
      return false;
  }
}

bool takes_rest_of_line(char letter, int32_t number) {
  // P may be unquoted for M98, M550 and M551.
  return takes_unlettered_string(letter, number) || (letter == 'M' && (number == 98 || number == 550 || number == 551));
}

ParamRange::iterator::iterator(std::string_view text, const Command& c) : t_(text), c_(c), done_(false) {
  pos_ = c.word.end;
  ++*this;
}

ParamRange::iterator& ParamRange::iterator::operator++() {
  const Lexer lex{t_, c_.cnc, nullptr};
  if (stage_ == 0) {
    stage_ = 1;
    if (lex.first_param(c_, pos_, c_.span.end, p_)) return *this;
  }
  if (!lex.next_param(c_, pos_, c_.span.end, p_)) done_ = true;
  return *this;
}

ParamRef ParsedFile::find(const Command& c, char letter) const {
  // The model and the rules ask one command for several letters in a row (M584 asks for every axis letter):
  // the parameters of the last command asked about are kept, per thread. They are lexed only as far as the
  // letters asked for need: RRF takes the first parameter with a letter, so a find stops at it.
  thread_local struct {
    uint64_t serial = 0;  // ParsedFile::serial: unique per parse, so a new parse never meets a stale entry
    Span span;
    std::vector<Param> params;  // lexed so far
    ParamRange::iterator next;  // where lexing goes on
  } last;
  if (last.serial != serial || last.span != c.span || serial == 0) {
    last.params.clear();
    last.next = params(c).begin();
    last.serial = serial;
    last.span = c.span;
  } else {
    for (const Param& p : last.params)
      if (p.letter == letter) return ParamRef(p);
  }
  for (; last.next != ParamRange::iterator(); ++last.next) {
    last.params.push_back(*last.next);
    if (last.params.back().letter == letter) {
      ++last.next;
      return ParamRef(last.params.back());
    }
  }
  return ParamRef();
}

void LineParser::parse_lines(uint32_t from, uint32_t to, bool any_nul, bool any_del) {
  const SourceFile& file = *out_.source;
  const std::string_view t = file.text();
  for (uint32_t i = from; i < to; ++i) {
    const Span ls = file.line_span(i);
    uint32_t b = ls.begin;
    // A UTF-8 byte-order mark: RRF118 byte-order-mark reports it; the line is read as the author wrote it.
    if (b == 0 && t.starts_with("\xEF\xBB\xBF")) b = std::min<uint32_t>(3, ls.end);
    bool after_nul = false;
    for (;;) {
      const void* nul = any_nul ? std::memchr(t.data() + b, '\0', ls.end - b) : nullptr;
      const uint32_t e = nul ? static_cast<uint32_t>(static_cast<const char*>(nul) - t.data()) : ls.end;
      next_cnc_ = lex_.cnc;
      next_laser_ = laser_;
      parse_logical_line(b, e, after_nul, any_del);
      lex_.cnc = next_cnc_;
      laser_ = next_laser_;
      if (any_nul) out_.lines.spans_.push_back(Span{b, e});
      if (!nul) break;
      out_.errors.push_back({Span{e, e + 1}, "NUL byte: RRF ends the line here and reads the rest as a new line"});
      b = e + 1;
      after_nul = true;
    }
  }
}

// Appends `part` (lines [first, end) of the file, already in place in pf.lines) to `pf`: its line records are
// re-pointed at the joined command and meta-command tables.
void LineParser::join_part(ParsedFile& pf, ParsedFile&& part, uint32_t first, uint32_t end) {
  const auto cmd_base = static_cast<uint32_t>(pf.commands.size());
  const auto meta_base = static_cast<uint32_t>(pf.lines.metas_.size());
  for (uint32_t i = first; i < end; ++i) {
    detail::LineRec& r = pf.lines.recs_[i];
    const auto kind = static_cast<LineKind>(r.kind_meta & 7);
    if (kind == LineKind::Commands || kind == LineKind::Bad) r.first += cmd_base;
    else if (kind == LineKind::Meta) r.first += meta_base;
  }
  pf.lines.metas_.insert(pf.lines.metas_.end(), part.lines.metas_.begin(), part.lines.metas_.end());
  pf.lines.big_counts_.merge(part.lines.big_counts_);  // keyed by line: already the file's indices
  pf.lines.long_lines_.merge(part.lines.long_lines_);
  pf.commands.append(std::move(part.commands));
  pf.errors.insert(pf.errors.end(), std::make_move_iterator(part.errors.begin()), std::make_move_iterator(part.errors.end()));
  pf.semicolon_cuts.insert(pf.semicolon_cuts.end(), part.semicolon_cuts.begin(), part.semicolon_cuts.end());
}

// A file without NUL bytes has one logical line per editor line, so each part writes its line records in place.
// A part's commands are counted from 0 until it is joined. A part starts in FFF mode (or the caller's mode, for
// the first); if the part before it ends in the other mode, it is parsed again once that is known.
void LineParser::parse_in_parts(ParsedFile& pf, const ParseOptions& opts, unsigned parts, bool any_del) {
  const SourceFile& file = *pf.source;
  std::vector<uint32_t> first(parts + 1, 0);
  first[parts] = file.line_count();
  for (unsigned j = 1; j < parts; ++j)
    first[j] = std::max(first[j - 1], file.line_of(static_cast<uint32_t>(uint64_t{file.size()} * j / parts)));
  reserve_huge(pf.lines.recs_, file.line_count());
  pf.lines.recs_.resize(file.line_count());  // not initialised (DefaultInit): each part writes its lines
  struct Part {
    ParsedFile out;
    bool cnc_in = false, cnc_out = false, laser_in = false, laser_out = false;
  };
  std::vector<Part> ps(parts);
  ps[0].cnc_in = opts.cnc_mode;
  ps[0].laser_in = opts.laser_mode;
  auto run = [&](size_t j) {
    Part& p = ps[j];
    ParsedFile& out = j == 0 ? pf : p.out;  // the first part goes straight into the result
    if (j > 0) {
      out = ParsedFile{};
      out.source = &file;
      out.lines.source_ = &file;
    }
    reserve_huge(out.commands.recs_, first[j + 1] - first[j] + 1);
    LineParser lp(out, p.cnc_in, p.laser_in, pf.lines.recs_.data(), first[j]);
    lp.fast_lines = opts.fast_lines;
    lp.rich_ = &pf.rich_lines;
    lp.parens_ = &pf.paren_lines;
    lp.apostrophes_ = &pf.apostrophe_lines;
    lp.colon_comments_ = &pf.colon_comment_lines;
    lp.parse_lines(first[j], first[j + 1], false, any_del);
    p.cnc_out = lp.lex_.cnc;
    p.laser_out = lp.laser_;
  };
  run_tasks(parts, std::min(parts, opts.threads), run);
  for (unsigned j = 1; j < parts; ++j) {
    if (ps[j].cnc_in != ps[j - 1].cnc_out || ps[j].laser_in != ps[j - 1].laser_out) {
      ps[j].cnc_in = ps[j - 1].cnc_out;
      ps[j].laser_in = ps[j - 1].laser_out;
      pf.rich_lines.clear(first[j], first[j + 1]);
      for (LineSet* set : {&pf.paren_lines, &pf.apostrophe_lines, &pf.colon_comment_lines}) set->clear(first[j], first[j + 1]);
      run(j);
    }
  }
  for (unsigned j = 1; j < parts; ++j) join_part(pf, std::move(ps[j].out), first[j], first[j + 1]);
}

// Sorts the commands by code: a counting sort whose counts the parse kept (CommandTable::push_rec), so one sweep
// of the records places them. Only the keys the file uses are kept (a few dozen, where the counts have 2,050).
void index_codes(ParsedFile& pf) {
  CommandTable& t = pf.commands;
  pf.code_keys_.clear();
  pf.code_start_.assign(1, 0);
  std::vector<uint32_t>& at = t.key_counts_;  // each key's count, then where its next command goes
  uint32_t pos = 0;
  for (size_t k = 0; k < at.size(); ++k) {
    const uint32_t count = at[k];
    at[k] = pos;
    if (count == 0) continue;
    pos += count;
    pf.code_keys_.push_back(static_cast<uint16_t>(k));
    pf.code_start_.push_back(pos);
  }
  pf.code_order_.resize(t.size());
  t.each_rec([&](size_t i, const detail::CommandRec& r) {
    pf.code_order_[at[code_key(detail::letter_of(r.bits), r.number)]++] = static_cast<uint32_t>(i);
  });
  std::vector<uint32_t>().swap(t.key_counts_);  // used up
  pf.fraction_keys_ = t.fraction_keys_;
  std::sort(pf.fraction_keys_.begin(), pf.fraction_keys_.end());
  pf.fraction_keys_.erase(std::unique(pf.fraction_keys_.begin(), pf.fraction_keys_.end()), pf.fraction_keys_.end());
  pf.any_exponent = t.all_bits_ & detail::kAnyExponent;
  pf.any_blank_before_colon = t.all_bits_ & detail::kAnyBlankColon;
  pf.any_repeated_letter = t.all_bits_ & detail::kAnyRepeat;
}

CodeCommands ParsedFile::run(size_t j) const {
  const uint32_t* base = code_order_.data();
  return CodeCommands(base + code_start_[j], base + code_start_[j + 1], &commands, source->text().data());
}

CodeCommands ParsedFile::with_code(char letter, int32_t number) const {
  const uint16_t key = code_key(letter, number);
  return key == kNoKey ? CodeCommands() : of_key(key);
}

CodeCommands ParsedFile::unlisted_codes() const { return of_key(kNoKey); }

CodeCommands ParsedFile::of_key(uint16_t key) const {
  const auto it = std::lower_bound(code_keys_.begin(), code_keys_.end(), key);
  if (it == code_keys_.end() || *it != key) return CodeCommands();
  return run(static_cast<size_t>(it - code_keys_.begin()));
}

std::vector<ParsedFile::UsedCode> ParsedFile::used_codes() const {
  std::vector<UsedCode> out;
  for (size_t j = 0; j < code_keys_.size(); ++j) {
    const uint16_t key = code_keys_[j];
    if (key == kNoKey) continue;
    const char letter = key == kTKey ? 'T' : key >= 1024 ? 'M' : 'G';
    const int32_t number = key == kTKey ? -1 : key % 1024;
    const bool fraction = std::binary_search(fraction_keys_.begin(), fraction_keys_.end(), key);
    out.push_back(UsedCode{letter, number, fraction, run(j)});
  }
  return out;
}

ParsedFile parse(const SourceFile& file, const ParseOptions& opts) {
  static std::atomic<uint64_t> serials{0};
  ParsedFile pf;
  pf.serial = ++serials;
  pf.source = &file;
  pf.lines.source_ = &file;
  pf.rich_lines.resize(file.line_count() + 1);  // NUL bytes add logical lines: insert() grows the set then
  for (LineSet* set : {&pf.paren_lines, &pf.apostrophe_lines, &pf.colon_comment_lines}) set->resize(file.line_count() + 1);
  const bool any_nul = file.any_nul();
  const bool any_del = file.any_del();
  // Four parts per thread, so that a thread slowed down (another process, a part with longer lines) is made up
  // for by the others taking more parts.
  const size_t parts = any_nul || opts.threads < 2 || opts.part_bytes == 0
                           ? 1
                           : std::min<size_t>(size_t{4} * opts.threads, file.size() / opts.part_bytes);
  if (parts > 1) {
    LineParser::parse_in_parts(pf, opts, static_cast<unsigned>(parts), any_del);
  } else {
    // Exact for lines (plus NUL splits); a config has about one command per line. Reserved, untouched pages
    // cost no memory, and no vector is copied while it grows on large files.
    reserve_huge(pf.lines.recs_, file.line_count() + 1);
    reserve_huge(pf.commands.recs_, file.line_count() + 1);
    LineParser lp(pf, opts.cnc_mode, opts.laser_mode);
    lp.fast_lines = opts.fast_lines;
    lp.parse_lines(0, file.line_count(), any_nul, any_del);
  }
  trace::mark("parse: lines");
  // Blocks (the lines) and the code index (the commands) touch different fields: a large file does both at once.
  run_tasks(2, parts > 1 ? 2u : 1u, [&](size_t k) {
    const trace::Scope time(k == 0 ? "blocks" : "code index");
    k == 0 ? compute_blocks(pf) : index_codes(pf);
  });
  return pf;
}

}  // namespace rrflint
