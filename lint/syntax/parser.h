// The RRF line parser: bytes -> lines -> commands and parameters, all as spans. What RRF does is described in
// docs/firmware-behaviour.md, sections #lines-and-line-endings to #expressions.
//
// One pass per file, no allocation per token. What the pass keeps is small: a 20-byte record per line and per
// command, decoded into the `Line` and `Command` values below when asked for, and a 4-byte link per command to the
// next of its code (`ParsedFile::with_code`). Parameters are not stored at all: the pass lexes them once (to report
// errors and count them) and `ParsedFile::params` / `find` lex a command's parameters again on demand, with the
// same code. The generated 100 MB benchmark file therefore costs about 1.3x its size in records (bench/RESULTS.md,
// P4). Most lines (`G1 X10 Y20 ; note`) take a short path that classifies their bytes 16 at a time and counts the
// parameters from bit masks; anything else goes through the full lexer (ParseOptions::fast_lines). A large file is
// parsed in parts on several threads (ParseOptions). Parse errors are collected and parsing resumes at the next
// line, the way RRF itself reports an error and carries on with the next line.
#pragma once

#include <algorithm>
#include <array>
#include <compare>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lint/base/source.h"
#include "lint/syntax/index_sets.h"  // LineSet, CodeCommands
#include "lint/syntax/records.h"     // CommandTable, LineTable: the records behind lines and commands

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
  Span span;        // letter (with a leading ' for lowercase axes) to the end of the value, trimmed
  Span value;       // the value text, trimmed; empty for ValueKind::None
  char letter = 0;  // 'A'..'Z', or 'a'..'z' for an apostrophe-prefixed lowercase axis; 0 = unlettered text
  ValueKind kind = ValueKind::None;
  bool has_expr = false;            // the value contains a {…} expression
  bool exponent_letter = false;     // the value swallowed an E/e after a digit (`X80E420`)
  bool blank_before_colon = false;  // a blank before ':' ends the list early (`E3 :4`)
};

/// A parameter found by `ParsedFile::find`, or none: use it like a pointer (`if (p) … p->value`).
class ParamRef {
 public:
  ParamRef() = default;
  explicit ParamRef(const Param& p) : p_(p), ok_(true) {}
  explicit operator bool() const { return ok_; }
  const Param* operator->() const { return &p_; }
  const Param& operator*() const { return p_; }
  /// Is this the same parameter of the same command as `p` (not merely the same letter)?
  bool is(const Param& p) const { return ok_ && p_.span == p.span; }
  friend bool operator==(const ParamRef& r, std::nullptr_t) { return !r.ok_; }

 private:
  Param p_;
  bool ok_ = false;
};

struct Command {
  Span span;                            // the whole command text, trimmed
  Span word;                            // "M563", "g59.3", "T{…}"
  char letter = 0;                      // 'G', 'M' or 'T' (upper-cased)
  int32_t number = -1;                  // code number; -1 for `T` with no number; for T{expr} also -1
  int8_t fraction = -1;                 // digit after '.', -1 if none
  bool number_expr = false;             // T{expr}
  bool has_number = false;              // digits follow the letter: tells `T-1` (deselect) from a bare `T` (report)
  bool cnc = false;                     // parsed in CNC mode: `( )` is a comment inside it
  bool any_exponent = false;            // some parameter swallowed an E after a digit (Param::exponent_letter)
  bool any_blank_before_colon = false;  // some parameter has Param::blank_before_colon
  bool any_repeated_letter = false;     // two parameters have the same letter
  uint32_t line = 0;                    // index into ParsedFile::lines
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
  Span span;                   // the logical line, without its terminator
  Span code;                   // the text RRF executes: no indentation, line number, checksum or comment; trimmed
  Span comment;                // the comment text including ';' (empty when none)
  uint32_t indent = 0;         // RRF indent units: a blank counts 1, a tab advances to the next multiple of 4
  uint32_t stored_length = 0;  // characters RRF stores for the length limit
  uint32_t first_command = 0;
  uint32_t command_count = 0;
  LineKind kind = LineKind::Blank;
  MetaKind meta = MetaKind::None;
  Span meta_arg;   // condition / expression / "name = expr" after the keyword
  Span meta_name;  // variable name for var/global/set
  bool indent_tabs = false;
  bool indent_spaces = false;
  bool line_number = false;  // starts with N…
  bool checksum = false;     // has *…
  bool conditional = false;  // inside an if/elif/else block
  bool in_loop = false;      // inside a while block
  bool after_nul = false;    // this logical line starts after a NUL byte on the same editor line
};

/// The checksum of a line with one (Line::checksum): the '*' the parse stopped at (after the code and blanks) and
/// the digits after it, in the file's text `t`. Empty, at the line's end, when the line has none.
inline Span checksum_span(std::string_view t, const Line& line) {
  if (!line.checksum) return Span{line.span.end, line.span.end};
  uint32_t star = line.code.end;
  while (star < line.span.end && t[star] != '*') ++star;
  if (star >= line.span.end) return Span{line.span.end, line.span.end};
  uint32_t e = star + 1;
  while (e < line.span.end && t[e] >= '0' && t[e] <= '9') ++e;
  return Span{star, e};
}

struct ParseError {
  Span span;
  std::string message;
  /// A line of bare axis words (`X5 F300`) read outside CNC and laser mode. In those modes (M453, M452) RRF repeats
  /// the last G0-G3 with them; a file that never sets the mode may run in one, which the syntax-error rule checks.
  bool axis_repeat = false;
};

struct ParseOptions {
  bool cnc_mode = false;    // `( )` comments are recognised only in CNC mode (M453)
  bool laser_mode = false;  // M452: like CNC mode, a line of axis words repeats the last move (no `( )` comments)
  /// A large file is cut at line starts into parts of at least `part_bytes`, parsed on up to `threads` threads
  /// and joined. The result is the same as a parse on one thread (a part that a mode switch before it changes is
  /// parsed again).
  unsigned threads = 1;
  size_t part_bytes = size_t{2} << 20;
  /// Most lines (`G1 X10 Y20 ; note`: commands of letters, numbers and lists, indented by spaces if at all) take a
  /// short path that classifies the line's bytes 16 at a time. Off: every line goes through the full lexer. The result
  /// is the same either way; the tests compare the two.
  bool fast_lines = true;
  /// Tests only: every prefilter off (ParsedFile::Prefilters: each line set holds every line, each flag is true,
  /// commands_with lists every command). The fixture runner lints each case both ways and requires the same
  /// findings, which proves the rules do not depend on the prefilters for their findings.
  bool no_prefilters = false;
};

/// The parameters of one command, lexed as they are iterated.
class ParamRange {
 public:
  class iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = Param;
    using difference_type = std::ptrdiff_t;
    using pointer = const Param*;
    using reference = const Param&;
    iterator() = default;
    iterator(std::string_view text, const Command& c);
    const Param& operator*() const { return p_; }
    const Param* operator->() const { return &p_; }
    iterator& operator++();
    friend bool operator==(const iterator& a, const iterator& b) {
      return a.done_ == b.done_ && (a.done_ || a.pos_ == b.pos_);
    }

   private:
    std::string_view t_;
    Command c_;
    uint32_t pos_ = 0;
    int stage_ = 0;  // 0: the T{…} or unlettered first parameter, 1: lettered parameters
    bool done_ = true;
    Param p_;
  };
  ParamRange(std::string_view text, const Command& c) : t_(text), c_(c) {}
  iterator begin() const { return iterator(t_, c_); }
  iterator end() const { return iterator(); }

 private:
  std::string_view t_;
  Command c_;
};

struct ParsedFile {
  const SourceFile* source = nullptr;
  LineTable lines;
  CommandTable commands;
  std::vector<ParseError> errors;
  /// Expressions cut short by a ';' (RRF113 reports them, not syntax-error): from the '{' (or the start of a
  /// meta-command expression) to the end of the code; the ';' follows after optional blanks. A result of the parse
  /// (the lexer's finding, like `errors`), not a prefilter.
  std::vector<Span> semicolon_cuts;
  /// The commands inside if/elif/else/while blocks (those whose line is LineTable::in_block), as ranges of
  /// command indices [first, second), in order, disjoint and not adjacent: the graph marks a range *maybe* at once.
  std::vector<std::pair<uint32_t, uint32_t>> block_commands;
  bool mixed_indentation = false;

  /// Per-rule prefilters: summaries the parse keeps so that a rule (or the suppression pass) can skip the lines,
  /// commands or files that cannot hold what it looks for.
  ///
  /// The contract: a prefilter may only over-approximate. A line set may hold lines without the byte it names,
  /// a flag may be true when no command has it, `commands_with` may list commands without the flag; a rule must
  /// check what it reports itself, and must give the same findings with every prefilter off (each line set = every
  /// line, each flag = true, `commands_with` = every command: ParseOptions::no_prefilters, LintOptions::no_prefilters;
  /// the fixture runner lints every case both ways). A new summary kept for one rule belongs here.
  struct Prefilters {
    /// The lines whose code holds a byte other than a letter, digit, blank, '.', '-', '+' or ':' (a quote, a
    /// brace, a parenthesis, an apostrophe …), in order. A rule that looks for such a byte walks these lines only.
    LineSet rich_lines;
    /// Of those, the command lines (LineKind::Commands) whose code holds a '(', and the lines whose code holds an
    /// apostrophe: the rules about them walk these only.
    LineSet paren_lines, apostrophe_lines;
    /// The lines whose comment holds a ':': a suppression comment (`; rrflint: ...`) can stand only there.
    LineSet colon_comment_lines;
    /// The command lines whose code may hold a value without a letter: the lines of the short path whose byte
    /// masks show a blank, then a digit, sign or '.', after a byte other than a letter, and every other command
    /// line (the rule tests those with may_hold_stray_value, lint/syntax/byte_classes.h).
    LineSet stray_value_lines;
    /// The command lines whose code may hold a closing quote with two letters right after it
    /// (may_have_word_after_quote in lint/syntax/byte_classes.h).
    LineSet word_after_quote_lines;
    /// Every line set above, to size, fill or clear them all.
    std::array<LineSet*, 6> line_sets() {
      return {&rich_lines,          &paren_lines,       &apostrophe_lines,
              &colon_comment_lines, &stray_value_lines, &word_after_quote_lines};
    }
    // Whether any command has the flag of that name (Command::any_exponent …): a rule skips the file when not.
    bool any_exponent = false;
    bool any_blank_before_colon = false;
    bool any_repeated_letter = false;
    bool any_line_number = false;  // some line starts with N…
    bool any_tab_indent = false;   // some line of code is indented with a tab
    /// The commands with Command::any_exponent / any_blank_before_colon / any_repeated_letter set, in order
    /// (CommandTable::with_flag); every command when the prefilters are off.
    std::vector<uint32_t> commands_with(const CommandTable& table, CommandTable::Flag f) const;
    bool off = false;  // ParseOptions::no_prefilters: everything above holds everything
  };
  Prefilters prefilters;
  /// Lines RRF writes into a file instead of running them: after `M28 name` up to and including its `M29` (to the
  /// end of the file without one), and after `M559`/`M560` up to and including the line with `<!-- **EoF** -->`.
  /// `written_lines` are [begin, end) line ranges in order; `written_commands` the same stretches as command index
  /// ranges. Their commands stay in `commands` (lexical rules read them as text), but no code index lists them
  /// (with_code, used_codes, unlisted_codes) and the boot graph does not run them.
  std::vector<std::pair<uint32_t, uint32_t>> written_lines, written_commands;
  uint64_t serial = 0;  // unique per parse (keys find()'s cache)
  /// The commands with this letter and number (any fraction), in file order, as indices into `commands`. For
  /// 'T' every T command, whatever its number. Numbers outside 0…1023 have no list: filter `commands` for them.
  CodeCommands with_code(char letter, int32_t number) const;
  /// The codes the file uses, in key order (G by number, then M, then T), each with its commands and whether
  /// one of them has a fraction (G59.3): a rule about codes looks at each code once instead of at every command.
  struct UsedCode {
    char letter;
    int32_t number;  // -1 for T
    bool any_fraction;
    CodeCommands commands;
  };
  std::vector<UsedCode> used_codes() const;
  /// The G and M commands with no list in with_code (no number, or one outside 0…1023), in file order.
  CodeCommands unlisted_codes() const;

  std::string_view text(Span s) const { return source->slice(s); }
  /// The parameters of a command, in order.
  ParamRange params(const Command& c) const { return ParamRange(source->text(), c); }
  /// The first parameter with this letter (RRF's Seen() finds the first one).
  ParamRef find(const Command& c, char letter) const;
  /// Does a parse error (`errors`), or a ';' cut (`semicolon_cuts`), start in [b, e)? A binary search: a rule asks
  /// this once per finding, and a large file may have thousands of errors.
  bool any_error_from(uint32_t b, uint32_t e) const { return any_from(error_starts_, b, e); }
  bool any_cut_from(uint32_t b, uint32_t e) const { return any_from(cut_starts_, b, e); }
  Line line_of(const Command& c) const { return lines[c.line]; }

 private:
  friend ParsedFile parse(const SourceFile&, const ParseOptions&);
  friend void index_codes(ParsedFile&);
  friend void mark_written(ParsedFile&);
  CodeCommands run(size_t j) const;  // the commands of code_keys_[j]
  CodeCommands of_key(uint16_t key) const;
  // Every command's index, sorted by code key (then file order). Keys: G0…G1023, M0…M1023, T, then the commands of
  // no key (unlisted_codes). code_keys_ are the keys the file uses, in order; the run of code_keys_[j] is
  // [code_start_[j], code_start_[j + 1]).
  std::vector<uint32_t> code_order_;
  std::vector<uint16_t> code_keys_;
  std::vector<uint32_t> code_start_;
  std::vector<uint16_t> fraction_keys_;  // the keys with a fractional command, in order
  // The starts of `errors` and of `semicolon_cuts`, sorted (filled at the end of parse()).
  std::vector<uint32_t> error_starts_, cut_starts_;
  static bool any_from(const std::vector<uint32_t>& starts, uint32_t b, uint32_t e) {
    const auto it = std::lower_bound(starts.begin(), starts.end(), b);
    return it != starts.end() && *it < e;
  }
};

ParsedFile parse(const SourceFile& file, const ParseOptions& opts = {});

/// True for codes whose single string argument may be unquoted and runs to the end of the line.
bool takes_rest_of_line(char letter, int32_t number);
/// True for the codes among those whose string needs no letter either (M117 text, M23 file).
bool takes_unlettered_string(char letter, int32_t number);

}  // namespace rrflint

// The records' inline decoders (CommandTable::operator[], LineTable::operator[]), which need Command and Line.
#include "lint/syntax/records_inl.h"  // IWYU pragma: export
