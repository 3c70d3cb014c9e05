// The full line parser: logical lines, meta commands and their expressions, commands, and blocks.

#include "lint/base/strings.h"
#include "lint/syntax/parse_internal.h"

namespace rrflint {

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
      error(k, e,
            k > p ? "byte 0x7F: RRF discards the whole line, the text before this byte too"
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
    default: break;
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
        text = utf8_prefix(text, 40);
        bool kw_case = false;
        for (const auto& mw : kMetaWords) {
          const std::string_view w = mw.word;
          if (e - b >= w.size()) {
            bool eq = true;
            for (size_t k = 0; k < w.size(); ++k) eq = eq && lower(t[b + k]) == w[k];
            if (eq && (e - b == w.size() || !is_alpha(t[b + w.size()]))) kw_case = true;
          }
        }
        error(b, e,
              kw_case ? fmt::format("Bad command: '{}': meta-command keywords must be lowercase", text)
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
    // The parameters are lexed here for their errors and counted; ParamRange lexes them again on demand. (A
    // shortcut that counted them from byte classes alone was measured to save nothing and is gone: bench/RESULTS.md.)
    lex_params(cmd, p, e);
    uint32_t end = p;
    while (end > cb && is_blank(t[end - 1])) --end;
    cmd.span = Span{cb, end};
    note_mode(cmd.letter, cmd.number, cmd.fraction);
    out_.commands.add(cmd);
    ++line.command_count;
  }
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
    if (line.flags & detail::kLineNumber) pf.prefilters.any_line_number = true;
    if (kind != LineKind::Commands && kind != LineKind::Meta && kind != LineKind::Bad) continue;
    if (line.flags & detail::kIndentTabs) pf.prefilters.any_tab_indent = true;
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
        pf.errors.push_back(
            {code, fmt::format("'{}' did not follow 'if' at the same indentation", meta_keyword(meta))});
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

}  // namespace rrflint
