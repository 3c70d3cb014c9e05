// What each command the model interprets does, in the project's own words: a one-line summary, its page in the
// public Duet G-code documentation, and its parameters. The language server's hover, completion and signature
// help read it (cli/server/); the rule docs may link to the same pages.
//
// Written for rrflint, not copied: the summaries say what the firmware does with the command as
// docs/firmware-behaviour.md describes it. A code that is not here gets no hover text rather than a guess.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace rrflint {

/// One parameter letter of a command and what it sets.
struct ParamDoc {
  char letter;
  std::string_view text;  // one short phrase: "tool number", "axis offsets (mm)"
};

struct CommandDoc {
  char letter;               // 'G', 'M' or 'T'
  int number;                // 10, 563, ...
  int fraction;              // -1: none (M563), else M569.1 -> 1
  std::string_view title;    // the short name: "Set tool offsets and temperatures"
  std::string_view summary;  // one line: what RRF does with it, as the model reads it
  std::string_view anchor;   // the anchor of its section on the Duet G-code page (kGcodePage + "#" + anchor)
  std::span<const ParamDoc> params;
};

/// The Duet G-code dictionary page; a command's link is kGcodePage + "#" + anchor.
inline constexpr std::string_view kGcodePage = "https://docs.duet3d.com/User_manual/Reference/Gcodes";

/// Every documented command, sorted by letter, number, fraction.
std::span<const CommandDoc> command_docs();
/// The documentation of one code, or nullptr when rrflint has none.
const CommandDoc* command_doc(char letter, int number, int fraction);
/// The public documentation link of a command.
std::string command_doc_url(const CommandDoc& d);
/// "M563", "M569.1".
std::string command_name(const CommandDoc& d);

}  // namespace rrflint
