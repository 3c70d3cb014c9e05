// The lexer of values and parameters (Lexer), and the parameters handed out again on demand (ParamRange, find).

#include "lint/syntax/parse_internal.h"

namespace rrflint {

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

bool takes_unlettered_string(char letter, int32_t number) {
  if (letter != 'M') return false;
  switch (number) {
    case 23:
    case 28:
    case 30:
    case 32:
    case 36:
    case 117:  // unprecedented strings
      return true;
    default: return false;
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

}  // namespace rrflint
