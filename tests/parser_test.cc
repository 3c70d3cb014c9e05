// Parser tests, one TEST_CASE per point of docs/firmware-behaviour.md (lines to expressions). Lines are rendered
// compactly (ninja's style):
//
//   cmd: G1 X=10 Y=20 | M400      commands of one line, separated by '|'
//   cmd@4?~NC: …                  indent 4, conditional (?), in a loop (~), line number (N), checksum (C)
//   meta: if var.x > 1            meta command with its argument
//   blank / comment / bad
//
// Parameters: X=10 (number), E=[0.3:0.4] (colon list), P=<file.g> (unquoted text), S="x" (string),
// T={…} (expression), X (no value), 'a=5 (lowercase axis), _=<text> (unlettered); suffix ^e = an E swallowed
// as an exponent, ^b = a blank before ':' ended the list.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "lint/base/strings.h"
#include "lint/syntax/byte_classes.h"
#include "lint/syntax/parser.h"
#include "tests/param_check.h"

using namespace rrflint;
namespace fs = std::filesystem;

namespace {

struct Parsed {
  std::unique_ptr<SourceFile> source;
  ParsedFile pf;
};

Parsed parse_text(std::string text, ParseOptions opts = {}) {
  Parsed p;
  p.source = std::make_unique<SourceFile>(0, "config.g", "/sys/config.g", std::move(text));
  p.pf = parse(*p.source, opts);
  return p;
}

std::string render_param(const ParsedFile& pf, const Param& p) {
  std::string out;
  if (p.letter == 0) out = "_";
  else if (p.letter >= 'a') out = std::string("'") + p.letter;
  else out = std::string(1, p.letter);
  const std::string v(pf.text(p.value));
  switch (p.kind) {
    case ValueKind::None: break;
    case ValueKind::List: out += "=[" + v + "]"; break;
    case ValueKind::Text: out += "=<" + v + ">"; break;
    default: out += "=" + v; break;
  }
  if (p.exponent_letter) out += "^e";
  if (p.blank_before_colon) out += "^b";
  return out;
}

std::string render_command(const ParsedFile& pf, const Command& c) {
  std::string out(1, c.letter);
  if (c.number_expr) out += "{}";
  else if (c.number != -1 || pf.text(c.word).find('-') != std::string_view::npos) out += std::to_string(c.number);
  if (c.fraction >= 0) out += "." + std::to_string(c.fraction);
  for (const Param& p : pf.params(c)) out += " " + render_param(pf, p);
  return out;
}

std::string render_line(const ParsedFile& pf, const Line& l) {
  std::string out;
  switch (l.kind) {
    case LineKind::Blank: out = "blank"; break;
    case LineKind::Comment: out = "comment"; break;
    case LineKind::Commands: out = "cmd"; break;
    case LineKind::Meta: out = "meta"; break;
    case LineKind::Bad: out = "bad"; break;
  }
  if (l.indent) out += "@" + std::to_string(l.indent);
  if (l.conditional) out += "?";
  if (l.in_loop) out += "~";
  if (l.line_number) out += "N";
  if (l.checksum) out += "C";
  if (l.after_nul) out += "0";
  if (l.kind == LineKind::Commands) {
    out += ":";
    for (uint32_t i = 0; i < l.command_count; ++i)
      out += (i ? " | " : " ") + render_command(pf, pf.commands[l.first_command + i]);
  } else if (l.kind == LineKind::Meta) {
    out += ": " + std::string(meta_keyword(l.meta));
    if (!l.meta_name.empty()) out += " " + std::string(pf.text(l.meta_name)) + " =";
    if (!l.meta_arg.empty()) out += " " + std::string(pf.text(l.meta_arg));
  }
  return out;
}

/// Every logical line of `text`, rendered and joined with newlines.
std::string dump(std::string text, ParseOptions opts = {}) {
  Parsed p = parse_text(std::move(text), opts);
  std::string out;
  for (const Line& l : p.pf.lines) out += (out.empty() ? "" : "\n") + render_line(p.pf, l);
  return out;
}

/// The first line only.
std::string one(std::string text) {
  Parsed p = parse_text(std::move(text));
  return p.pf.lines.empty() ? "" : render_line(p.pf, p.pf.lines[0]);
}

/// The parse errors as "offset: message".
std::vector<std::string> errors(std::string text) {
  Parsed p = parse_text(std::move(text));
  std::vector<std::string> out;
  for (const ParseError& e : p.pf.errors) out.push_back(std::to_string(e.span.begin) + ": " + e.message);
  return out;
}

std::string text_of(const Parsed& p, Span s) { return std::string(p.pf.text(s)); }

}  // namespace

// Line assembly (firmware-behaviour.md#lines-and-line-endings).
TEST_CASE("parser: lines end at LF, CRLF and lone CR", "[parser]") {
  CHECK(dump("G1 X1\nG1 X2\n") == "cmd: G1 X=1\ncmd: G1 X=2");
  CHECK(dump("G1 X1\r\nG1 X2\r\n") == "cmd: G1 X=1\ncmd: G1 X=2");
  // rrflint reads a CR-only file line by line, as its author meant it (RRF107 reports the firmware's view).
  CHECK(dump("G1 X1\rG1 X2\r") == "cmd: G1 X=1\ncmd: G1 X=2");
  // No final newline: the last line still counts; a final newline adds no empty line.
  CHECK(dump("M83\nG1 X2") == "cmd: M83\ncmd: G1 X=2");
  CHECK(dump("M83\n\n") == "cmd: M83\nblank");
  CHECK(dump("") == "blank");

  Parsed p = parse_text("G1 X1\r\nM83\n");
  REQUIRE(p.pf.lines.size() == 2);
  CHECK(p.pf.lines[0].span == Span{0, 5});
  CHECK(p.pf.lines[1].span == Span{7, 10});
  CHECK(p.source->endings().crlf == 1);
  CHECK(p.source->endings().lf == 1);
  CHECK(p.source->usual_ending() == "\n");  // a tie goes to LF
  CHECK(parse_text("G1 X1\r\nM83\r\nM82\n").source->usual_ending() == "\r\n");
  CHECK(parse_text("G1 X1\rM83\rM82\r\n").source->usual_ending() == "\r");
  CHECK(parse_text("G1 X1\rM83\r\nM82").source->usual_ending() == "\r\n");  // CRLF wins a tie with CR
  CHECK(parse_text("G1 X1").source->usual_ending() == "\n");
}

TEST_CASE("parser: NUL ends a line and the rest is a new line", "[parser]") {
  Parsed p = parse_text(std::string("G1 X1\0G1 Y2\nM83\n", 16));
  CHECK(render_line(p.pf, p.pf.lines[0]) == "cmd: G1 X=1");
  CHECK(render_line(p.pf, p.pf.lines[1]) == "cmd0: G1 Y=2");
  CHECK(render_line(p.pf, p.pf.lines[2]) == "cmd: M83");
  REQUIRE(p.pf.errors.size() == 1);
  CHECK(p.pf.errors[0].span == Span{5, 6});
  CHECK(p.pf.errors[0].message.starts_with("NUL byte"));
}

TEST_CASE("parser: 0x7F discards the whole line", "[parser]") {
  // StringParser::Put() empties the line buffer at 0x7F and discards the rest: the command before it is lost too.
  Parsed p = parse_text("G1 X1\x7fY2\nM83\n  M84\x7f\n");
  CHECK(render_line(p.pf, p.pf.lines[0]) == "blank");
  CHECK(render_line(p.pf, p.pf.lines[1]) == "cmd: M83");
  CHECK(render_line(p.pf, p.pf.lines[2]) == "blank@2");
  CHECK(p.pf.commands.size() == 1);
  REQUIRE(p.pf.errors.size() == 2);
  CHECK(p.pf.errors[0].span == Span{5, 8});
  CHECK(p.pf.errors[0].message.starts_with("byte 0x7F"));
  CHECK(p.pf.errors[1].span == Span{18, 19});
}

TEST_CASE("parser: a UTF-8 byte-order mark at the start is not part of the first line's code", "[parser]") {
  Parsed p = parse_text("\xEF\xBB\xBFM83\nG21\n");
  CHECK(render_line(p.pf, p.pf.lines[0]) == "cmd: M83");
  CHECK(p.pf.errors.empty());
  Parsed q = parse_text("\xEF\xBB\xBF; comment\nG21\n");
  CHECK(render_line(q.pf, q.pf.lines[0]) == "comment");
}

TEST_CASE("parser: expressions RRF's expression parser rejects", "[parser]") {
  auto first_error = [](std::string text) {
    Parsed p = parse_text(std::move(text));
    return p.pf.errors.empty() ? std::string() : p.pf.errors[0].message;
  };
  CHECK(first_error("G1 X{(1 + 2} F6000\n").starts_with("expected ')'"));
  CHECK(first_error("G1 X{1 + } F6000\n").starts_with("expected an expression"));
  CHECK(first_error("G1 X{1 2}\n").starts_with("expected '}'"));
  CHECK(first_error("if true false\n  M400\n").starts_with("Unexpected characters after expression"));
  CHECK(first_error("echo 1 2\n").starts_with("expected ','"));
  CHECK(first_error("var a = 1 +\n").starts_with("expected an expression"));
  // Valid: RRF reads one expression after '=' and ignores the rest; arrays, functions, literals, ternaries.
  CHECK(first_error("var a = 1 2\n") == "");
  CHECK(first_error("G1 X{max(1, 2) + #move.axes - 0x1F * 1.5e3} Y{{1, 2,}[0]} Z{a ? 'b' : \"c\"\"d\"}\n") == "");
  CHECK(first_error("if exists(global.x) && !(a.b[1].c != 2) || d >= e\n  M400\n") == "");
  CHECK(first_error("echo >>\"/sys/x.txt\" 1, \"two\",\n") == "");
  // Deep nesting is left alone rather than recursed into without bound.
  CHECK(first_error("G1 X{" + std::string(5000, '(') + "1" + std::string(5000, ')') + "}\n") == "");
}

TEST_CASE("parser: axis words alone repeat the last move in CNC and laser mode only", "[parser]") {
  Parsed p = parse_text("X5 F300\nM453\nX5 F300 M5\nM452\n'a5\nM451\nY1\n");
  REQUIRE(p.pf.errors.size() == 2);
  CHECK(p.pf.errors[0].axis_repeat);
  CHECK(p.pf.errors[1].axis_repeat);
  CHECK(render_line(p.pf, p.pf.lines[2]) == "cmd: M5");
  CHECK(render_line(p.pf, p.pf.lines[4]) == "cmd:");
}

// Indentation (firmware-behaviour.md#indentation-and-blocks).
TEST_CASE("parser: a blank counts 1, a tab moves to the next multiple of 4", "[parser]") {
  auto indent = [](std::string text) { return parse_text(std::move(text)).pf.lines[0].indent; };
  CHECK(indent("G1") == 0);
  CHECK(indent("  G1") == 2);
  CHECK(indent("\tG1") == 4);
  CHECK(indent("\t\tG1") == 8);
  CHECK(indent("   \tG1") == 4);
  CHECK(indent("    \tG1") == 8);
  CHECK(indent(" \t G1") == 5);
  CHECK(indent("\t  G1") == 6);

  Parsed mixed = parse_text("if true\n\tM83\nif true\n    M82\n");
  CHECK(mixed.pf.lines[1].indent_tabs);
  CHECK_FALSE(mixed.pf.lines[1].indent_spaces);
  CHECK(mixed.pf.lines[3].indent_spaces);
  CHECK(mixed.pf.mixed_indentation);
  CHECK_FALSE(parse_text("if true\n  M83\nif true\n  M82\n").pf.mixed_indentation);
}

// Line numbers and checksums (firmware-behaviour.md#line-numbers-and-checksums).
TEST_CASE("parser: N line numbers and * checksums", "[parser]") {
  Parsed p = parse_text("N10 G1 X5*42 ; move\n");
  const Line& l = p.pf.lines[0];
  CHECK(render_line(p.pf, l) == "cmdNC: G1 X=5");
  CHECK(text_of(p, l.code) == "G1 X5");
  CHECK(text_of(p, l.comment) == "; move");
  CHECK(l.stored_length == 5);
  CHECK(one("n7 M83") == "cmdN: M83");
  // '*' starts a checksum only after N and outside braces; otherwise it is an ordinary character.
  CHECK(one("G1 X{2*3}") == "cmd: G1 X={2*3}");
  CHECK(one("N3 G1 X{2*3}*17") == "cmdNC: G1 X={2*3}");
  CHECK(one("G1 X5*3") == "cmd: G1 X=5*3");
  // 'N' followed by a non-digit is not a line number.
  CHECK(one("NG1") == "bad");
}

// Comments (firmware-behaviour.md#comments).
TEST_CASE("parser: comments", "[parser]") {
  CHECK(dump("; whole line\n  ; indented\n\t; tabbed\n") == "comment\nblank@2\nblank@4");
  Parsed p = parse_text("G1 X5 ; to the left\n");
  CHECK(text_of(p, p.pf.lines[0].comment) == "; to the left");
  CHECK(text_of(p, p.pf.lines[0].code) == "G1 X5");
  // ';' inside quotes is text; inside braces it still ends the line.
  CHECK(one("M291 P\"a;b\" S1") == "cmd: M291 P=\"a;b\" S=1");
  Parsed braces = parse_text("G1 X{1;2}\n");
  CHECK(text_of(braces, braces.pf.lines[0].code) == "G1 X{1");
  CHECK(text_of(braces, braces.pf.lines[0].comment) == ";2}");
  // The cut is recorded for RRF113 (semicolon-in-expression), not as a syntax error.
  CHECK(braces.pf.errors.empty());
  REQUIRE(braces.pf.semicolon_cuts.size() == 1);
  CHECK(text_of(braces, braces.pf.semicolon_cuts[0]) == "{1");
  Parsed meta = parse_text("echo {\"a\" ^ \"b\" ; \"c\"}\n");
  CHECK(meta.pf.errors.empty());
  REQUIRE(meta.pf.semicolon_cuts.size() == 1);
  CHECK(text_of(meta, meta.pf.semicolon_cuts[0]) == "{\"a\" ^ \"b\"");
}

TEST_CASE("parser: any_error_from and any_cut_from find what starts in a range", "[parser]") {
  // Errors and cuts on lines 2 and 4, in a file parsed in parts as well as whole (the starts are sorted at the end).
  const std::string text = "G1 X1\nM291 P\"open\nG1 Y2\nG1 X{1 ; c}\nG1 Z3\n";
  for (unsigned threads : {1u, 3u}) {
    Parsed p = parse_text(text, ParseOptions{.threads = threads, .part_bytes = threads > 1 ? 4u : 0u});
    REQUIRE(p.pf.errors.size() == 1);
    REQUIRE(p.pf.semicolon_cuts.size() == 1);
    const uint32_t e = p.pf.errors[0].span.begin, c = p.pf.semicolon_cuts[0].begin;
    CHECK(p.pf.any_error_from(e, e + 1));
    CHECK(p.pf.any_error_from(0, e + 1));
    CHECK_FALSE(p.pf.any_error_from(0, e));      // the end is not in the range
    CHECK_FALSE(p.pf.any_error_from(e + 1, c));  // nor before the begin
    CHECK_FALSE(p.pf.any_error_from(c, c + 1));  // a cut is not an error
    CHECK(p.pf.any_cut_from(c, static_cast<uint32_t>(text.size())));
    CHECK_FALSE(p.pf.any_cut_from(c + 1, static_cast<uint32_t>(text.size())));
    CHECK_FALSE(p.pf.any_cut_from(0, c));
  }
}

TEST_CASE("parser: ( ) comments only in CNC mode, after M453", "[parser]") {
  // In FFF mode the text is part of the command: "(" stays in X's value and "slow)" starts an S parameter.
  CHECK(one("G1 X5 (slow) Y6") == "cmd: G1 X=5 ( S L O W=<)> Y=6");
  CHECK(dump("M453\nG1 X5 (slow) Y6\nM452\nG1 X5 (a) Y6\n") ==
        "cmd: M453\ncmd: G1 X=5 Y=6\ncmd: M452\ncmd: G1 X=5 ( A=<)> Y=6");
  Parsed cnc = parse_text("G1 X5 (slow) Y6\n", ParseOptions{.cnc_mode = true});
  CHECK(cnc.pf.lines[0].stored_length == std::string("G1 X5  Y6").size());
  // Inside braces '(' is an expression bracket, also in CNC mode.
  Parsed expr = parse_text("G1 X{(1+2)*3}\n", ParseOptions{.cnc_mode = true});
  CHECK(render_line(expr.pf, expr.pf.lines[0]) == "cmd: G1 X={(1+2)*3}");
}

// The command word (firmware-behaviour.md#command-words).
TEST_CASE("parser: command words", "[parser]") {
  CHECK(one("g1 x10") == "cmd: G1 X=10");
  CHECK(one("m563 p0 s\"T\"") == "cmd: M563 P=0 S=\"T\"");
  CHECK(one("G59.3") == "cmd: G59.3");
  CHECK(one("M569.1 P0.2 S1") == "cmd: M569.1 P=0.2 S=1");
  // One fractional digit only: the second is left over as unlettered text.
  CHECK(one("G59.12") == "cmd: G59.1 _=<2>");
  CHECK(one("T-1") == "cmd: T-1");
  CHECK(one("T3 P0") == "cmd: T3 P=0");
  CHECK(one("T") == "cmd: T");
  CHECK(one("T{state.nextTool}") == "cmd: T{} T={state.nextTool}");

  Parsed p = parse_text("  M569.1 P0.2 ; c\n");
  const Command& c = p.pf.commands[0];
  CHECK(c.is('M', 569, 1));
  CHECK_FALSE(c.is('M', 569));
  CHECK(text_of(p, c.word) == "M569.1");
  CHECK(text_of(p, c.span) == "M569.1 P0.2");
  CHECK(c.span == Span{2, 13});

  // T-1 (deselect) and a bare T (report) must be told apart.
  Parsed t = parse_text("T-1\nT\n");
  CHECK(t.pf.commands[0].number == -1);
  CHECK(t.pf.commands[0].has_number);
  CHECK_FALSE(t.pf.commands[1].has_number);
}

TEST_CASE("parser: a line that does not start with G, M, T is a Bad command", "[parser]") {
  CHECK(errors("X10 Y20") ==
        std::vector<std::string>{"0: Bad command: 'X10 Y20': a line must start with G, M or T (axis words alone repeat "
                                 "the last move only in CNC or laser mode, after M453 or M452)"});
  CHECK(errors("IF true") ==
        std::vector<std::string>{"0: Bad command: 'IF true': meta-command keywords must be lowercase"});
  CHECK(errors("Echo \"x\"").size() == 1);
  CHECK(errors("G") == std::vector<std::string>{"0: expected a number after 'G'"});
  CHECK(one("ifx") == "bad");
  // The line is quoted up to 40 bytes, never up to part of a character (a message must stay valid UTF-8: the
  // language server's JSON cannot carry a cut one). Byte 40 here is the second byte of an "é".
  CHECK(errors("Q" + std::string(18, '-') +
               "\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9") ==
        std::vector<std::string>{
            "0: Bad command: "
            "'Q------------------\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9': a "
            "line must start with G, M "
            "or T"});
  CHECK(utf8_prefix("ab\xc3\xa9", 3) == "ab");
  CHECK(utf8_prefix("ab\xc3\xa9", 4) == "ab\xc3\xa9");
  CHECK(utf8_prefix("\xf0\x9f\x98\x80x", 2) == "");
  CHECK(utf8_prefix("abc", 10) == "abc");
  // An expression error found inside a character (RRF reads a character literal byte by byte: after the first byte
  // of "é" it wants the closing quote) is quoted from the character's start (found by fuzz_session).
  const std::vector<std::string> e = errors("if x == '\xc3\xa9'");
  REQUIRE(e.size() == 1);
  CHECK(e[0].find("at '\xc3\xa9''") != std::string::npos);
  CHECK(utf8_start("a\xf0\x9f\x98\x80", 4) == 1);
  CHECK(utf8_start("a\xf0\x9f\x98\x80", 2) == 1);
  CHECK(utf8_start("a\xf0\x9f\x98\x80", 1) == 1);
  CHECK(utf8_start("\x80\x80", 1, 1) == 1);  // not before the floor
}

// Several commands on one line (firmware-behaviour.md#several-commands-on-one-line).
TEST_CASE("parser: G and M start a new command, T and 'g do not", "[parser]") {
  CHECK(one("G1 X10 M400") == "cmd: G1 X=10 | M400");
  CHECK(one("G1 X10G1 Y20") == "cmd: G1 X=10 | G1 Y=20");
  CHECK(one("g1 x1 m83") == "cmd: G1 X=1 | M83");
  CHECK(one("G1 X10 T1") == "cmd: G1 X=10 T=1");
  CHECK(one("G1 X10 'g5") == "cmd: G1 X=10 'g=5");
  // Inside quotes and braces G and M are text.
  CHECK(one("M291 P\"Go Mad\" S1") == "cmd: M291 P=\"Go Mad\" S=1");
  CHECK(one("G1 X{move.axes[0].max}") == "cmd: G1 X={move.axes[0].max}");
  Parsed p = parse_text("G1 X10 M400 ; c\n");
  CHECK(p.pf.lines[0].command_count == 2);
  CHECK(text_of(p, p.pf.commands[0].span) == "G1 X10");
  CHECK(text_of(p, p.pf.commands[1].span) == "M400");
  CHECK(p.pf.commands[1].line == 0);
}

// Parameters (firmware-behaviour.md#parameters).
TEST_CASE("parser: parameter letters", "[parser]") {
  CHECK(one("G1X10Y20") == "cmd: G1 X=10 Y=20");
  CHECK(one("M584 'a0.5 'B0.6") == "cmd: M584 'a=0.5 'b=0.6");
  CHECK(one("M584 a0.5") == "cmd: M584 A=0.5");
  // E straight after a digit is an exponent; after a blank it is a parameter.
  CHECK(one("G1 X80E420") == "cmd: G1 X=80E420^e");
  CHECK(one("M584 X0 Y1 Z2E3") == "cmd: M584 X=0 Y=1 Z=2E3^e");
  CHECK(one("G1 X80 E4") == "cmd: G1 X=80 E=4");
  CHECK(one("G1 E4") == "cmd: G1 E=4");
  CHECK(one("G1 X1.5e-3") == "cmd: G1 X=1.5e-3^e");
  CHECK(one("M584 X") == "cmd: M584 X");

  Parsed p = parse_text("G1 X1 Y2 X3\n");
  const Command& c = p.pf.commands[0];
  ParamRef x = p.pf.find(c, 'X');
  REQUIRE(x);
  CHECK(text_of(p, x->value) == "1");
  CHECK(x->span == Span{3, 5});
  CHECK(p.pf.find(c, 'Z') == nullptr);
  CHECK(c.param_count == 3);
  Parsed lower = parse_text("G1 'a5\n");
  ParamRef a = lower.pf.find(lower.pf.commands[0], 'a');
  REQUIRE(a);
  CHECK(a->span == Span{3, 6});
  CHECK(lower.pf.find(lower.pf.commands[0], 'A') == nullptr);
}

// Values (firmware-behaviour.md#numbers-and-lists).
TEST_CASE("parser: value kinds and spans", "[parser]") {
  CHECK(one("G1 X-3.5 Y+2 Z.5") == "cmd: G1 X=-3.5 Y=+2 Z=.5");
  CHECK(one("M569 P1.2 S0") == "cmd: M569 P=1.2 S=0");
  CHECK(one("M584 E0.3:0.4:1.0") == "cmd: M584 E=[0.3:0.4:1.0]");
  CHECK(one("M92 E420: 430") == "cmd: M92 E=[420: 430]");
  CHECK(one("M92 E420 :430") == "cmd: M92 E=[420 :430]^b");
  CHECK(one("M584 E{global.d}:0.4") == "cmd: M584 E=[{global.d}:0.4]");
  CHECK(one("M550 PBench printer 2") == "cmd: M550 P=<Bench printer 2>");
  CHECK(one("M98 Pmacro.g") == "cmd: M98 P=<macro.g>");
  CHECK(one("M117 Hello world") == "cmd: M117 _=<Hello world>");
  CHECK(one("M117 \"Hi\"") == "cmd: M117 _=\"Hi\"");
  // Strings: "" is a quote, 'x a lowercase letter; G/M inside are text.
  CHECK(one("M550 P\"A \"\"big\"\" 'Machine\"") == "cmd: M550 P=\"A \"\"big\"\" 'Machine\"");
  // Braces nest, and a string inside may hold a brace.
  CHECK(one("M291 P{\"a}\" ^ {1 + (2)}} S1") == "cmd: M291 P={\"a}\" ^ {1 + (2)}} S=1");
  Parsed p = parse_text("M291 P{\"x\"} S1\n");
  ParamRef pp = p.pf.find(p.pf.commands[0], 'P');
  REQUIRE(pp);
  CHECK(pp->kind == ValueKind::Expression);
  CHECK(pp->has_expr);
  CHECK(pp->value == Span{6, 11});
  CHECK_FALSE(p.pf.find(p.pf.commands[0], 'S')->has_expr);
}

TEST_CASE("parser: unterminated strings and braces", "[parser]") {
  CHECK(errors("M550 P\"abc") ==
        std::vector<std::string>{"6: unterminated string: a quoted string must end with '\"' on the same line"});
  CHECK(errors("G1 X{1 + 2") == std::vector<std::string>{"4: unterminated '{': the expression has no closing '}'"});
  CHECK(errors("M550 P\"a\tb\"").size() == 1);
  CHECK(errors("M291 P\"a\" S1").empty());
}

// Meta commands (firmware-behaviour.md#meta-commands).
TEST_CASE("parser: meta commands", "[parser]") {
  CHECK(one("if move.axes[0].homed") == "meta: if move.axes[0].homed");
  CHECK(one("while iterations < 3") == "meta: while iterations < 3");
  CHECK(one("var speed = 30") == "meta: var speed = 30");
  CHECK(one("global parkX = {1, 2}") == "meta: global parkX = {1, 2}");
  CHECK(one("set var.speed = var.speed + 1") == "meta: set var.speed = var.speed + 1");
  CHECK(one("set global.pts[1] = 3") == "meta: set global.pts = 3");
  CHECK(one("echo \"a\", 1") == "meta: echo \"a\", 1");
  CHECK(one("echo >>\"f.txt\" \"a\"") == "meta: echo >>\"f.txt\" \"a\"");
  // The keyword must be followed by the end, a blank, '{', '"' or '(': `echo>>` is a Bad command.
  CHECK(one("echo>>\"f.txt\" \"a\"") == "bad");
  CHECK(one("abort \"stop\"") == "meta: abort \"stop\"");
  CHECK(one("skip") == "meta: skip");
  CHECK(one("if(true)") == "meta: if (true)");
  CHECK(one("N5 if true") == "metaN: if true");

  Parsed p = parse_text("var speed = 30 ; c\n");
  const Line& l = p.pf.lines[0];
  CHECK(l.meta == MetaKind::Var);
  CHECK(l.meta_name == Span{4, 9});
  CHECK(l.meta_arg == Span{12, 14});
  CHECK(l.stored_length == 15);
}

TEST_CASE("parser: meta command errors", "[parser]") {
  CHECK(errors("else") == std::vector<std::string>{"0: 'else' did not follow 'if' at the same indentation"});
  CHECK(errors("elif true") == std::vector<std::string>{"0: 'elif' did not follow 'if' at the same indentation"});
  CHECK(errors("break") == std::vector<std::string>{"0: 'break' was not inside a loop"});
  CHECK(errors("if true\n  continue") == std::vector<std::string>{"10: 'continue' was not inside a loop"});
  CHECK(errors("if") == std::vector<std::string>{"0: expected a condition after 'if'"});
  CHECK(errors("set x = 1") ==
        std::vector<std::string>{"4: expected a global or local variable after 'set' ('var.name' or 'global.name')"});
  CHECK(errors("var 1x = 1") == std::vector<std::string>{"4: expected a new variable name after 'var'"});
  CHECK(errors("var x 1") == std::vector<std::string>{"6: expected '='"});
  CHECK(errors("var x =") == std::vector<std::string>{"0: expected an expression after '='"});
  CHECK(errors("else junk").size() == 2);  // unexpected characters, and no 'if'
  CHECK(errors("if (a\n  M83") == std::vector<std::string>{"3: unclosed '(' in the 'if' condition"});
  CHECK(errors("while a)\n  M83") == std::vector<std::string>{"7: unbalanced ')' in the 'while' condition"});
  CHECK(errors("if true\n  M83\nelse\n  M82\n").empty());
  CHECK(errors("while true\n  if true\n    break\n  continue\n").empty());
}

TEST_CASE("parser: blocks by indentation set the conditional and loop flags", "[parser]") {
  CHECK(dump("if a\n  G1 X1\nelif b\n  G1 X2\nelse\n  G1 X3\nG1 X4\n") ==
        "meta: if a\ncmd@2?: G1 X=1\nmeta: elif b\ncmd@2?: G1 X=2\nmeta: else\ncmd@2?: G1 X=3\ncmd: G1 X=4");
  CHECK(dump("while a\n  G1 X1\n  if b\n    break\n  G1 X2\nG1 X3\n") ==
        "meta: while a\ncmd@2~: G1 X=1\nmeta@2~: if b\nmeta@4?~: break\ncmd@2~: G1 X=2\ncmd: G1 X=3");
  // Indentation without an opening if/while is a plain block: neither conditional nor in a loop.
  CHECK(dump("M83\n  G1 X1\n") == "cmd: M83\ncmd@2: G1 X=1");
  // Blank and comment lines do not end a block here (RRF109 judges column-0 comments by version).
  CHECK(dump("if a\n  G1 X1\n\n  ; note\n  G1 X2\n") == "meta: if a\ncmd@2?: G1 X=1\nblank\nblank@2\ncmd@2?: G1 X=2");
  // A deeper 'else' pairs with the inner 'if'.
  CHECK(dump("if a\n  if b\n    M83\n  else\n    M82\n") ==
        "meta: if a\nmeta@2?: if b\ncmd@4?: M83\nmeta@2?: else\ncmd@4?: M82");
  CHECK(errors("if a\n  if b\n    M83\nelse\n  M82\n").empty());
  CHECK(errors("if a\n  M83\n  else\n    M82\n").size() == 1);
}

TEST_CASE("parser: the commands inside blocks, as ranges", "[parser]") {
  using Ranges = std::vector<std::pair<uint32_t, uint32_t>>;
  auto ranges = [](std::string text, ParseOptions o = {}) {
    Parsed p = parse_text(std::move(text), o);
    CHECK(test::block_commands_mismatch(p.pf).empty());
    return p.pf.block_commands;
  };
  CHECK(ranges("G1 X1\nG1 X2\n").empty());
  // Two lines of one block, and a line of two commands: one range; a plain indented block is not a block here.
  CHECK(ranges("M83\nif a\n  G1 X1\n  G1 X2 G1 X3\nM84\n  G1 X4\n") == Ranges{{1, 4}});
  // Meta lines and blank lines inside a block hold no commands and do not break a range; a command outside does.
  CHECK(ranges("while a\n  G1 X1\n  if b\n    break\n\n  G1 X2\nG1 X3\nif c\n  T0\n") == Ranges{{0, 2}, {3, 4}});
  // A block at the start, and one that runs to the end of the file.
  CHECK(ranges("if a\n  M83\nelse\n  M82\n") == Ranges{{0, 2}});
  // Parsed in parts on several threads, the same.
  std::string text;
  for (int i = 0; i < 500; ++i) text += i % 3 == 0 ? "if a\n  G1 X1 G1 X2\n" : "G1 Y1\n";
  const Ranges serial = ranges(text);
  CHECK(serial.size() == 167);
  CHECK(ranges(text, ParseOptions{.threads = 3, .part_bytes = 100}) == serial);
}

// Stored line length (firmware-behaviour.md#lines-and-line-endings).
TEST_CASE("parser: stored line length", "[parser]") {
  auto stored = [](std::string text, ParseOptions o = {}) {
    return parse_text(std::move(text), o).pf.lines[0].stored_length;
  };
  CHECK(stored("G1 X10") == 6);
  CHECK(stored("    G1 X10") == 6);          // indentation is not stored
  CHECK(stored("\tG1 X10 ; comment") == 7);  // the blank before ';' is stored, the comment is not
  CHECK(stored("N100 G1 X10*99") == 6);      // neither the line number nor the checksum
  CHECK(stored("M117 \"a;b\"") == 10);       // quoted text is stored
  CHECK(stored("G1 X{1 + 2}") == 11);
  CHECK(stored("G1 X5 (slow) Y6", ParseOptions{.cnc_mode = true}) == 9);
  CHECK(stored("G1 X5 (slow) Y6") == 15);
}

TEST_CASE("parser: parameters lexed on demand are those the parse counted", "[parser]") {
  // The parse lexes parameters once for their errors and counts; ParamRange lexes them again from the stored
  // command. Every fixture file (and the awkward lines below) must agree both ways.
  std::vector<std::string> texts = {
      "M117 \"unterminated\nM98 Pmacro.g ; old style\nT{1+1} P0\nG1 X1 Y2 X3 E1e3\nM584 'a1 'b2 X0:1 :2\n",
      "M453\nG1 X1 (comment) Y2\nM451\nG1 X(1) Y2\nN10 G1 X5 *71 ; c\nG1 X{var.a ; cut}\n",
      "M550 Pmy printer\nM23 \"file.g\"\nM32 {\"x\"}\nG10 P0 X0 Y0 Z0 G10 P1\n\tG1 X\"a\"\"b\" \x7f tail\n",
  };
  for (const auto& e : fs::recursive_directory_iterator(fs::path(RRFLINT_SOURCE_DIR) / "fixtures"))
    if (e.is_regular_file() && e.path().extension() == ".g") {
      std::ifstream in(e.path(), std::ios::binary);
      texts.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  REQUIRE(texts.size() > 100);
  size_t commands = 0;
  for (const std::string& text : texts) {
    Parsed p = parse_text(text);
    for (const Command& c : p.pf.commands) {
      ++commands;
      INFO(text.substr(c.span.begin, c.span.size()));
      CHECK(test::param_mismatch(p.pf, c) == "");
    }
  }
  CHECK(commands > 1000);
}

TEST_CASE("parser: the short path for simple lines records what the full lexer records", "[parser]") {
  // Lines at the edges of what the short path takes (ParseOptions::fast_lines): exponents, a letter right after
  // the word, lists with and without a blank before ':', G/M letters that start a new command, words without a
  // number, commands that take the rest of the line, lowercase, tabs, indentation, 64- and 65-byte lines, mode
  // switches, repeated letters and comments.
  const std::vector<std::string> pieces = {
      "G1 X10 Y20",
      "G1 X80E420",
      "G1E5 X1",
      "G59.3E1",
      "G1 X1e5Y2",
      "G1 X1 E-2 E3",
      "M92 X80:80 Y1:2",
      "M92 X80 :80",
      "M584 X0.1:0.2 E:3",
      "G1 X1 M400 G4 S1",
      "G1 X1 g4 S1",
      "T-1",
      "T",
      "T0 P0",
      "T-",
      "G X1",
      "M",
      "G1.5.3 X1",
      "G-1 X2",
      "M98 Pmacro.g",
      "M117 hello world",
      "M550 PPrinter 1",
      "M23 file.g",
      "m563 P0",
      "g1 X1",
      "G1 X1 ; comment",
      "G1 X1;c",
      "G1 X1\t; tab",
      "\tG1 X1",
      "  G1 X1",
      "    M400 ; note",
      " ; indented comment",
      "G1 X1.2.3",
      "G1 X+1 Y-.5",
      "G1 X1 X2",
      "G1 'a1",
      "G1 X'",
      "G1 X1 *5",
      "N1 G1 X1",
      "M453",
      "M451",
      "M452",
      "G1 X1 (cnc) Y2",
      "M291 P\"a\"",
      "G1 X{1}",
      "G1 X1 }",
      "G1 X1 Y2 Z3 U4 V5 W6 A7 B8 C9 D10 H11 I12 J13 K14 L15",
      "G1 X1 Y2 Z3 U4 V5 W6 A7 B8 C9 D10 H11 I12 J13 K14 L1",
      "G1 X1 Y2 Z3 U4 V5 W6 A7 B8 C9 D10 H11 I12 J13 K14 L",
      "G1 X999999999999 Y-99999999999",
      "G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G4 G",
      "G1 X\xc3\xa9",
      "G1 X1 \x01",
      "if true",
      "  G1 X1 ; in a block",
      "else",
      "  M400",
      "",
      "G1 X1 ",
      "G1 X1  ",
      "M92 X80:",
      "M92 X:1",
      "G1 X1E",
      "G1 XE1",
      "G1 X1 E",
      "G10 P0 X0 Y0 Z0 G10 P1",
      "M" + std::string(63, '8'),  // a word that ends at the 64th byte (libFuzzer: a shift by 64)
      "G1 X1 M" + std::string(57, '5'),
  };
  std::string text;
  for (size_t i = 0; i < 3000; ++i) {
    text += pieces[(i * 7 + i / 11) % pieces.size()];
    if (i % 3 == 0) text += " " + pieces[(i / 3) % pieces.size()];  // two pieces on a line, as one
    text += i % 9 == 0 ? "\r\n" : "\n";
  }
  for (const std::string& p : pieces) text += p + "\n";
  text += pieces[0];  // the last line, with no terminator and no 64 bytes after it
  for (ParseOptions o :
       {ParseOptions{}, ParseOptions{.cnc_mode = true}, ParseOptions{.threads = 3, .part_bytes = 500}}) {
    const std::string fast = test::parse_dump(parse_text(text, o).pf);
    o.fast_lines = false;
    const std::string full = test::parse_dump(parse_text(text, o).pf);
    CHECK(fast == full);
    CHECK(fast.find(" P") != std::string::npos);
  }
  // The lines whose code holds a byte other than letters, digits, blanks, '.', '-', '+' and ':', on both paths.
  for (bool fast : {true, false}) {
    Parsed r = parse_text("G1 X1:2 ; (comment)\nM950 C\"a\"\nif x > 1\n  G1 X(1)\nG1 'a1\n; \"\n" +
                              std::string(70, ' ') + "G1 X1\nG1 X{1}\n",
                          ParseOptions{.fast_lines = fast});
    const ParsedFile::Prefilters& pre = r.pf.prefilters;
    CHECK(std::vector<uint32_t>(pre.rich_lines.begin(), pre.rich_lines.end()) == std::vector<uint32_t>{1, 2, 3, 4, 7});
    CHECK(pre.rich_lines.contains(7));
    CHECK_FALSE(pre.rich_lines.contains(6));
    CHECK(std::vector<uint32_t>(pre.paren_lines.begin(), pre.paren_lines.end()) == std::vector<uint32_t>{3});
    CHECK(std::vector<uint32_t>(pre.apostrophe_lines.begin(), pre.apostrophe_lines.end()) == std::vector<uint32_t>{4});
    // The lines whose comment holds a ':': after code, alone at column 0, indented (a blank line to RRF), after a
    // checksum; not a ':' in the code.
    Parsed c =
        parse_text("G1 X1 ; a: b\n  ; b:\nM83 ; c\n; c:\nG1 X2;d:\nG1 X1:2 ; e\nN1 G1 X1*12 ; f:\nM117 \"a:b\"\n",
                   ParseOptions{.fast_lines = fast});
    const LineSet& colons = c.pf.prefilters.colon_comment_lines;
    CHECK(std::vector<uint32_t>(colons.begin(), colons.end()) == std::vector<uint32_t>{0, 1, 3, 4, 6});
    // A value after a blank that follows no letter (RRF120): the short path tests its masks, the full path keeps
    // every command line for the rule to test; a blank after a letter or inside an expression is no such blank.
    // (The short path needs 64 bytes of the file after a line's start: a long comment ends the file.)
    Parsed v = parse_text("G1 X10 20\nG1 X10 Y20\nG1 X 10\nG1 X{1 + 2}\nG1 X{1} 5\necho 1 2\n; " + std::string(70, '-'),
                          ParseOptions{.fast_lines = fast});
    const LineSet& strays = v.pf.prefilters.stray_value_lines;
    CHECK(strays.contains(0));
    CHECK(strays.contains(4));
    CHECK_FALSE(strays.contains(5));  // a meta command
    if (fast) CHECK_FALSE(strays.contains(1));
    if (fast) CHECK_FALSE(strays.contains(2));
    for (uint32_t li = 0; li < 5; ++li)
      CHECK(may_hold_stray_value(v.source->text(), v.pf.lines.code(li)) == (li == 0 || li == 4));
    // A closing quote with two letters after it (RRF117); "" inside a string closes and opens again.
    Parsed q = parse_text("M291 P\"a\"bc\nM291 P\"abc\" S1\nM291 P\"a \"\"b\"\" c\"def\nG1 X1\nM291 P\"a\"b\n",
                          ParseOptions{.fast_lines = fast});
    const LineSet& words = q.pf.prefilters.word_after_quote_lines;
    CHECK(std::vector<uint32_t>(words.begin(), words.end()) == std::vector<uint32_t>{0, 2});
  }
  // And every fixture.
  size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(RRFLINT_SOURCE_DIR) / "fixtures"))
    if (e.is_regular_file() && e.path().extension() == ".g") {
      std::ifstream in(e.path(), std::ios::binary);
      const std::string t{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      INFO(e.path().string());
      CHECK(test::parse_dump(parse_text(t).pf) ==
            test::parse_dump(parse_text(t, ParseOptions{.fast_lines = false}).pf));
      ++files;
    }
  CHECK(files > 100);
}

TEST_CASE("parser: records that overflow their compact fields decode exactly", "[parser]") {
  // A 20-byte record saturates a few counters; the exact values live in side tables. Exercise each one.
  std::string many_commands;
  for (int i = 0; i < 70000; ++i) many_commands += "G4 ";
  std::string many_params = "M92";
  for (int i = 0; i < 300; ++i) many_params += " X" + std::to_string(i);
  const std::string long_word = "T{" + std::string(300, '1') + "}";
  const std::string deep = std::string(70000, ' ') + "G1 X1";
  Parsed p = parse_text(many_commands + "\n" + many_params + "\n" + long_word + " P0\n" + deep + "\n");
  REQUIRE(p.pf.lines.size() == 4);
  CHECK(p.pf.lines[0].command_count == 70000);
  CHECK(p.pf.commands.size() == 70000 + 3);
  const Command m92 = p.pf.commands[70000];
  CHECK(m92.is('M', 92));
  CHECK(m92.param_count == 300);
  CHECK(p.pf.find(m92, 'X')->value == Span{m92.word.end + 2, m92.word.end + 3});
  const Command t = p.pf.commands[70001];
  CHECK(t.number_expr);
  CHECK(t.word.size() == long_word.size());
  CHECK(t.param_count == 2);
  CHECK(p.pf.find(t, 'T')->kind == ValueKind::Expression);
  CHECK(p.pf.lines[3].indent == 70000);
  CHECK(p.pf.lines[3].code.size() == 5);
  CHECK(p.pf.lines[0].stored_length == many_commands.size());
  // A block opened under a deep indentation still ends where the indentation drops back by one (saturated
  // indents would both read 65535 and keep the second line in the block).
  Parsed blocks = parse_text("if true\n" + std::string(70000, ' ') + "G1 X1\n" + std::string(69999, ' ') + "G1 X2\n");
  CHECK(blocks.pf.lines[1].conditional);
  CHECK_FALSE(blocks.pf.lines[2].conditional);
  CHECK(p.pf.errors.empty());
}

TEST_CASE("parser: a file parsed in parts on several threads parses as on one", "[parser]") {
  // Lines of every kind, among them mode switches (a part after an M453 is parsed again in CNC mode), records
  // that overflow, errors, cut expressions, blocks and a DEL byte.
  const std::vector<std::string> kinds = {
      "G1 X10 Y20 E0.5 F1800 ; move",
      "M453 ; CNC mode from the next line",
      "G1 X1 (a comment only in CNC mode) Y2",
      "M452",
      "if move.axes[0].homed",
      "  G1 X{move.axes[0].max - 5} Y3",
      "  while iterations < 3",
      "\t  M400",
      "else",
      "  echo \"unterminated",
      "N10 G1 X5*71 ; checksum",
      "M98 P\"macro.g\" G4 S1",
      "G1 X{1 + ; cut} Y2",
      "set var.x = {1",
      "bogus line",
      "T{" + std::string(300, '7') + "} P0",
      "M584 X0 Y1 Z2 E3:4 :5",
      "G10 P0 X80E420 X1",
      ";comment at column 0",
      "",
      "G1 X1\x7f ignored",
      "M117 Printing (50%)",
      "var y = (1 + 2",
  };
  std::string many_params = "M92";
  for (int i = 0; i < 300; ++i) many_params += " X" + std::to_string(i);
  std::string text;
  for (int i = 0; i < 14000; ++i) {
    text += kinds[(i * 7 + i / 13) % kinds.size()] + (i % 5 == 0 ? "\r\n" : "\n");
    if (i % 1000 == 999) text += many_params + "\n";
  }
  // Every field of the parse, its parameters and its rich lines (test::parse_dump).
  const Parsed serial_parse = parse_text(text);
  const std::string serial = test::parse_dump(serial_parse.pf);
  CHECK(serial.find("\nE ") != std::string::npos);  // the text has errors,
  CHECK(serial.find("\nS ") != std::string::npos);  // cut expressions,
  CHECK(serial.find("\nR ") != std::string::npos);  // rich lines,
  CHECK(std::any_of(serial_parse.pf.commands.begin(), serial_parse.pf.commands.end(),
                    [](const Command& c) { return c.cnc; }));  // CNC-mode commands
  CHECK(serial_parse.pf.commands.size() > 2 * 4096);  // and spans three of the blocks that find a command's part
  for (unsigned threads : {2u, 3u, 4u, 7u}) {
    for (size_t part : {size_t{1}, size_t{700}, text.size() / 3}) {
      INFO("threads " << threads << ", parts of " << part << " bytes");
      CHECK(test::parse_dump(parse_text(text, ParseOptions{.threads = threads, .part_bytes = part}).pf) == serial);
    }
  }
  // Started in CNC mode (a macro run from a CNC config), every part agrees too.
  const ParseOptions cnc{.cnc_mode = true};
  CHECK(test::parse_dump(parse_text(text, ParseOptions{.cnc_mode = true, .threads = 3, .part_bytes = 500}).pf) ==
        test::parse_dump(parse_text(text, cnc).pf));
}

TEST_CASE("parser: parts guess their mode from mode lines anywhere, and a wrong guess is parsed again", "[parser]") {
  // Mode words the guess sees (at a line's start, after blanks or a line number, lowercase) and those it cannot
  // tell from text (later in a line, in a comment, inside a CNC ( ) comment, with a fraction or a longer number):
  // wherever the parts are cut, the parse is the one a single thread makes.
  const std::vector<std::string> kinds = {
      "M453",
      "G1 X1 (M451) Y2",
      "  N7 m452 ; laser",
      "G90 M453",
      "; M451 in a comment",
      "M451.1",
      "M4531 X1",
      "G1 X2 Y3",
      "X5 Y6",
      "M451",
      "\tM453\t; tabbed",
      "N12M452",
      "G1 X1 (a comment in CNC mode) Y2 E0.1",
  };
  std::string text;
  for (int i = 0; i < 3000; ++i) text += kinds[(i * 5 + i / 17) % kinds.size()] + (i % 9 == 0 ? "\r\n" : "\n");
  // And a long run with no mode line at all after the last M453: every part of it starts in CNC mode.
  text += "M453\n";
  for (int i = 0; i < 2000; ++i) text += "G1 X" + std::to_string(i) + " (cnc) Y1\n";
  for (const ParseOptions& start : {ParseOptions{}, ParseOptions{.cnc_mode = true}, ParseOptions{.laser_mode = true}}) {
    const std::string serial = test::parse_dump(parse_text(text, start).pf);
    for (unsigned threads : {2u, 3u, 8u}) {
      for (size_t part : {size_t{3}, size_t{97}, size_t{4096}, text.size() / 5}) {
        INFO("threads " << threads << ", parts of " << part << " bytes, cnc " << start.cnc_mode);
        ParseOptions o = start;
        o.threads = threads;
        o.part_bytes = part;
        CHECK(test::parse_dump(parse_text(text, o).pf) == serial);
      }
    }
  }
}

TEST_CASE("source: the line index finds every line start, whatever the alignment", "[parser]") {
  // Lines of every length from 0 to 40 bytes, so that LFs fall on every position of a 16-byte block.
  for (size_t shift = 0; shift < 17; ++shift) {
    std::string text(shift, 'x');
    for (int len = 0; len <= 40; ++len) text += std::string(static_cast<size_t>(len), 'G') + "\n";
    text += "tail";
    std::vector<uint32_t> starts{0};
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') starts.push_back(static_cast<uint32_t>(i + 1));
    for (unsigned threads : {1u, 2u, 3u, 7u}) {  // built in parts on several threads: the same index
      const SourceFile f(0, "t.g", "/sys/t.g", text, threads);
      REQUIRE(f.line_count() == starts.size());
      for (uint32_t l = 0; l < starts.size(); ++l) CHECK(f.line_span(l).begin == starts[l]);
      CHECK(f.endings().lf == starts.size() - 1);
    }
  }
}

TEST_CASE("parser: commands by code", "[parser]") {
  for (unsigned threads : {1u, 3u}) {
    INFO("threads " << threads);
    Parsed p = parse_text("M563 P0\nG1 X1\nT0\nM563.1 P1 G1 Y2\nT{1}\nM1024\nG1 X80E4\n",
                          ParseOptions{.threads = threads, .part_bytes = 4});
    auto list = [&](char l, int n) {
      std::vector<uint32_t> v;
      for (uint32_t i : p.pf.with_code(l, n)) v.push_back(i);
      return v;
    };
    CHECK(list('M', 563) == std::vector<uint32_t>{0, 3});
    CHECK(list('G', 1) == std::vector<uint32_t>{1, 4, 7});
    CHECK(list('T', 5) == std::vector<uint32_t>{2, 5});  // every T, whatever the number
    CHECK(list('M', 1024).empty());                      // beyond the index: not listed
    CHECK(p.pf.with_code('G', 10).empty());
    CHECK(p.pf.with_code('M', 1).empty());  // a code the file does not use
    CHECK(p.pf.prefilters.any_exponent);
    CHECK_FALSE(p.pf.prefilters.any_blank_before_colon);
    CHECK_FALSE(p.pf.prefilters.any_repeated_letter);
    CHECK_FALSE(p.pf.prefilters.any_line_number);
    CHECK_FALSE(p.pf.prefilters.any_tab_indent);
  }
  Parsed q = parse_text("N1 G1 X1\nif true\n\tG1 X1 X2\n  ; a tab-indented comment is blank\n");
  CHECK(q.pf.prefilters.any_line_number);
  CHECK(q.pf.prefilters.any_tab_indent);
  CHECK(q.pf.prefilters.any_repeated_letter);
  CHECK_FALSE(parse_text("if true\n\t; only a comment\n").pf.prefilters.any_tab_indent);
}

TEST_CASE("parser: the codes a file uses, and the commands with a flag", "[parser]") {
  const std::string text = "M563 P0\nG1 X1\nT0\nM563.1 P1 G1 Y2\nT{1}\nM1024\nG1 X80E4\nM584 E3 :4 X0 X1\nG59.3\nG-1\n";
  for (unsigned threads : {1u, 3u}) {
    INFO("threads " << threads);
    Parsed p = parse_text(text, ParseOptions{.threads = threads, .part_bytes = 4});
    // Each code once, in key order (G, then M, then T), with its commands in file order.
    std::vector<std::string> seen;
    for (const ParsedFile::UsedCode& u : p.pf.used_codes()) {
      std::string s = fmt::format("{}{}{}:", u.letter, u.number, u.any_fraction ? "f" : "");
      for (uint32_t i : u.commands) s += fmt::format(" {}", i);
      seen.push_back(s);
    }
    CHECK(seen == std::vector<std::string>{"G1: 1 4 7", "G59f: 9", "M563f: 0 3", "M584: 8", "T-1: 2 5"});
    std::vector<uint32_t> unlisted(p.pf.unlisted_codes().begin(), p.pf.unlisted_codes().end());
    CHECK(unlisted == std::vector<uint32_t>{6, 10});  // M1024 and G-1: no list of their own
    // The flags, as the decoded commands have them.
    for (auto [flag, field] : {std::pair{CommandTable::Flag::Exponent, &Command::any_exponent},
                               std::pair{CommandTable::Flag::BlankBeforeColon, &Command::any_blank_before_colon},
                               std::pair{CommandTable::Flag::RepeatedLetter, &Command::any_repeated_letter}}) {
      std::vector<uint32_t> want;
      for (uint32_t i = 0; i < p.pf.commands.size(); ++i)
        if (p.pf.commands[i].*field) want.push_back(i);
      CHECK_FALSE(want.empty());
      CHECK(p.pf.commands.with_flag(flag) == want);
    }
  }
  CHECK(parse_text("").pf.used_codes().empty());
  CHECK(parse_text("").pf.with_code('G', 1).empty());
}

TEST_CASE("source: the line index notes NUL and DEL bytes, and CR sends it to the general scan", "[parser]") {
  for (unsigned threads : {1u, 2u, 3u}) {
    INFO("threads " << threads);
    const std::string plain(100, 'G');
    for (size_t at : {size_t{0}, size_t{15}, size_t{16}, size_t{50}, size_t{99}}) {
      INFO("at " << at);
      for (char c : {'\0', '\x7f', '\r'}) {
        std::string t = plain;
        t[at] = c;
        const SourceFile f(0, "t.g", "/sys/t.g", t, threads);
        CHECK(f.any_nul() == (c == '\0'));
        CHECK(f.any_del() == (c == '\x7f'));
        CHECK(f.endings().cr == (c == '\r' ? 1u : 0u));
        CHECK(f.line_count() == (c == '\r' && at < 99 ? 2u : 1u));
      }
    }
    const SourceFile none(0, "t.g", "/sys/t.g", "G1\nM2\n", threads);
    CHECK_FALSE(none.any_nul());
    CHECK_FALSE(none.any_del());
    const SourceFile crlf(0, "t.g", "/sys/t.g", "G1\r\nM2\nG3\r\n", threads);
    CHECK(crlf.line_count() == 3);
    CHECK(crlf.endings().crlf == 2);
    CHECK(crlf.endings().lf == 1);
  }
}

TEST_CASE("source: span_has finds a byte in any span, also near the end of the buffer", "[parser]") {
  std::string t;
  for (int i = 0; i < 70; ++i) t += static_cast<char>('a' + i % 26);
  for (uint32_t b = 0; b <= t.size(); ++b)
    for (uint32_t e = b; e <= t.size(); ++e)
      for (char c : {'a', 'q', 'r', 'z', '!'}) {
        const bool want = t.substr(b, e - b).find(c) != std::string::npos;
        if (span_has(t, Span{b, e}, c) != want) FAIL("span [" << b << ", " << e << ") byte " << c);
      }
}

TEST_CASE("parser: lines M28 writes into a file are in no code index", "[parser]") {
  using Range = std::pair<uint32_t, uint32_t>;
  auto p = parse_text(
      "G28\nM28 start.g\nM98 P\"x.g\"\nT0\nM29\nM98 P\"y.g\"\nM560 P\"a.htm\"\n<b>M98 P\"z.g\"</b>\n"
      "<!-- **EoF** -->\nG1 X1\nM28 tail.g\nG1 X2\n");
  REQUIRE(p.pf.written_lines == std::vector<Range>{{2, 5}, {7, 9}, {11, 12}});
  CHECK(p.pf.with_code('M', 98).size() == 1);  // only line 6's
  CHECK(p.pf.commands[*p.pf.with_code('M', 98).begin()].line == 5);
  CHECK(p.pf.with_code('T', 0).size() == 0);
  CHECK(p.pf.with_code('M', 29).size() == 0);  // the M29 is the writer's, not a command that runs
  CHECK(p.pf.with_code('G', 1).size() == 1);
  CHECK(p.pf.errors.empty());  // the upload's HTML is not G-code
  // Without any of them, nothing is written (and the common path is untouched).
  CHECK(parse_text("G28\nM98 P\"x.g\"\n").pf.written_lines.empty());
}
