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

#include <compare>
#include <cstring>
#include <cstdint>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <string_view>
#include <vector>

#include "lint/base/source.h"

// Decoding is inlined where a record is read, so that the compiler drops the fields a caller never reads (most
// loops read a line's kind or a command's code only).
#if defined(__GNUC__)
#define RRFLINT_ALWAYS_INLINE __attribute__((always_inline))
#else
#define RRFLINT_ALWAYS_INLINE
#endif

namespace rrflint {

struct ParsedFile;
class LineParser;

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
  Span span;             // the whole command text, trimmed
  Span word;             // "M563", "g59.3", "T{…}"
  char letter = 0;       // 'G', 'M' or 'T' (upper-cased)
  int32_t number = -1;   // code number; -1 for `T` with no number; for T{expr} also -1
  int8_t fraction = -1;  // digit after '.', -1 if none
  bool number_expr = false;  // T{expr}
  bool has_number = false;   // digits follow the letter: tells `T-1` (deselect) from a bare `T` (report)
  bool cnc = false;          // parsed in CNC mode: `( )` is a comment inside it
  bool any_exponent = false;        // some parameter swallowed an E after a digit (Param::exponent_letter)
  bool any_blank_before_colon = false;  // some parameter has Param::blank_before_colon
  bool any_repeated_letter = false;     // two parameters have the same letter
  uint32_t line = 0;         // index into ParsedFile::lines
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
  /// A line of bare axis words (`X5 F300`) read outside CNC and laser mode. In those modes (M453, M452) RRF repeats
  /// the last G0-G3 with them; a file that never sets the mode may run in one, which the syntax-error rule checks.
  bool axis_repeat = false;
};

struct ParseOptions {
  bool cnc_mode = false;  // `( )` comments are recognised only in CNC mode (M453)
  bool laser_mode = false;  // M452: like CNC mode, a line of axis words repeats the last move (no `( )` comments)
  /// A large file is cut at line starts into parts of at least `part_bytes`, parsed on up to `threads` threads
  /// and joined. The result is the same as a parse on one thread (a part that a mode switch before it changes is
  /// parsed again).
  unsigned threads = 1;
  size_t part_bytes = size_t{2} << 20;
  /// Most lines (`G1 X10 Y20 ; note`: commands of letters, numbers and lists, indented by spaces if at all) take a short path
  /// that classifies the line's bytes 16 at a time. Off: every line goes through the full lexer. The result is the
  /// same either way; the tests compare the two.
  bool fast_lines = true;
};

namespace detail {

enum LineFlag : uint8_t {
  kIndentTabs = 1,
  kIndentSpaces = 2,
  kLineNumber = 4,
  kChecksum = 8,
  kConditional = 16,
  kInLoop = 32,
  kAfterNul = 64,
  kCutByDel = 128,  // a 0x7F byte ended the line early
};

enum CommandBits : uint8_t {
  kLetterMask = 3,  // 0 G, 1 M, 2 T
  kNumberExpr = 4,
  kHasNumber = 8,
  kCnc = 16,
  kAnyExponent = 32,
  kAnyBlankColon = 64,
  kAnyRepeat = 128,
};

/// The command letter stored in a CommandRec's bits, and the bits that store one ('G', 'M' or 'T').
inline char letter_of(uint8_t bits) {
  const unsigned l = bits & kLetterMask;
  return l == 0 ? 'G' : l == 1 ? 'M' : 'T';
}
inline uint8_t letter_bits(char letter) { return letter == 'G' ? 0 : letter == 'M' ? 1 : 2; }

// The stored form of a line: 20 bytes. Spans, the comment and the meta-command parts are recovered on decoding.
// Both records are trivial (no member initialisers): LineTable::put and CommandTable::add write every field, and a
// table sized ahead of a parse in parts is not zeroed first (DefaultInit below).
struct LineRec {
  uint32_t code_begin, code_end;
  uint32_t first;            // Commands/Bad: first command; Meta: index into the meta table
  uint16_t indent;           // saturated: the exact value is then in LineTable::long_lines_
  uint16_t stored_length;    // saturated: likewise
  uint16_t command_count;    // saturated: the exact count is then in LineTable::big_counts_
  uint8_t kind_meta;         // LineKind (3 bits) | MetaKind (4 bits) << 3 | 0x80 when the line has a comment
  uint8_t flags;             // LineFlag bits
};

// The stored form of a command: 20 bytes.
struct CommandRec {
  uint32_t begin, end;  // the command's span
  uint32_t line;
  int32_t number;
  uint8_t word_len;     // saturated: the exact word is then in CommandTable::long_words_
  int8_t fraction;
  uint8_t bits;         // letter (2 bits) and CommandFlag bits
  uint8_t param_count;  // saturated: the exact count is then in CommandTable::big_counts_
};

// An allocator that leaves trivial elements uninitialised on resize() (the parser writes each one).
template <class T>
struct DefaultInit : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInit<U>;
  };
  using std::allocator<T>::allocator;
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace detail

/// A random-access view that decodes records on access. Elements are values: bind them as `const T&` (the
/// temporary lives as long as the reference) and never keep pointers to them.
template <class Table, class T>
class DecodingIterator {
 public:
  using iterator_category = std::random_access_iterator_tag;
  using value_type = T;
  using difference_type = std::ptrdiff_t;
  using pointer = void;
  using reference = T;
  DecodingIterator() = default;
  DecodingIterator(const Table* t, size_t i) : t_(t), i_(i) {}
  RRFLINT_ALWAYS_INLINE T operator*() const { return (*t_)[i_]; }
  T operator[](difference_type n) const { return (*t_)[i_ + n]; }
  DecodingIterator& operator++() { ++i_; return *this; }
  DecodingIterator operator++(int) { auto r = *this; ++i_; return r; }
  DecodingIterator& operator--() { --i_; return *this; }
  DecodingIterator& operator+=(difference_type n) { i_ += n; return *this; }
  DecodingIterator operator+(difference_type n) const { return {t_, i_ + n}; }
  DecodingIterator operator-(difference_type n) const { return {t_, i_ - n}; }
  difference_type operator-(const DecodingIterator& o) const { return static_cast<difference_type>(i_ - o.i_); }
  friend bool operator==(const DecodingIterator& a, const DecodingIterator& b) { return a.i_ == b.i_; }
  friend auto operator<=>(const DecodingIterator& a, const DecodingIterator& b) { return a.i_ <=> b.i_; }

 private:
  const Table* t_ = nullptr;
  size_t i_ = 0;
};

/// The commands of a file, in order.
class CommandTable {
 public:
  Command operator[](size_t i) const;
  size_t size() const { return recs_.size() + tail_size_; }
  bool empty() const { return size() == 0; }
  DecodingIterator<CommandTable, Command> begin() const { return {this, 0}; }
  DecodingIterator<CommandTable, Command> end() const { return {this, size()}; }
  /// Command i's letter, number, fraction and line, read from its record without decoding the command (the graph
  /// and the forward pass ask every command for its code and act on few).
  struct Code {
    char letter;
    int32_t number;
    int8_t fraction;
    uint32_t line;
    /// Is this `letter``number` with no fraction (M563, not M563.1)? Like Command::is.
    bool is(char l, int32_t n) const { return letter == l && number == n && fraction < 0; }
  };
  Code code(size_t i) const {
    const detail::CommandRec& r = rec(i);
    return Code{detail::letter_of(r.bits), r.number, r.fraction, r.line};
  }
  /// The commands with Command::any_exponent / any_blank_before_colon / any_repeated_letter set, in order, read
  /// from the records in one sweep (a rule about such commands need not decode every command).
  enum class Flag : uint8_t {
    Exponent = detail::kAnyExponent,
    BlankBeforeColon = detail::kAnyBlankColon,
    RepeatedLetter = detail::kAnyRepeat
  };
  std::vector<uint32_t> with_flag(Flag f) const;

 private:
  friend class LineParser;
  friend struct ParsedFile;
  friend ParsedFile parse(const SourceFile&, const ParseOptions&);
  friend void index_codes(ParsedFile&);
  friend class CodeCommands;
  void add(const Command& c);
  /// Appends the commands of a later part of the file (a parse in parts); `part` is left empty.
  void append(CommandTable&& part);
  uint32_t long_word_end(size_t i) const;
  uint32_t big_count(size_t i) const;
  const detail::CommandRec& rec(size_t i) const { return i < recs_.size() ? recs_[i] : tail_rec(i); }
  /// Calls f(i, record) for every command in order: a sweep of the parts, with no per-command part look-up.
  template <class F>
  void each_rec(F f) const {
    for (size_t i = 0; i < recs_.size(); ++i) f(i, recs_[i]);
    for (const Tail& t : tails_)
      for (size_t i = 0; i < t.recs.size(); ++i) f(t.begin + i, t.recs[i]);
  }
  const detail::CommandRec& tail_rec(size_t i) const;
  std::vector<detail::CommandRec> recs_;
  // A file parsed in parts keeps the later parts' records as they were made, after recs_: no copy, no peak.
  struct Tail {
    size_t begin;  // the index of its first command
    std::vector<detail::CommandRec> recs;
  };
  std::vector<Tail> tails_;
  size_t tail_size_ = 0;
  std::vector<uint32_t> block_tail_;  // per block of 64K commands: the last tail starting at or before it
  void push_rec(const detail::CommandRec& r);
  // Kept as records are pushed, for index_codes: commands per code key, the keys of fractional commands (with
  // repeats), and the OR of every record's bits.
  std::vector<uint32_t> key_counts_;
  std::vector<uint16_t> fraction_keys_;
  uint8_t all_bits_ = 0;
  std::map<uint32_t, uint32_t> long_words_;  // command -> word end, for words of 255 bytes or more
  std::map<uint32_t, uint32_t> big_counts_;  // command -> parameter count, for 255 or more
};

/// The logical lines of a file, in order (an editor line with NUL bytes holds several).
class LineTable {
 public:
  Line operator[](size_t i) const;
  /// Line i's `conditional || in_loop`, without decoding the line (the graph asks for every command it runs).
  bool in_block(size_t i) const { return recs_[i].flags & (detail::kConditional | detail::kInLoop); }
  /// Line i's kind and code, without decoding the line (a rule skips most lines on these).
  LineKind kind(size_t i) const { return static_cast<LineKind>(recs_[i].kind_meta & 7); }
  Span code(size_t i) const { return Span{recs_[i].code_begin, recs_[i].code_end}; }
  bool has_comment(size_t i) const { return recs_[i].kind_meta & 0x80; }
  /// Line i's span (without its terminator) and stored length, likewise.
  Span span(size_t i) const { return spans_.empty() ? source_->line_span(static_cast<uint32_t>(i)) : spans_[i]; }
  uint32_t stored_length(size_t i) const {
    return recs_[i].stored_length < 65535 ? recs_[i].stored_length : long_length(i);
  }
  size_t size() const { return recs_.size(); }
  bool empty() const { return recs_.empty(); }
  DecodingIterator<LineTable, Line> begin() const { return {this, 0}; }
  DecodingIterator<LineTable, Line> end() const { return {this, size()}; }

 private:
  friend class LineParser;
  friend struct ParsedFile;
  friend ParsedFile parse(const SourceFile&, const ParseOptions&);
  friend void compute_blocks(ParsedFile&);
  void add(const Line& l);
  /// Stores line `i` into `dst`: its meta-command parts and any saturated counts go to this table.
  void put(detail::LineRec& dst, uint32_t i, const Line& l);
  uint32_t big_count(size_t i) const;
  uint32_t long_indent(size_t i) const;
  uint32_t long_length(size_t i) const;
  struct MetaRec {
    Span arg, name;
  };
  const SourceFile* source_ = nullptr;
  std::vector<detail::LineRec, detail::DefaultInit<detail::LineRec>> recs_;
  std::vector<MetaRec> metas_;
  std::vector<Span> spans_;  // every logical line's span, kept only when the file has NUL bytes
  std::map<uint32_t, uint32_t> big_counts_;  // line -> command count, for 65535 or more
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> long_lines_;  // line -> (indent, stored length), 65535 or more
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
    friend bool operator==(const iterator& a, const iterator& b) { return a.done_ == b.done_ && (a.done_ || a.pos_ == b.pos_); }

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

namespace detail {
// What a forward iterator over indices needs besides `*`, prefix `++` and `==` (CodeCommands, LineSet).
template <class Derived>
struct IndexIterator {
  using iterator_category = std::forward_iterator_tag;
  using value_type = uint32_t;
  using difference_type = std::ptrdiff_t;
  using pointer = const uint32_t*;
  using reference = uint32_t;
  Derived operator++(int) {
    Derived r = static_cast<Derived&>(*this);
    ++static_cast<Derived&>(*this);
    return r;
  }
};
}  // namespace detail

/// A set of line indices, a bit per line of the file (about 0.4 MB for 3 million lines), iterated in order.
class LineSet {
 public:
  class iterator : public detail::IndexIterator<iterator> {
   public:
    iterator() = default;
    iterator(const std::vector<uint64_t>* w, size_t bit) : w_(w), bit_(bit) { seek(); }
    uint32_t operator*() const { return static_cast<uint32_t>(bit_); }
    iterator& operator++() {
      ++bit_;
      seek();
      return *this;
    }
    using IndexIterator::operator++;
    friend bool operator==(const iterator& a, const iterator& b) { return a.bit_ == b.bit_; }

   private:
    void seek() {  // on to the next set bit, or the end
      const size_t end = w_->size() * 64;
      while (bit_ < end) {
        const uint64_t rest = (*w_)[bit_ / 64] >> (bit_ % 64);
        if (rest) {
          bit_ += static_cast<size_t>(__builtin_ctzll(rest));
          return;
        }
        bit_ = (bit_ / 64 + 1) * 64;
      }
      bit_ = end;
    }
    const std::vector<uint64_t>* w_ = nullptr;
    size_t bit_ = 0;
  };
  iterator begin() const { return {&words_, 0}; }
  iterator end() const { return {&words_, words_.size() * 64}; }
  bool contains(uint32_t i) const { return i / 64 < words_.size() && (words_[i / 64] >> (i % 64) & 1); }

 private:
  friend class LineParser;
  friend ParsedFile parse(const SourceFile&, const ParseOptions&);
  void resize(size_t lines) { words_.assign(lines / 64 + 1, 0); }
  /// Parts of a file parsed at once set bits of the same word at their edges: atomically.
  void insert(uint32_t i);
  void clear(uint32_t from, uint32_t to);
  std::vector<uint64_t> words_;
};

/// The indices of a file's commands of one code, in file order (ParsedFile::with_code): a run of a table sorted
/// by code. The commands of a code lie far apart in a large file, so the iterator asks the processor to fetch the
/// records and the text of the commands a few steps ahead.
class CodeCommands {
 public:
  class iterator : public detail::IndexIterator<iterator> {
   public:
    iterator() = default;
    iterator(const uint32_t* p, const uint32_t* end, const CommandTable* table, const char* text)
        : p_(p), end_(end), table_(table), text_(text) {}
    uint32_t operator*() const { return *p_; }
    iterator& operator++() {
      ++p_;
#if defined(__GNUC__)
      if (end_ - p_ > 8) __builtin_prefetch(&table_->rec(p_[8]));
      if (end_ - p_ > 4) __builtin_prefetch(text_ + table_->rec(p_[4]).begin);
#endif
      return *this;
    }
    using IndexIterator::operator++;
    friend bool operator==(const iterator& a, const iterator& b) { return a.p_ == b.p_; }

   private:
    const uint32_t* p_ = nullptr;
    const uint32_t* end_ = nullptr;
    const CommandTable* table_ = nullptr;
    const char* text_ = nullptr;
  };
  CodeCommands() = default;
  CodeCommands(const uint32_t* begin, const uint32_t* end, const CommandTable* table, const char* text)
      : begin_(begin), end_(end), table_(table), text_(text) {}
  iterator begin() const { return {begin_, end_, table_, text_}; }
  iterator end() const { return {end_, end_, table_, text_}; }
  bool empty() const { return begin_ == end_; }
  size_t size() const { return static_cast<size_t>(end_ - begin_); }

 private:
  const uint32_t* begin_ = nullptr;
  const uint32_t* end_ = nullptr;
  const CommandTable* table_ = nullptr;
  const char* text_ = nullptr;
};

struct ParsedFile {
  const SourceFile* source = nullptr;
  LineTable lines;
  CommandTable commands;
  std::vector<ParseError> errors;
  /// Expressions cut short by a ';' (RRF113 reports them, not syntax-error): from the '{' (or the start of a
  /// meta-command expression) to the end of the code; the ';' follows after optional blanks.
  std::vector<Span> semicolon_cuts;
  /// The lines whose code holds a byte other than a letter, digit, blank, '.', '-', '+' or ':' (a quote, a brace,
  /// a parenthesis, an apostrophe …), in order. A rule that looks for such a byte walks these lines only.
  LineSet rich_lines;
  /// Of those, the command lines (LineKind::Commands) whose code holds a '(', and the lines whose code holds an
  /// apostrophe: the rules about them walk these only.
  LineSet paren_lines, apostrophe_lines;
  /// The lines whose comment holds a ':': a suppression comment (`; rrflint: ...`) can stand only there.
  LineSet colon_comment_lines;
  /// The commands inside if/elif/else/while blocks (those whose line is LineTable::in_block), as ranges of
  /// command indices [first, second), in order, disjoint and not adjacent: the graph marks a range *maybe* at once.
  std::vector<std::pair<uint32_t, uint32_t>> block_commands;
  bool mixed_indentation = false;
  // Whether any command has the flag of that name (Command::any_exponent …): a rule skips the file when not.
  bool any_exponent = false;
  bool any_blank_before_colon = false;
  bool any_repeated_letter = false;
  bool any_line_number = false;  // some line starts with N…
  bool any_tab_indent = false;   // some line of code is indented with a tab
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
  Line line_of(const Command& c) const { return lines[c.line]; }

 private:
  friend ParsedFile parse(const SourceFile&, const ParseOptions&);
  friend void index_codes(ParsedFile&);
  CodeCommands run(size_t j) const;     // the commands of code_keys_[j]
  CodeCommands of_key(uint16_t key) const;
  // Every command's index, sorted by code key (then file order). Keys: G0…G1023, M0…M1023, T, then the commands of
  // no key (unlisted_codes). code_keys_ are the keys the file uses, in order; the run of code_keys_[j] is
  // [code_start_[j], code_start_[j + 1]).
  std::vector<uint32_t> code_order_;
  std::vector<uint16_t> code_keys_;
  std::vector<uint32_t> code_start_;
  std::vector<uint16_t> fraction_keys_;  // the keys with a fractional command, in order
};

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

ParsedFile parse(const SourceFile& file, const ParseOptions& opts = {});

/// True for codes whose single string argument may be unquoted and runs to the end of the line.
bool takes_rest_of_line(char letter, int32_t number);
/// True for the codes among those whose string needs no letter either (M117 text, M23 file).
bool takes_unlettered_string(char letter, int32_t number);

}  // namespace rrflint
