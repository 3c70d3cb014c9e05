// Private to the parser's .cc files (lint/syntax/*.cc): the lexer, the line parser and what they share. The
// parser is split by stage: lexer.cc (Lexer, ParamRange), line_parser.cc (logical lines, meta commands, blocks),
// expr_syntax.cc (RRF's expression grammar), fast_lines.cc (simple_line), records.cc (the tables),
// code_index.cc (with_code), parts.cc (a file parsed in parts), parser.cc (parse(), the prefilters).
#pragma once

#include <algorithm>
#include <cstring>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "lint/base/strings.h"  // clip
#include "lint/syntax/byte_classes.h"
#include "lint/syntax/parser.h"

namespace rrflint {

inline char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }
inline char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c + 32) : c; }

struct MetaWord {
  std::string_view word;
  MetaKind kind;
};
inline constexpr MetaWord kMetaWords[] = {
    {"if", MetaKind::If},       {"elif", MetaKind::Elif},   {"else", MetaKind::Else},
    {"while", MetaKind::While}, {"break", MetaKind::Break}, {"continue", MetaKind::Continue},
    {"abort", MetaKind::Abort}, {"var", MetaKind::Var},     {"global", MetaKind::Global},
    {"set", MetaKind::Set},     {"echo", MetaKind::Echo},   {"skip", MetaKind::Skip},
};

// A command whose one string argument needs no letter (M117 text); a fraction makes it another command.
inline bool unlettered_string(const Command& c) {
  return c.fraction < 0 && takes_unlettered_string(c.letter, c.number);
}

// RRF's expression grammar (expr_syntax.cc). clip() is lint/base/strings.h's.
// "'…'" or "the end": where an expression error is, for a message.
std::string error_place(std::string_view t, uint32_t at, uint32_t e);
// Is the {…} group [b, e) (from its '{' to after its '}') a complete expression? `msg` and `at` say why not.
bool brace_expression_ok(std::string_view t, uint32_t b, uint32_t e, const char** msg, uint32_t* at);

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

// Code keys: G0…G1023, then M0…M1023, then every T.
inline constexpr uint16_t kTKey = 2048, kNoKey = 2049;
inline uint16_t code_key(char letter, int32_t number) {
  if (letter == 'T') return kTKey;
  if (number < 0 || number >= 1024) return kNoKey;
  return static_cast<uint16_t>((letter == 'M' ? 1024 : 0) + number);
}

// Appends a record and counts its code for index_codes, which then needs no sweep of its own to size the runs.
RRFLINT_ALWAYS_INLINE inline void CommandTable::push_rec(const detail::CommandRec& r) {
  if (key_counts_.empty()) key_counts_.assign(kNoKey + 1, 0);
  const uint16_t key = code_key(detail::letter_of(r.bits), r.number);
  ++key_counts_[key];
  if (r.fraction >= 0 && (fraction_keys_.empty() || fraction_keys_.back() != key)) fraction_keys_.push_back(key);
  all_bits_ |= r.bits;
  recs_.push_back(r);
}

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
  void lex_params(Command& cmd, uint32_t& p, uint32_t e);
  // `what` names the expression in a message: "the '<kw>' <role>", or "the <role>" without a keyword (built only
  // for an error: most expressions are fine).
  /// False when it reported an error or a ';' cut the expression.
  bool check_expression(uint32_t b, uint32_t e, std::string_view kw, std::string_view role);
  /// The meta command's expressions as RRF's expression parser reads them (after check_expression passed).
  void check_meta_syntax(MetaKind kind, uint32_t b, uint32_t e);
  void add_line(const Line& line, bool cut_by_del) {
    if (!line.code.empty() &&
        any_rich(lex_.t.data(), static_cast<uint32_t>(lex_.t.size()), line.code.begin, line.code.end)) {
      sets_->rich_lines.insert(next_line_);
      if (line.kind == LineKind::Commands && span_has(lex_.t, line.code, '(')) sets_->paren_lines.insert(next_line_);
      if (span_has(lex_.t, line.code, '\'')) sets_->apostrophe_lines.insert(next_line_);
      if (line.kind == LineKind::Commands && may_have_word_after_quote(lex_.t, line.code))
        sets_->word_after_quote_lines.insert(next_line_);
    }
    // Every command line of the full path: its test (may_hold_stray_value) is left to the rule, on the helper
    // thread, where the parse is on the critical path of both.
    if (line.kind == LineKind::Commands) sets_->stray_value_lines.insert(next_line_);
    if (span_has(lex_.t, line.comment, ':')) sets_->colon_comment_lines.insert(next_line_);
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
  // The line sets the parse fills: the file's (a part of a file writes to the whole file's).
  ParsedFile::Prefilters* sets_ = &out_.prefilters;
  detail::LineRec* in_place_;
  uint32_t next_line_;     // the index of the next logical line
  bool next_cnc_ = false;  // the mode after this line (M453 / M451 / M452 take effect on the next line)
  bool laser_ = false;     // laser mode (M452): a line of axis words repeats the last move, as in CNC mode
  bool next_laser_ = false;
  friend ParsedFile parse(const SourceFile&, const ParseOptions&);
};

// Blocks and the code index, after the lines are parsed (line_parser.cc, code_index.cc).
void compute_blocks(ParsedFile& pf);
void index_codes(ParsedFile& pf);
/// Finds the lines written into a file (ParsedFile::written_lines); before index_codes and compute_blocks.
void mark_written(ParsedFile& pf);

}  // namespace rrflint
