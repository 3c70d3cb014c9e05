// The code index: every command sorted by code, for ParsedFile::with_code and used_codes.

#include "lint/syntax/parse_internal.h"

namespace rrflint {

// Sorts the commands by code: a counting sort whose counts the parse kept (CommandTable::push_rec), so one sweep
// of the records places them. Only the keys the file uses are kept (a few dozen, where the counts have 2,050).
void index_codes(ParsedFile& pf) {
  CommandTable& t = pf.commands;
  pf.code_keys_.clear();
  pf.code_start_.assign(1, 0);
  std::vector<uint32_t>& at = t.key_counts_;  // each key's count, then where its next command goes
  uint32_t pos = 0;
  for (size_t k = 0; k < at.size(); ++k) {
    const uint32_t count = at[k];
    at[k] = pos;
    if (count == 0) continue;
    pos += count;
    pf.code_keys_.push_back(static_cast<uint16_t>(k));
    pf.code_start_.push_back(pos);
  }
  pf.code_order_.resize(t.size());
  t.each_rec([&](size_t i, const detail::CommandRec& r) {
    pf.code_order_[at[code_key(detail::letter_of(r.bits), r.number)]++] = static_cast<uint32_t>(i);
  });
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
