// The code index: every command sorted by code, for ParsedFile::with_code and used_codes.

#include <algorithm>
#include <string_view>

#include "lint/syntax/parse_internal.h"

namespace rrflint {

// Sorts the commands by code: a counting sort whose counts the parse kept (CommandTable::push_rec), so one sweep
// of the records places them. Only the keys the file uses are kept (a few dozen, where the counts have 2,050).
void mark_written(ParsedFile& pf) {
  const CommandTable& t = pf.commands;
  const std::vector<uint32_t>& counts = t.key_counts_;
  if (counts.empty() || (!counts[code_key('M', 28)] && !counts[code_key('M', 559)] && !counts[code_key('M', 560)]))
    return;                                              // the common case: nothing is written
  constexpr std::string_view kEof = "<!-- **EoF** -->";  // RRF's EOF_STRING, which ends M559/M560
  const size_t n = t.size();
  const auto lines = static_cast<uint32_t>(pf.lines.size());
  for (size_t i = 0; i < n; ++i) {
    const CommandTable::Code c = t.code(i);
    if (!(c.is('M', 28) || c.is('M', 559) || c.is('M', 560))) continue;
    const uint32_t begin = c.line + 1;
    size_t j = i + 1;
    while (j < n && t.code(j).line < begin) ++j;  // the rest of the opening line runs
    const size_t first = j;
    uint32_t end = lines;
    if (c.number == 28) {
      while (j < n && !t.code(j).is('M', 29)) ++j;
      if (j < n) end = t.code(j).line + 1;
    } else {
      for (uint32_t l = begin; l < lines; ++l)
        if (pf.text(pf.lines.span(l)).find(kEof) != std::string_view::npos) {
          end = l + 1;
          break;
        }
    }
    while (j < n && t.code(j).line < end) ++j;
    if (c.number != 28 && begin < end) {  // an upload (HTML, binary) is not G-code: no parse error stands there
      const uint32_t from = pf.lines.span(begin).begin, to = pf.lines.span(end - 1).end;
      std::erase_if(pf.errors, [&](const ParseError& e) { return e.span.begin >= from && e.span.begin <= to; });
    }
    if (begin < end) {
      pf.written_lines.emplace_back(begin, end);
      pf.written_commands.emplace_back(static_cast<uint32_t>(first), static_cast<uint32_t>(j));
    }
    i = j - 1;  // go on after the written stretch
  }
}

void index_codes(ParsedFile& pf) {
  CommandTable& t = pf.commands;
  pf.code_keys_.clear();
  pf.code_start_.assign(1, 0);
  std::vector<uint32_t>& at = t.key_counts_;  // each key's count, then where its next command goes
  // Written commands (mark_written) are in no list: count the others again (rare: an M28 in the file).
  const auto& written = pf.written_commands;
  auto w = written.begin();
  auto is_written = [&](size_t i) {  // for increasing i
    while (w != written.end() && w->second <= i) ++w;
    return w != written.end() && w->first <= i;
  };
  if (!written.empty()) {
    std::fill(at.begin(), at.end(), 0);
    t.each_rec([&](size_t i, const detail::CommandRec& r) {
      if (!is_written(i)) ++at[code_key(detail::letter_of(r.bits), r.number)];
    });
    w = written.begin();
  }
  uint32_t pos = 0;
  auto place = [&](size_t k) {  // key k's commands go next
    const uint32_t count = at[k];
    at[k] = pos;
    if (count == 0) return;
    pos += count;
    pf.code_keys_.push_back(static_cast<uint16_t>(k));
    pf.code_start_.push_back(pos);
  };
  if (t.size() * 8 < at.size()) {
    // Few commands (a line parsed on its own, as a fix checks its edit): only the keys they use, not all ~2,000.
    std::vector<uint16_t> keys;
    t.each_rec([&](size_t, const detail::CommandRec& r) {
      keys.push_back(static_cast<uint16_t>(code_key(detail::letter_of(r.bits), r.number)));
    });
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    for (const uint16_t k : keys) place(k);
  } else {
    for (size_t k = 0; k < at.size(); ++k) place(k);
  }
  pf.code_order_.resize(pos);
  if (written.empty()) {
    t.each_rec([&](size_t i, const detail::CommandRec& r) {
      pf.code_order_[at[code_key(detail::letter_of(r.bits), r.number)]++] = static_cast<uint32_t>(i);
    });
  } else {
    t.each_rec([&](size_t i, const detail::CommandRec& r) {
      if (!is_written(i))
        pf.code_order_[at[code_key(detail::letter_of(r.bits), r.number)]++] = static_cast<uint32_t>(i);
    });
  }
  std::vector<uint32_t>().swap(t.key_counts_);  // used up
  pf.fraction_keys_ = t.fraction_keys_;
  std::sort(pf.fraction_keys_.begin(), pf.fraction_keys_.end());
  pf.fraction_keys_.erase(std::unique(pf.fraction_keys_.begin(), pf.fraction_keys_.end()), pf.fraction_keys_.end());
  pf.prefilters.any_exponent = t.all_bits_ & detail::kAnyExponent;
  pf.prefilters.any_blank_before_colon = t.all_bits_ & detail::kAnyBlankColon;
  pf.prefilters.any_repeated_letter = t.all_bits_ & detail::kAnyRepeat;
}

CodeCommands ParsedFile::run(size_t j) const {
  const uint32_t* base = code_order_.data();
  return CodeCommands(base + code_start_[j], base + code_start_[j + 1], &commands, source->text().data());
}

CodeCommands ParsedFile::with_code(char letter, int32_t number) const {
  const uint16_t key = code_key(letter, number);
  return key == kNoKey ? CodeCommands() : of_key(key);
}

CodeCommands ParsedFile::unlisted_codes() const { return of_key(kNoKey); }

CodeCommands ParsedFile::of_key(uint16_t key) const {
  const auto it = std::lower_bound(code_keys_.begin(), code_keys_.end(), key);
  if (it == code_keys_.end() || *it != key) return CodeCommands();
  return run(static_cast<size_t>(it - code_keys_.begin()));
}

std::vector<ParsedFile::UsedCode> ParsedFile::used_codes() const {
  std::vector<UsedCode> out;
  for (size_t j = 0; j < code_keys_.size(); ++j) {
    const uint16_t key = code_keys_[j];
    if (key == kNoKey) continue;
    const char letter = key == kTKey ? 'T' : key >= 1024 ? 'M' : 'G';
    const int32_t number = key == kTKey ? -1 : key % 1024;
    const bool fraction = std::binary_search(fraction_keys_.begin(), fraction_keys_.end(), key);
    out.push_back(UsedCode{letter, number, fraction, run(j)});
  }
  return out;
}

}  // namespace rrflint
