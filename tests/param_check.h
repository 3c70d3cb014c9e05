// Parameters are lexed twice: while parsing (for errors, counts and flags) and again on demand
// (ParsedFile::params / find). Shared by the parser test and the fuzz target: both must see the same parameters.
#pragma once

#include <string>
#include <vector>

#include "lint/syntax/parser.h"

namespace rrflint::test {

/// Why the parameters lexed on demand for `c` disagree with what the parse recorded; empty when they agree.
inline std::string param_mismatch(const ParsedFile& pf, const Command& c) {
  uint32_t n = 0;
  bool exponent = false, colon = false, repeated = false;
  uint64_t seen = 0;  // a bit per letter: 'A'..'Z', then 'a'..'z' (an apostrophe axis)
  for (const Param& p : pf.params(c)) {
    ++n;
    if (p.letter) {
      const uint64_t bit = uint64_t{1} << (p.letter >= 'a' ? p.letter - 'a' + 26 : p.letter - 'A');
      repeated = repeated || (seen & bit);
      seen |= bit;
    }
    exponent = exponent || p.exponent_letter;
    colon = colon || p.blank_before_colon;
    if (p.span.begin < c.span.begin || p.span.end > c.span.end) return "a parameter lies outside its command";
  }
  if (n != c.param_count)
    return "lexed " + std::to_string(n) + " parameters, the parse counted " + std::to_string(c.param_count);
  if (exponent != c.any_exponent) return "the exponent flag differs";
  if (colon != c.any_blank_before_colon) return "the blank-before-colon flag differs";
  if (repeated != c.any_repeated_letter) return "the repeated-letter flag differs";
  return "";
}

/// Why ParsedFile::block_commands disagrees with the block flag of each command's line; empty when they agree.
inline std::string block_commands_mismatch(const ParsedFile& pf) {
  std::vector<bool> in_range(pf.commands.size(), false);
  uint32_t prev_end = 0;
  for (size_t k = 0; k < pf.block_commands.size(); ++k) {
    auto [a, b] = pf.block_commands[k];
    if (a >= b || b > pf.commands.size() || (k > 0 && a <= prev_end))
      return "block range " + std::to_string(k) + " is out of order\n";
    for (uint32_t i = a; i < b; ++i) in_range[i] = true;
    prev_end = b;
  }
  for (uint32_t i = 0; i < pf.commands.size(); ++i)
    if (in_range[i] != pf.lines.in_block(pf.commands.code(i).line))
      return "block ranges differ at command " + std::to_string(i) + '\n';
  return "";
}

/// Everything a parse recorded, as text: every line and command field, every parameter as lexed on demand, the
/// errors, the cut expressions and the file flags. Two parses that must agree (in parts or not, with or without
/// the short path for simple lines) must give the same text.
inline std::string parse_dump(const ParsedFile& pf) {
  std::string out;
  auto num = [&](uint64_t v) {
    out += std::to_string(v);
    out += ' ';
  };
  auto span = [&](Span s) { out += std::to_string(s.begin) + '-' + std::to_string(s.end) + ' '; };
  for (const Line& l : pf.lines) {
    out += "L ";
    span(l.span), span(l.code), span(l.comment), span(l.meta_arg), span(l.meta_name);
    num(l.indent), num(l.stored_length), num(l.first_command), num(l.command_count);
    num(static_cast<unsigned>(l.kind)), num(static_cast<unsigned>(l.meta));
    for (bool b : {l.indent_tabs, l.indent_spaces, l.line_number, l.checksum, l.conditional, l.in_loop, l.after_nul})
      out += b ? '1' : '0';
    out += '\n';
  }
  for (const Command& c : pf.commands) {
    out += "C ";
    span(c.span), span(c.word);
    out += c.letter;
    out += ' ';
    num(static_cast<uint32_t>(c.number)), num(static_cast<uint8_t>(c.fraction)), num(c.line), num(c.param_count);
    for (bool b : {c.number_expr, c.has_number, c.cnc, c.any_exponent, c.any_blank_before_colon, c.any_repeated_letter})
      out += b ? '1' : '0';
    for (const Param& p : pf.params(c)) {
      out += " P";
      out += p.letter ? p.letter : '_';
      span(p.span), span(p.value), num(static_cast<unsigned>(p.kind));
      for (bool b : {p.has_expr, p.exponent_letter, p.blank_before_colon}) out += b ? '1' : '0';
    }
    out += '\n';
  }
  for (const ParseError& e : pf.errors)
    out += "E " + std::to_string(e.span.begin) + '-' + std::to_string(e.span.end) + ' ' + e.message + '\n';
  for (Span s : pf.semicolon_cuts) out += "S " + std::to_string(s.begin) + '-' + std::to_string(s.end) + '\n';
  for (uint32_t l : pf.prefilters.rich_lines) out += "R " + std::to_string(l) + '\n';
  for (uint32_t l : pf.prefilters.paren_lines) out += "( " + std::to_string(l) + '\n';
  for (uint32_t l : pf.prefilters.apostrophe_lines) out += "' " + std::to_string(l) + '\n';
  for (uint32_t l : pf.prefilters.colon_comment_lines) out += ": " + std::to_string(l) + '\n';
  // The sets hold every line they name (the colon set may hold more: a comment cut by a DEL byte).
  const std::string_view text = pf.source->text();
  for (uint32_t l = 0; l < pf.lines.size(); ++l) {
    const Line line = pf.lines[l];
    auto has = [&](Span s, char c) { return text.substr(s.begin, s.size()).find(c) != std::string_view::npos; };
    if ((line.kind == LineKind::Commands && has(line.code, '(')) != pf.prefilters.paren_lines.contains(l))
      out += "paren set differs at " + std::to_string(l) + '\n';
    if (has(line.code, '\'') != pf.prefilters.apostrophe_lines.contains(l))
      out += "apostrophe set differs at " + std::to_string(l) + '\n';
    if (has(line.comment, ':') && !pf.prefilters.colon_comment_lines.contains(l))
      out += "colon set misses " + std::to_string(l) + '\n';
    if (pf.prefilters.colon_comment_lines.contains(l) && line.comment.empty())
      out += "colon set: no comment at " + std::to_string(l) + '\n';
  }
  for (auto [a, b] : pf.block_commands) out += "B " + std::to_string(a) + '-' + std::to_string(b) + '\n';
  out += block_commands_mismatch(pf);
  const ParsedFile::Prefilters& pre = pf.prefilters;
  for (bool b : {pf.mixed_indentation, pre.any_exponent, pre.any_blank_before_colon, pre.any_repeated_letter,
                 pre.any_line_number, pre.any_tab_indent})
    out += b ? '1' : '0';
  return out;
}

}  // namespace rrflint::test
