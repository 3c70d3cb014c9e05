#include "parser.h"

#include <cstring>

#include <fmt/format.h>

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

class LineParser {
 public:
  LineParser(ParsedFile& out, const ParseOptions& opts) : out_(out), t_(out.source->text()), cnc_(opts.cnc_mode) {}

  void parse_logical_line(uint32_t b, uint32_t e, bool after_nul);

 private:
  void error(uint32_t b, uint32_t e, std::string msg) { out_.errors.push_back({Span{b, e}, std::move(msg)}); }
  // Skips a quoted string starting at `p` (on the opening quote). Returns the position after it, or `e` and
  // records an error when the string is not closed.
  uint32_t skip_string(uint32_t p, uint32_t e);
  // Skips a {…} expression starting at `p` (on '{'). Strings inside are skipped whole.
  uint32_t skip_braces(uint32_t p, uint32_t e);
  uint32_t skip_blanks(uint32_t p, uint32_t e);
  // Did a ';' cut an open expression at `e`, the end of the code? Only when the comment after it holds the
  // `closer` the expression lacks: `X{a ; b}` is cut, `X{a ; note` just misses its '}'.
  bool cut_by_semicolon(uint32_t e, char closer) const {
    while (e < t_.size() && is_blank(t_[e])) ++e;
    if (e >= t_.size() || t_[e] != ';') return false;
    for (; e < t_.size() && t_[e] != '\n' && t_[e] != '\r' && t_[e] != '\0'; ++e)
      if (t_[e] == closer) return true;
    return false;
  }
  void parse_meta(Line& line, MetaKind kind, uint32_t after_kw, uint32_t e);
  void parse_commands(Line& line, uint32_t b, uint32_t e);
  void check_expression(uint32_t b, uint32_t e, std::string_view what);
  uint32_t parse_value(uint32_t p, uint32_t e, Param& param);

  ParsedFile& out_;
  std::string_view t_;
  bool cnc_;
};

uint32_t LineParser::skip_blanks(uint32_t p, uint32_t e) {
  for (;;) {
    while (p < e && is_blank(t_[p])) ++p;
    if (cnc_ && p < e && t_[p] == '(') {  // CNC-mode ( ) comment, treated as a blank
      while (p < e && t_[p] != ')') ++p;
      if (p < e) ++p;
      continue;
    }
    return p;
  }
}

uint32_t LineParser::skip_string(uint32_t p, uint32_t e) {
  const uint32_t start = p++;
  while (p < e) {
    char c = t_[p];
    if (c == '"') {
      if (p + 1 < e && t_[p + 1] == '"') {
        p += 2;
        continue;
      }
      return p + 1;
    }
    if (static_cast<unsigned char>(c) < 0x20 && c != '\t') break;
    if (c == '\t') {
      error(p, p + 1, "control character in string: a tab inside quotes is rejected by RRF");
    }
    ++p;
  }
  error(start, e, "unterminated string: a quoted string must end with '\"' on the same line");
  return e;
}

uint32_t LineParser::skip_braces(uint32_t p, uint32_t e) {
  const uint32_t start = p;
  int depth = 0;
  while (p < e) {
    char c = t_[p];
    if (c == '"') {
      p = skip_string(p, e);
      continue;
    }
    if (c == '{') ++depth;
    else if (c == '}') {
      if (--depth == 0) return p + 1;
    }
    ++p;
  }
  // A ';' that cut the line is RRF113's finding (semicolon-in-expression), not a syntax error.
  if (cut_by_semicolon(e, '}')) out_.semicolon_cuts.push_back(Span{start, e});
  else error(start, e, "unterminated '{': the expression has no closing '}'");
  return e;
}

void LineParser::check_expression(uint32_t b, uint32_t e, std::string_view what) {
  // Parsed just far enough to know it is an expression: balanced brackets and closed strings.
  std::string stack;
  for (uint32_t p = b; p < e; ++p) {
    char c = t_[p];
    if (c == '"') {
      p = skip_string(p, e) - 1;
      continue;
    }
    if (c == '\'' && p + 2 < e && t_[p + 2] == '\'') {  // character literal 'x' (3.5+)
      p += 2;
      continue;
    }
    if (c == '(' || c == '[' || c == '{') stack.push_back(c);
    else if (c == ')' || c == ']' || c == '}') {
      char want = c == ')' ? '(' : c == ']' ? '[' : '{';
      if (stack.empty() || stack.back() != want) {
        error(p, p + 1, fmt::format("unbalanced '{}' in {}", c, what));
        return;
      }
      stack.pop_back();
    }
  }
  if (!stack.empty()) {
    const char closer = stack.back() == '(' ? ')' : stack.back() == '[' ? ']' : '}';
    if (cut_by_semicolon(e, closer)) out_.semicolon_cuts.push_back(Span{b, e});
    else error(b, e, fmt::format("unclosed '{}' in {}", stack.back(), what));
  }
}

void LineParser::parse_logical_line(uint32_t b, uint32_t e, bool after_nul) {
  Line line;
  line.span = Span{b, e};
  line.after_nul = after_nul;
  uint32_t p = b;
  // Indentation: a blank counts 1, a tab advances to the next multiple of 4.
  while (p < e && is_blank(t_[p])) {
    if (t_[p] == '\t') {
      line.indent = (line.indent + 4) & ~3u;
      line.indent_tabs = true;
    } else {
      ++line.indent;
      line.indent_spaces = true;
    }
    ++p;
  }
  // 0x7F discards the rest of the line.
  for (uint32_t k = p; k < e; ++k) {
    if (t_[k] == '\x7f') {
      error(k, e, "byte 0x7F: RRF discards the rest of the line from here");
      e = k;
      break;
    }
  }
  if (p >= e) {
    out_.lines.push_back(line);
    return;
  }
  if (t_[p] == ';') {
    line.comment = Span{p, e};
    line.kind = line.indent == 0 ? LineKind::Comment : LineKind::Blank;
    out_.lines.push_back(line);
    return;
  }
  // Optional line number N<digits>.
  if ((t_[p] == 'N' || t_[p] == 'n') && p + 1 < e && is_digit(t_[p + 1])) {
    line.line_number = true;
    ++p;
    while (p < e && is_digit(t_[p])) ++p;
    while (p < e && is_blank(t_[p])) ++p;
  }
  const uint32_t code_begin = p;
  // Find the end of the code: ';' outside quotes (braces do not protect it), '*' after N outside braces.
  uint32_t code_end = e;
  uint32_t paren_chars = 0;
  {
    bool in_quote = false;
    int braces = 0;
    for (uint32_t k = p; k < e; ++k) {
      char c = t_[k];
      if (in_quote) {
        if (c == '"') in_quote = false;  // "" re-enters at once: same result
        continue;
      }
      if (c == '"') in_quote = true;
      else if (c == '{') ++braces;
      else if (c == '}') braces = braces > 0 ? braces - 1 : 0;
      else if (c == ';') {
        code_end = k;
        line.comment = Span{k, e};
        break;
      } else if (c == '*' && line.line_number && braces == 0) {
        code_end = k;
        line.checksum = true;
        uint32_t q = k + 1;
        while (q < e && t_[q] != ';') ++q;
        if (q < e) line.comment = Span{q, e};
        break;
      } else if (c == '(' && cnc_ && braces == 0) {
        uint32_t q = k;
        while (q < e && t_[q] != ')') ++q;
        paren_chars += (q < e ? q + 1 : e) - k;
        k = q < e ? q : e - 1;
      }
    }
  }
  line.stored_length = code_end - code_begin - paren_chars;
  uint32_t ce = code_end;
  while (ce > code_begin && is_blank(t_[ce - 1])) --ce;
  line.code = Span{code_begin, ce};
  if (ce == code_begin) {
    out_.lines.push_back(line);
    return;
  }
  // Meta command: 2-8 lowercase letters followed by end, blank, '{', '"' or '('.
  {
    uint32_t q = code_begin;
    while (q < ce && t_[q] >= 'a' && t_[q] <= 'z' && q - code_begin <= 8) ++q;
    uint32_t len = q - code_begin;
    if (len >= 2 && len <= 8 && (q == ce || is_blank(t_[q]) || t_[q] == '{' || t_[q] == '"' || t_[q] == '(')) {
      std::string_view word = t_.substr(code_begin, len);
      for (const auto& mw : kMetaWords) {
        if (mw.word == word) {
          line.kind = LineKind::Meta;
          line.meta = mw.kind;
          parse_meta(line, mw.kind, q, ce);
          out_.lines.push_back(line);
          return;
        }
      }
    }
  }
  parse_commands(line, code_begin, ce);
  out_.lines.push_back(line);
}

void LineParser::parse_meta(Line& line, MetaKind kind, uint32_t p, uint32_t e) {
  p = skip_blanks(p, e);
  line.meta_arg = Span{p, e};
  const std::string_view kw = meta_keyword(kind);
  switch (kind) {
    case MetaKind::If:
    case MetaKind::Elif:
    case MetaKind::While:
      if (p >= e) error(line.code.begin, e, fmt::format("expected a condition after '{}'", kw));
      else check_expression(p, e, fmt::format("the '{}' condition", kw));
      break;
    case MetaKind::Else:
      if (p < e) error(p, e, "unexpected characters after 'else' (use 'elif' for a condition)");
      break;
    case MetaKind::Var:
    case MetaKind::Global:
    case MetaKind::Set: {
      uint32_t q = p;
      if (kind == MetaKind::Set) {
        std::string_view rest = t_.substr(p, e - p);
        if (rest.starts_with("var.")) q += 4;
        else if (rest.starts_with("global.")) q += 7;
        else {
          error(p, e, "expected a global or local variable after 'set' ('var.name' or 'global.name')");
          return;
        }
      }
      uint32_t name_begin = q;
      if (q < e && is_alpha(t_[q])) {
        ++q;
        while (q < e && (is_alpha(t_[q]) || is_digit(t_[q]) || t_[q] == '_')) ++q;
      }
      if (q == name_begin) {
        error(p, e, fmt::format("expected a {}variable name after '{}'", kind == MetaKind::Set ? "" : "new ", kw));
        return;
      }
      line.meta_name = Span{kind == MetaKind::Set ? p : name_begin, q};
      if (q - name_begin > 120) error(name_begin, q, "variable name longer than 120 characters");
      if (kind == MetaKind::Set) {  // optional indices [i]
        while (q < e && t_[q] == '[') {
          uint32_t r = q;
          int d = 0;
          for (; r < e; ++r) {
            if (t_[r] == '[') ++d;
            else if (t_[r] == ']' && --d == 0) break;
          }
          if (r >= e) {
            error(q, e, "unclosed '[' in the variable index");
            return;
          }
          q = r + 1;
        }
      }
      q = skip_blanks(q, e);
      if (q >= e || t_[q] != '=') {
        error(q < e ? q : e, e, "expected '='");
        return;
      }
      q = skip_blanks(q + 1, e);
      if (q >= e) {
        error(line.code.begin, e, "expected an expression after '='");
        return;
      }
      line.meta_arg = Span{q, e};
      check_expression(q, e, "the expression");
      break;
    }
    case MetaKind::Echo:
    case MetaKind::Abort:
      if (p < e) check_expression(p, e, fmt::format("the '{}' arguments", kw));
      break;
    default:
      break;
  }
}

uint32_t LineParser::parse_value(uint32_t p, uint32_t e, Param& param) {
  // A value runs to the next parameter letter (or G/M command letter) outside quotes and braces.
  // An E or e straight after a digit is an exponent, not a parameter (rrf-semantics §1.8).
  uint32_t vb = skip_blanks(p, e);
  uint32_t q = vb;
  bool colon = false;
  while (q < e) {
    char c = t_[q];
    if (c == '"') {
      q = skip_string(q, e);
      continue;
    }
    if (c == '{') {
      param.has_expr = true;
      q = skip_braces(q, e);
      continue;
    }
    if (cnc_ && c == '(') break;
    if (is_alpha(c)) {
      if ((c == 'E' || c == 'e') && q > vb && is_digit(t_[q - 1])) {
        param.exponent_letter = true;
        ++q;
        if (q < e && (t_[q] == '+' || t_[q] == '-')) ++q;
        continue;
      }
      break;
    }
    if (c == '\'' && q + 1 < e && is_alpha(t_[q + 1])) break;
    if (c == ':') {
      colon = true;
      if (q > vb && is_blank(t_[q - 1])) param.blank_before_colon = true;
    }
    ++q;
  }
  uint32_t ve = q;
  while (ve > vb && is_blank(t_[ve - 1])) --ve;
  param.value = Span{vb, ve};
  if (vb == ve) param.kind = ValueKind::None;
  else {
    char f = t_[vb];
    if (colon) param.kind = ValueKind::List;
    else if (f == '"') param.kind = ValueKind::String;
    else if (f == '{') param.kind = ValueKind::Expression;
    else if (is_digit(f) || f == '-' || f == '+' || f == '.') param.kind = ValueKind::Number;
    else param.kind = ValueKind::Text;
  }
  return q;
}

void LineParser::parse_commands(Line& line, uint32_t b, uint32_t e) {
  line.kind = LineKind::Commands;
  line.first_command = static_cast<uint32_t>(out_.commands.size());
  const auto line_index = static_cast<uint32_t>(out_.lines.size());
  uint32_t p = b;
  bool first = true;
  while (true) {
    p = skip_blanks(p, e);
    if (p >= e) break;
    Command cmd;
    cmd.line = line_index;
    const uint32_t cb = p;
    char L = upper(t_[p]);
    if (L != 'G' && L != 'M' && L != 'T') {
      if (first) {
        std::string_view text = t_.substr(b, e - b);
        if (text.size() > 40) text = text.substr(0, 40);
        bool kw_case = false;
        for (const auto& mw : kMetaWords) {
          std::string_view w = mw.word;
          if (e - b >= w.size()) {
            bool eq = true;
            for (size_t k = 0; k < w.size(); ++k) eq = eq && lower(t_[b + k]) == w[k];
            if (eq && (e - b == w.size() || !is_alpha(t_[b + w.size()]))) kw_case = true;
          }
        }
        error(b, e, kw_case ? fmt::format("Bad command: '{}': meta-command keywords must be lowercase", text)
                            : fmt::format("Bad command: '{}': a line must start with G, M or T", text));
        line.kind = LineKind::Bad;
      }
      break;
    }
    first = false;
    cmd.letter = L;
    ++p;
    if (L == 'T' && p < e && t_[p] == '{') {
      uint32_t q = skip_braces(p, e);
      cmd.number_expr = true;
      cmd.word = Span{cb, q};
      // T{expr} is T with a T parameter: record the expression as that parameter.
      Param tp;
      tp.letter = 'T';
      tp.span = Span{p, q};
      tp.value = Span{p, q};
      tp.kind = ValueKind::Expression;
      tp.has_expr = true;
      cmd.first_param = static_cast<uint32_t>(out_.params.size());
      out_.params.push_back(tp);
      cmd.param_count = 1;
      p = q;
    } else {
      bool neg = false;
      if (p < e && t_[p] == '-' && p + 1 < e && is_digit(t_[p + 1])) {
        neg = true;
        ++p;
      }
      uint32_t db = p;
      int64_t n = 0;
      while (p < e && is_digit(t_[p])) {
        if (n < 100000000) n = n * 10 + (t_[p] - '0');
        ++p;
      }
      if (p == db) {
        if (L != 'T') {
          error(cb, std::min(cb + 1, e), fmt::format("expected a number after '{}'", t_[cb]));
          line.kind = LineKind::Bad;
          break;
        }
      } else {
        cmd.number = static_cast<int32_t>(neg ? -n : n);
        cmd.has_number = true;
      }
      if (p + 1 < e && t_[p] == '.' && is_digit(t_[p + 1])) {
        cmd.fraction = static_cast<int8_t>(t_[p + 1] - '0');
        p += 2;
      }
      cmd.word = Span{cb, p};
      cmd.first_param = static_cast<uint32_t>(out_.params.size());
    }
    const bool rest_of_line = takes_rest_of_line(cmd.letter, cmd.number) && cmd.fraction < 0;
    // Unprecedented string commands (M117 text, M23 file) take everything after the code as one string.
    const bool unlettered = rest_of_line && cmd.letter == 'M' &&
                            (cmd.number == 117 || cmd.number == 23 || cmd.number == 28 || cmd.number == 30 ||
                             cmd.number == 32 || cmd.number == 36);
    if (unlettered) {
      uint32_t q = skip_blanks(p, e);
      if (q < e) {
        Param tp;
        tp.letter = 0;
        tp.span = tp.value = Span{q, e};
        tp.kind = t_[q] == '"' ? ValueKind::String : t_[q] == '{' ? ValueKind::Expression : ValueKind::Text;
        if (tp.kind == ValueKind::String) {
          uint32_t r = skip_string(q, e);
          tp.span = tp.value = Span{q, r};
        }
        out_.params.push_back(tp);
        ++cmd.param_count;
      }
      p = e;
    }
    for (;;) {
      p = skip_blanks(p, e);
      if (p >= e) break;
      char c = t_[p];
      if (c == 'G' || c == 'g' || c == 'M' || c == 'm') break;  // the next command on this line
      Param param;
      const uint32_t pb = p;
      if (c == '\'' && p + 1 < e && is_alpha(t_[p + 1])) {
        param.letter = lower(t_[p + 1]);
        p += 2;
      } else if (is_alpha(c)) {
        param.letter = upper(c);
        ++p;
      } else {
        // Stray text before the first letter (RRF skips it); keep it as an unlettered parameter.
        param.letter = 0;
      }
      if (rest_of_line && param.letter == 'P' && p < e && t_[p] != '"' && t_[p] != '{') {
        param.value = Span{p, e};
        param.kind = p < e ? ValueKind::Text : ValueKind::None;
        p = e;
      } else if (param.letter == 0) {
        uint32_t q = p;
        while (q < e && !is_alpha(t_[q])) {
          if (t_[q] == '"') q = skip_string(q, e);
          else if (t_[q] == '{') q = skip_braces(q, e);
          else ++q;
        }
        param.value = Span{p, q};
        while (param.value.end > param.value.begin && is_blank(t_[param.value.end - 1])) --param.value.end;
        param.kind = ValueKind::Text;
        p = q;
      } else {
        p = parse_value(p, e, param);
      }
      param.span = Span{pb, param.value.empty() ? (param.letter >= 'a' ? pb + 2 : pb + 1) : param.value.end};
      out_.params.push_back(param);
      ++cmd.param_count;
    }
    uint32_t end = p;
    while (end > cb && is_blank(t_[end - 1])) --end;
    cmd.span = Span{cb, end};
    out_.commands.push_back(cmd);
    ++line.command_count;
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
  for (Line& line : pf.lines) {
    if (line.kind != LineKind::Commands && line.kind != LineKind::Meta && line.kind != LineKind::Bad) continue;
    while (stack.size() > 1 && line.indent < stack.back().indent) stack.pop_back();
    if (line.indent > stack.back().indent) {
      bool opener = prev_meta == MetaKind::If || prev_meta == MetaKind::Elif || prev_meta == MetaKind::Else ||
                    prev_meta == MetaKind::While;
      stack.push_back({line.indent, opener ? prev_meta : MetaKind::None, MetaKind::None});
      if (line.indent_tabs) saw_tabs = true;
      if (line.indent_spaces) saw_spaces = true;
    }
    for (size_t k = 1; k < stack.size(); ++k) {
      MetaKind kk = stack[k].kind;
      if (kk == MetaKind::If || kk == MetaKind::Elif || kk == MetaKind::Else) line.conditional = true;
      if (kk == MetaKind::While) line.in_loop = true;
    }
    if (line.meta == MetaKind::Else || line.meta == MetaKind::Elif) {
      MetaKind last = stack.back().last;
      if (last != MetaKind::If && last != MetaKind::Elif) {
        pf.errors.push_back({line.code, fmt::format("'{}' did not follow 'if' at the same indentation",
                                                    meta_keyword(line.meta))});
      }
    }
    if ((line.meta == MetaKind::Break || line.meta == MetaKind::Continue) && !line.in_loop) {
      pf.errors.push_back({line.code, fmt::format("'{}' was not inside a loop", meta_keyword(line.meta))});
    }
    stack.back().last = line.meta;
    prev_meta = line.meta;
  }
  pf.mixed_indentation = saw_tabs && saw_spaces;
}

}  // namespace

std::string_view meta_keyword(MetaKind k) {
  for (const auto& mw : kMetaWords)
    if (mw.kind == k) return mw.word;
  return "";
}

bool takes_rest_of_line(char letter, int32_t number) {
  if (letter != 'M') return false;
  switch (number) {
    case 23: case 28: case 30: case 32: case 36: case 117:  // unprecedented strings
    case 98: case 550: case 551:                             // P may be unquoted
      return true;
    default:
      return false;
  }
}

const Param* ParsedFile::find(const Command& c, char letter) const {
  for (const Param* p = param_begin(c); p != param_end(c); ++p)
    if (p->letter == letter) return p;
  return nullptr;
}

ParsedFile parse(const SourceFile& file, const ParseOptions& opts) {
  ParsedFile pf;
  pf.source = &file;
  const std::string_view t = file.text();
  pf.lines.reserve(file.line_count() + 1);
  pf.commands.reserve(file.line_count());
  pf.params.reserve(file.line_count() * 3);
  ParseOptions o = opts;
  for (uint32_t i = 0; i < file.line_count(); ++i) {
    Span ls = file.line_span(i);
    uint32_t b = ls.begin;
    bool after_nul = false;
    for (;;) {
      const void* nul = std::memchr(t.data() + b, '\0', ls.end - b);
      uint32_t e = nul ? static_cast<uint32_t>(static_cast<const char*>(nul) - t.data()) : ls.end;
      LineParser lp(pf, o);
      const size_t before = pf.commands.size();
      lp.parse_logical_line(b, e, after_nul);
      // Track the machine mode for ( ) comments: M453 = CNC, M451/M452 = not.
      for (size_t k = before; k < pf.commands.size(); ++k) {
        const Command& c = pf.commands[k];
        if (c.letter == 'M' && c.fraction < 0) {
          if (c.number == 453) o.cnc_mode = true;
          else if (c.number == 451 || c.number == 452) o.cnc_mode = false;
        }
      }
      if (!nul) break;
      pf.errors.push_back({Span{e, e + 1}, "NUL byte: RRF ends the line here and reads the rest as a new line"});
      b = e + 1;
      after_nul = true;
    }
  }
  compute_blocks(pf);
  return pf;
}

}  // namespace rrflint
