// RRF's expression grammar, checked without evaluating anything (ExprSyntax): in {…} parameters and in meta
// commands (LineParser::check_meta_syntax), and the messages about it.

#include "lint/base/strings.h"
#include "lint/syntax/parse_internal.h"

namespace rrflint {

namespace {

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
      case '"': return quoted(p);
      case '\'':  // a character literal 'x'
        p += 2;
        if (p > e_ || at_char(p) != '\'') return fail(std::min(p, e_), "expected \"'\"");
        ++p;
        return true;
      case '-':
      case '+':
      case '!': ++p; return operand(p, depth + 1);
      case '#': p = skip(p + 1); return is_alpha(at_char(p)) ? identifier(p, depth + 1) : operand(p, depth + 1);
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
      while (p < e_ &&
             (x == 'x' ? std::isxdigit(static_cast<unsigned char>(t_[p])) != 0 : (t_[p] == '0' || t_[p] == '1')))
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

}  // namespace

// "'…'" or "the end": where an expression error is, for a message.
std::string error_place(std::string_view t, uint32_t at, uint32_t e) {
  if (at >= e) return "at the end";
  // A byte-wise scan may stop inside a character (after the first byte of `'é'`): quote from the character's start.
  at = static_cast<uint32_t>(utf8_start(t, at));
  std::string_view rest = t.substr(at, e - at);
  if (rest.size() > 16) return fmt::format("at '{}…'", utf8_prefix(rest, 16));
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
        if (is_blank(c))
          note = " (standalone RRF wants the file name straight after '>'; DSF in SBC mode skips the blank)";
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
  error(std::min(x.at, e > b ? e - 1 : b), e,
        fmt::format("{} in {}, {}{}", x.msg, where, error_place(t, x.at, e), note));
}

}  // namespace rrflint
