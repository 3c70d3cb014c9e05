// The command documentation table (command_docs.h): the lookup over the parts in command_docs_g.cc and
// command_docs_m{1,2,3}.cc, joined in order into one sorted view.
//
// Anchors. docs.duet3d.com is a Wiki.js site whose page User_manual/Reference/Gcodes is the markdown file
// User_manual/Reference/Gcodes.md of github.com/Duet3D/wiki-content, read at commit
// 91f23488a78d0f1baad02bf1c582e8292ac5d3b2 (2026-08-22). Each command has a `## CODE: title` heading, and the
// site makes its anchor from the heading text the way Wiki.js does (its `uslug` slugs): lower-case it, keep letters,
// digits, '-', '_' and '~', drop every other character (':', '.', '/', '(', ...), and turn each run of blanks and
// hyphens into one '-'; a slug that starts with a digit gets "h-" in front and a repeated slug gets "-1", "-2".
// So "## M563: Define or remove a tool" -> m563-define-or-remove-a-tool, "## M569.1: Stepper driver closed loop
// configuration" -> m5691-stepper-driver-closed-loop-configuration, "## M304: Set PID parameters - Bed" ->
// m304-set-pid-parameters-bed. The rule reproduces 273 of the 278 distinct Gcodes# links inside wiki-content
// itself; the other five point at headings that no longer exist. Where the page has several sections for one
// code (G10: temperatures, offsets, retract; M568: tool settings and the old mixing switch), the entry links the
// one RRF 3 mostly means.
//
// Summaries and parameter phrases are rrflint's own words for what the firmware does (docs/firmware-behaviour.md
// and the source it cites), not text from the dictionary. The table has only codes RRF implements in some
// version rrflint knows (lint/boot/command_table.inc); tests/command_docs_test.cc checks that, and that every
// code the machine model or a rule interprets has an entry.
#include "lint/boot/command_docs.h"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "lint/boot/command_docs_parts.h"

namespace rrflint {
namespace {

/// The parts in table order (each part is sorted, and each starts after the previous one ends).
const std::vector<CommandDoc>& all_docs() {
  static const std::vector<CommandDoc> all = [] {
    std::vector<CommandDoc> v;
    for (auto part : {docs::g_codes(), docs::m_codes_low(), docs::m_codes_mid(), docs::m_codes_high()})
      v.insert(v.end(), part.begin(), part.end());
    return v;
  }();
  return all;
}

}  // namespace

std::span<const CommandDoc> command_docs() { return all_docs(); }

const CommandDoc* command_doc(char letter, int number, int fraction) {
  // Every T command (T0, T-1, T alone) is the one command "T": its entry has number and fraction -1.
  if (letter == 'T') number = fraction = -1;
  const auto want = std::tuple(letter, number, fraction);
  const std::vector<CommandDoc>& all = all_docs();
  auto it = std::lower_bound(all.begin(), all.end(), want,
                             [](const CommandDoc& d, const auto& k) { return docs::key(d) < k; });
  return it != all.end() && docs::key(*it) == want ? &*it : nullptr;
}

std::string command_doc_url(const CommandDoc& d) { return fmt::format("{}#{}", kGcodePage, d.anchor); }

std::string command_name(const CommandDoc& d) {
  if (d.letter == 'T') return "T";
  return d.fraction < 0 ? fmt::format("{}{}", d.letter, d.number)
                        : fmt::format("{}{}.{}", d.letter, d.number, d.fraction);
}

}  // namespace rrflint
