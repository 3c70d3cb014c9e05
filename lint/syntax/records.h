// The parse's storage: a 20-byte record per line and per command, decoded into `Line` and `Command` values when
// asked for (the decoders are inline, in records_inl.h, included at the end of lint/syntax/parser.h). Included by
// parser.h; rules use the tables through ParsedFile::lines and ParsedFile::commands.
#pragma once

#include <compare>
#include <cstdint>
#include <iterator>
#include <map>
#include <memory>
#include <utility>
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
struct ParseOptions;
struct Command;
struct Line;
enum class LineKind : uint8_t;
enum class MetaKind : uint8_t;
ParsedFile parse(const SourceFile&, const ParseOptions&);

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
  uint32_t first;          // Commands/Bad: first command; Meta: index into the meta table
  uint16_t indent;         // saturated: the exact value is then in LineTable::long_lines_
  uint16_t stored_length;  // saturated: likewise
  uint16_t command_count;  // saturated: the exact count is then in LineTable::big_counts_
  uint8_t kind_meta;       // LineKind (3 bits) | MetaKind (4 bits) << 3 | 0x80 when the line has a comment
  uint8_t flags;           // LineFlag bits
};

// The stored form of a command: 20 bytes.
struct CommandRec {
  uint32_t begin, end;  // the command's span
  uint32_t line;
  int32_t number;
  uint8_t word_len;  // saturated: the exact word is then in CommandTable::long_words_
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
  DecodingIterator& operator++() {
    ++i_;
    return *this;
  }
  DecodingIterator operator++(int) {
    auto r = *this;
    ++i_;
    return r;
  }
  DecodingIterator& operator--() {
    --i_;
    return *this;
  }
  DecodingIterator& operator+=(difference_type n) {
    i_ += n;
    return *this;
  }
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
  friend void mark_written(ParsedFile&);
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
  // For each block of 2^kTailBlock commands (by index), the tail that holds the block's first command (0 for the
  // blocks that start in recs_): tail_rec searches only the few tails between it and the next block's.
  static constexpr unsigned kTailBlock = 12;
  std::vector<uint32_t> tail_of_block_;
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
  /// Line i's indentation and meta keyword, likewise.
  uint32_t indent(size_t i) const { return recs_[i].indent < 65535 ? recs_[i].indent : long_indent(i); }
  MetaKind meta(size_t i) const { return static_cast<MetaKind>((recs_[i].kind_meta >> 3) & 15); }
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
  std::vector<Span> spans_;                  // every logical line's span, kept only when the file has NUL bytes
  std::map<uint32_t, uint32_t> big_counts_;  // line -> command count, for 65535 or more
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> long_lines_;  // line -> (indent, stored length), 65535 or more
};

}  // namespace rrflint
