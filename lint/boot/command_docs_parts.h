// The parts of the command documentation table (command_docs.h), one file each so that none grows too long:
// command_docs_g.cc (the G codes), command_docs_m1.cc (M0 to M299), command_docs_m2.cc (M300 to M569.x) and
// command_docs_m3.cc (M570 on, then T). command_docs.cc joins them, in that order, into one sorted view.
#pragma once

#include <cstddef>
#include <span>
#include <tuple>

#include "lint/boot/command_docs.h"

namespace rrflint::docs {

/// The order of the table: letter, number, fraction (-1, no fraction, first).
constexpr auto key(const CommandDoc& d) { return std::tuple(d.letter, d.number, d.fraction); }

/// Is a part strictly sorted (sorted, and no code twice)? Each part asserts it at compile time.
template <std::size_t N>
constexpr bool strictly_sorted(const CommandDoc (&t)[N]) {
  for (std::size_t i = 1; i < N; ++i)
    if (!(key(t[i - 1]) < key(t[i]))) return false;
  return true;
}

std::span<const CommandDoc> g_codes();
std::span<const CommandDoc> m_codes_low();
std::span<const CommandDoc> m_codes_mid();
/// M570 and above, then T.
std::span<const CommandDoc> m_codes_high();

}  // namespace rrflint::docs
