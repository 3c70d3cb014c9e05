// The inline decoders of the records (records.h): included at the end of lint/syntax/parser.h, where `Command` and
// `Line` are complete. Decoding is inlined where a record is read, so that the compiler drops the fields a caller
// never reads.
#pragma once

#include <cstring>

#include "lint/syntax/parser.h"

namespace rrflint {

RRFLINT_ALWAYS_INLINE inline Command CommandTable::operator[](size_t i) const {
  const detail::CommandRec& r = rec(i);
  Command c;
  c.span = Span{r.begin, r.end};
  c.word = Span{r.begin, r.word_len < 255 ? r.begin + r.word_len : long_word_end(i)};
  c.letter = detail::letter_of(r.bits);
  c.number = r.number;
  c.fraction = r.fraction;
  c.number_expr = r.bits & detail::kNumberExpr;
  c.has_number = r.bits & detail::kHasNumber;
  c.cnc = r.bits & detail::kCnc;
  c.any_exponent = r.bits & detail::kAnyExponent;
  c.any_blank_before_colon = r.bits & detail::kAnyBlankColon;
  c.any_repeated_letter = r.bits & detail::kAnyRepeat;
  c.line = r.line;
  c.param_count = r.param_count < 255 ? r.param_count : big_count(i);
  return c;
}

RRFLINT_ALWAYS_INLINE inline Line LineTable::operator[](size_t i) const {
  const detail::LineRec& r = recs_[i];
  const std::string_view t = source_->text();
  Line l;
  l.span = span(i);
  l.code = Span{r.code_begin, r.code_end};
  l.kind = static_cast<LineKind>(r.kind_meta & 7);
  l.meta = static_cast<MetaKind>((r.kind_meta >> 3) & 15);
  l.indent = r.indent < 65535 ? r.indent : long_indent(i);
  l.stored_length = stored_length(i);
  l.command_count = r.command_count < 65535 ? r.command_count : big_count(i);
  if (l.kind == LineKind::Meta) {
    l.meta_arg = metas_[r.first].arg;
    l.meta_name = metas_[r.first].name;
  } else if (l.kind == LineKind::Commands || l.kind == LineKind::Bad) {
    l.first_command = r.first;
  }
  l.indent_tabs = r.flags & detail::kIndentTabs;
  l.indent_spaces = r.flags & detail::kIndentSpaces;
  l.line_number = r.flags & detail::kLineNumber;
  l.checksum = r.flags & detail::kChecksum;
  l.conditional = r.flags & detail::kConditional;
  l.in_loop = r.flags & detail::kInLoop;
  l.after_nul = r.flags & detail::kAfterNul;
  // The comment: after the code (and a checksum), or the whole line after its indentation when it has no code.
  if (!(r.kind_meta & 0x80)) return l;
  uint32_t e = l.span.end;
  if (r.flags & detail::kCutByDel) {
    const void* del = std::memchr(t.data() + l.span.begin, 0x7f, l.span.end - l.span.begin);
    if (del) e = static_cast<uint32_t>(static_cast<const char*>(del) - t.data());
  }
  uint32_t q = (r.code_begin == 0 && r.code_end == 0) ? l.span.begin : r.code_end;
  while (q < e && (t[q] == ' ' || t[q] == '\t')) ++q;
  if (q < e && t[q] == '*' && l.checksum)
    while (q < e && t[q] != ';') ++q;
  if (q < e && t[q] == ';') l.comment = Span{q, e};
  return l;
}

}  // namespace rrflint
