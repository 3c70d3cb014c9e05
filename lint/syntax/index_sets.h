// Sets of indices the parse hands out: LineSet (a bit per line) and CodeCommands (the commands of one code).
// Included by lint/syntax/parser.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <span>
#include <vector>

#include "lint/syntax/records.h"

namespace rrflint {

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
  /// Every line of [0, lines) (ParseOptions::no_prefilters).
  void fill(size_t lines) {
    words_.assign(lines / 64 + 1, 0);
    for (size_t i = 0; i < lines; ++i) words_[i / 64] |= uint64_t{1} << (i % 64);
  }
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
  /// The command indices themselves, ascending (for a binary search).
  std::span<const uint32_t> indices() const { return {begin_, end_}; }

 private:
  const uint32_t* begin_ = nullptr;
  const uint32_t* end_ = nullptr;
  const CommandTable* table_ = nullptr;
  const char* text_ = nullptr;
};

}  // namespace rrflint
