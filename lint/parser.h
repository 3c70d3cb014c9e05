// The RRF line parser (rrf-semantics §1): bytes -> lines -> commands and parameters, all as spans.
//
// One pass per file, no allocation per token: commands and parameters live in two flat vectors of the
// ParsedFile and refer to each other by index. Parse errors are collected and parsing resumes at the next
// line, the way RRF itself reports an error and carries on with the next line.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "source.h"

namespace rrflint {

enum class ValueKind : uint8_t {
  None,        // the letter has no value (`M584 X`)
  Number,      // 12, -3.5, 1.2 (a driver id), 80E420
  List,        // colon list: 0:1:2, 3.0:3.1, {a}:400
  String,      // "quoted"
  Expression,  // {…}
  Text,        // unquoted text (M98 Pfile.g on old firmware, M550 PName, M117 text)
};

struct Param {
  Span span;             // letter (with a leading ' for lowercase axes) to the end of the value, trimmed
  Span value;            // the value text, trimmed; empty for ValueKind::None
  char letter = 0;       // 'A'..'Z', or 'a'..'z' for an apostrophe-prefixed lowercase axis; 0 = unlettered text
  ValueKind kind = ValueKind::None;
  bool has_expr = false;         // the value contains a {…} expression
  bool exponent_letter = false;  // the value swallowed an E/e after a digit (`X80E420`)
  bool blank_before_colon = false;  // a blank before ':' ends the list early (`E3 :4`)
};

struct Command {
  Span span;             // the whole command text, trimmed
  Span word;             // "M563", "g59.3", "T{…}"
  char letter = 0;       // 'G', 'M' or 'T' (upper-cased)
  int32_t number = -1;   // code number; -1 for `T` with no number; for T{expr} also -1
  int8_t fraction = -1;  // digit after '.', -1 if none
  bool number_expr = false;  // T{expr}
  bool has_number = false;   // digits follow the letter: tells `T-1` (deselect) from a bare `T` (report)
  uint32_t line = 0;         // index into ParsedFile::lines
  uint32_t first_param = 0;
  uint32_t param_count = 0;
  bool is(char l, int32_t n, int8_t f = -1) const { return letter == l && number == n && fraction == f; }
};

enum class LineKind : uint8_t {
  Blank,     // empty, whitespace, or an indented comment (RRF treats it as an empty line)
  Comment,   // a whole-line comment starting at column 0
  Commands,  // one or more G/M/T commands
  Meta,      // if/elif/else/while/break/continue/abort/var/global/set/echo/skip
  Bad,       // a line RRF rejects (reported as a parse error)
};

enum class MetaKind : uint8_t { None, If, Elif, Else, While, Break, Continue, Abort, Var, Global, Set, Echo, Skip };
std::string_view meta_keyword(MetaKind k);

struct Line {
  Span span;        // the logical line, without its terminator
  Span code;        // the text RRF executes: no indentation, line number, checksum or comment; trimmed
  Span comment;     // the comment text including ';' (empty when none)
  uint32_t indent = 0;      // RRF indent units: a blank counts 1, a tab advances to the next multiple of 4
  uint32_t stored_length = 0;  // characters RRF stores for the length limit
  uint32_t first_command = 0;
  uint32_t command_count = 0;
  LineKind kind = LineKind::Blank;
  MetaKind meta = MetaKind::None;
  Span meta_arg;            // condition / expression / "name = expr" after the keyword
  Span meta_name;           // variable name for var/global/set
  bool indent_tabs = false;
  bool indent_spaces = false;
  bool line_number = false;  // starts with N…
  bool checksum = false;     // has *…
  bool conditional = false;  // inside an if/elif/else block
  bool in_loop = false;      // inside a while block
  bool after_nul = false;    // this logical line starts after a NUL byte on the same editor line
};

struct ParseError {
  Span span;
  std::string message;
};

struct ParseOptions {
  bool cnc_mode = false;  // `( )` comments are recognised only in CNC mode (M453)
};

struct ParsedFile {
  const SourceFile* source = nullptr;
  std::vector<Line> lines;
  std::vector<Command> commands;
  std::vector<Param> params;
  std::vector<ParseError> errors;
  /// Expressions cut short by a ';' (RRF113 reports them, not syntax-error): from the '{' (or the start of a
  /// meta-command expression) to the end of the code; the ';' follows after optional blanks.
  std::vector<Span> semicolon_cuts;
  bool mixed_indentation = false;

  std::string_view text(Span s) const { return source->slice(s); }
  const Param* param_begin(const Command& c) const { return params.data() + c.first_param; }
  const Param* param_end(const Command& c) const { return params.data() + c.first_param + c.param_count; }
  /// The first parameter with this letter (RRF's Seen() finds the first one).
  const Param* find(const Command& c, char letter) const;
  const Line& line_of(const Command& c) const { return lines[c.line]; }
};

ParsedFile parse(const SourceFile& file, const ParseOptions& opts = {});

/// True for codes whose single string argument may be unquoted and runs to the end of the line.
bool takes_rest_of_line(char letter, int32_t number);

}  // namespace rrflint
