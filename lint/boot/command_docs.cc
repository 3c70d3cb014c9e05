// The command documentation table (command_docs.h).
#include "lint/boot/command_docs.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <tuple>

namespace rrflint {
namespace {

constexpr ParamDoc kG10[] = {
    {'P', "tool number"},
    {'L', "form: L1 tool offsets, L2/L20 workplace origins"},
    {'X', "X offset (mm)"},
    {'Y', "Y offset (mm)"},
    {'Z', "Z offset (mm)"},
    {'R', "standby temperatures, one per heater"},
    {'S', "active temperatures, one per heater"},
};
constexpr ParamDoc kM563[] = {
    {'P', "tool number"},
    {'S', "tool name"},
    {'D', "extruder drives"},
    {'H', "heaters"},
    {'F', "fans"},
    {'X', "axes the tool's X maps to"},
    {'Y', "axes the tool's Y maps to"},
    {'Z', "axes the tool's Z maps to (3.5+)"},
    {'R', "spindle (3.3+)"},
};

constexpr CommandDoc kDocs[] = {
    {'G', 10, -1, "Set tool offsets, temperatures or workplace origins",
     "With P: sets (or reports) the offsets and temperatures of an existing tool; with L2/L20: workplace origins; "
     "otherwise firmware retraction.",
     "g10-set-tool-offsets-and-temperatures", kG10},
    {'M', 563, -1, "Define or remove a tool",
     "Creates tool P (re-creating it when it exists, which resets its offsets and temperatures) with its extruders, "
     "heaters, fans and axis maps.",
     "m563-define-or-remove-a-tool", kM563},
};

constexpr auto key(const CommandDoc& d) { return std::tuple(d.letter, d.number, d.fraction); }

}  // namespace

std::span<const CommandDoc> command_docs() {
  static_assert(std::is_sorted(std::begin(kDocs), std::end(kDocs),
                               [](const CommandDoc& a, const CommandDoc& b) { return key(a) < key(b); }));
  return kDocs;
}

const CommandDoc* command_doc(char letter, int number, int fraction) {
  const auto want = std::tuple(letter, number, fraction);
  auto it = std::lower_bound(std::begin(kDocs), std::end(kDocs), want,
                             [](const CommandDoc& d, const auto& k) { return key(d) < k; });
  return it != std::end(kDocs) && key(*it) == want ? &*it : nullptr;
}

std::string command_doc_url(const CommandDoc& d) { return fmt::format("{}#{}", kGcodePage, d.anchor); }

std::string command_name(const CommandDoc& d) {
  return d.fraction < 0 ? fmt::format("{}{}", d.letter, d.number)
                        : fmt::format("{}{}.{}", d.letter, d.number, d.fraction);
}

}  // namespace rrflint
