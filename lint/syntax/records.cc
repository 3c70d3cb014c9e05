// The record tables: commands and lines stored as 20-byte records, and the line sets.

#include <algorithm>
#include <atomic>

#include "lint/syntax/parse_internal.h"

namespace rrflint {

void LineSet::insert(uint32_t i) {
  if (i / 64 >= words_.size()) words_.resize(i / 64 + 1, 0);  // only a parse on one thread (NUL bytes) gets here
  std::atomic_ref<uint64_t>(words_[i / 64]).fetch_or(uint64_t{1} << (i % 64), std::memory_order_relaxed);
}

void LineSet::clear(uint32_t from, uint32_t to) {
  for (uint32_t i = from; i < to && i / 64 < words_.size(); ++i) words_[i / 64] &= ~(uint64_t{1} << (i % 64));
}

void CommandTable::add(const Command& c) {
  detail::CommandRec r;
  const auto i = static_cast<uint32_t>(recs_.size());
  r.begin = c.span.begin;
  r.end = c.span.end;
  r.line = c.line;
  r.number = c.number;
  r.fraction = c.fraction;
  const uint32_t wl = c.word.end - c.word.begin;
  r.word_len = static_cast<uint8_t>(wl < 255 ? wl : 255);
  if (wl >= 255) long_words_[i] = c.word.end;
  r.param_count = static_cast<uint8_t>(c.param_count < 255 ? c.param_count : 255);
  if (c.param_count >= 255) big_counts_[i] = c.param_count;
  r.bits = static_cast<uint8_t>(detail::letter_bits(c.letter) | (c.number_expr ? detail::kNumberExpr : 0) |
                                (c.has_number ? detail::kHasNumber : 0) | (c.cnc ? detail::kCnc : 0) |
                                (c.any_exponent ? detail::kAnyExponent : 0) |
                                (c.any_blank_before_colon ? detail::kAnyBlankColon : 0) |
                                (c.any_repeated_letter ? detail::kAnyRepeat : 0));
  push_rec(r);
}

std::vector<uint32_t> CommandTable::with_flag(Flag f) const {
  std::vector<uint32_t> out;
  const auto bit = static_cast<uint8_t>(f);
  each_rec([&](size_t i, const detail::CommandRec& r) {
    if (r.bits & bit) out.push_back(static_cast<uint32_t>(i));
  });
  return out;
}

const detail::CommandRec& CommandTable::tail_rec(size_t i) const {
  // The last tail that starts at or before i (tails of no commands share their begin with the next one, which
  // upper_bound then picks): it lies between the tails of i's block and of the next block, which are few (one or
  // two, but many when a file is parsed in parts of a few bytes, so a binary search).
  const size_t b = i >> kTailBlock;
  const auto first = tails_.begin() + tail_of_block_[b];
  const auto last = b + 1 < tail_of_block_.size() ? tails_.begin() + tail_of_block_[b + 1] + 1 : tails_.end();
  const auto t = std::upper_bound(first, last, i, [](size_t v, const Tail& x) { return v < x.begin; });
  return (t - 1)->recs[i - (t - 1)->begin];
}

void CommandTable::append(CommandTable&& part) {
  const auto base = static_cast<uint32_t>(size());
  for (const auto& [k, v] : part.long_words_) long_words_[k + base] = v;
  for (const auto& [k, v] : part.big_counts_) big_counts_[k + base] = v;
  tail_size_ += part.recs_.size();
  if (!part.key_counts_.empty()) {
    if (key_counts_.empty()) key_counts_.assign(part.key_counts_.size(), 0);
    if (part.recs_.size() < key_counts_.size() / 8) {
      // A small part (tests parse in parts of a few bytes): count its records rather than add every key.
      for (const detail::CommandRec& r : part.recs_) ++key_counts_[code_key(detail::letter_of(r.bits), r.number)];
    } else {
      for (size_t k = 0; k < key_counts_.size(); ++k) key_counts_[k] += part.key_counts_[k];
    }
  }
  fraction_keys_.insert(fraction_keys_.end(), part.fraction_keys_.begin(), part.fraction_keys_.end());
  all_bits_ |= part.all_bits_;
  tails_.push_back(Tail{base, std::move(part.recs_)});
  // The blocks that start in this tail (none when it is empty); those before it are numbered already.
  const auto tail = static_cast<uint32_t>(tails_.size() - 1);
  while ((tail_of_block_.size() << kTailBlock) < base + tails_.back().recs.size())
    tail_of_block_.push_back((tail_of_block_.size() << kTailBlock) < base ? 0 : tail);
  part = CommandTable{};
}

uint32_t CommandTable::long_word_end(size_t i) const { return long_words_.at(static_cast<uint32_t>(i)); }
uint32_t CommandTable::big_count(size_t i) const { return big_counts_.at(static_cast<uint32_t>(i)); }

void LineTable::add(const Line& l) {
  recs_.emplace_back();
  put(recs_.back(), static_cast<uint32_t>(recs_.size() - 1), l);
}

void LineTable::put(detail::LineRec& r, uint32_t i, const Line& l) {
  r.code_begin = l.code.begin;
  r.code_end = l.code.end;
  if (l.kind == LineKind::Meta) {
    r.first = static_cast<uint32_t>(metas_.size());
    metas_.push_back({l.meta_arg, l.meta_name});
  } else {
    r.first = l.first_command;
  }
  r.indent = static_cast<uint16_t>(l.indent < 65535 ? l.indent : 65535);
  r.stored_length = static_cast<uint16_t>(l.stored_length < 65535 ? l.stored_length : 65535);
  if (l.indent >= 65535 || l.stored_length >= 65535) long_lines_[i] = {l.indent, l.stored_length};
  r.command_count = static_cast<uint16_t>(l.command_count < 65535 ? l.command_count : 65535);
  if (l.command_count >= 65535) big_counts_[i] = l.command_count;
  r.kind_meta = static_cast<uint8_t>(static_cast<unsigned>(l.kind) | (static_cast<unsigned>(l.meta) << 3) |
                                     (l.comment.empty() ? 0 : 0x80));
  r.flags =
      static_cast<uint8_t>((l.indent_tabs ? detail::kIndentTabs : 0) | (l.indent_spaces ? detail::kIndentSpaces : 0) |
                           (l.line_number ? detail::kLineNumber : 0) | (l.checksum ? detail::kChecksum : 0) |
                           (l.conditional ? detail::kConditional : 0) | (l.in_loop ? detail::kInLoop : 0) |
                           (l.after_nul ? detail::kAfterNul : 0));
}

uint32_t LineTable::big_count(size_t i) const { return big_counts_.at(static_cast<uint32_t>(i)); }
uint32_t LineTable::long_indent(size_t i) const { return long_lines_.at(static_cast<uint32_t>(i)).first; }
uint32_t LineTable::long_length(size_t i) const { return long_lines_.at(static_cast<uint32_t>(i)).second; }

}  // namespace rrflint
