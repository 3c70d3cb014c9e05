// Whether a fix's edit of one line leaves the line parsing as well as before it (the unquoted-string fixes).
#pragma once

#include <string>
#include <string_view>

#include "lint/base/source.h"
#include "lint/syntax/parser.h"

namespace rrflint::tools {

/// The longest line a fix's check parses again (each check parses its whole line, so a line of many commands with
/// a finding each would cost the square of its length). RRF holds at most 255 characters of a line's code (from
/// 3.4, fewer before), so a fix on a longer line only matters when a long comment makes it long: such a line gets
/// no fix.
inline constexpr uint32_t kMaxReparsedLine = 4096;

/// Does line `line` of `pf`, with the bytes of `edit` (inside the line) replaced by `text`, parse with no more
/// errors than it does now? The line is parsed on its own, in the mode of `cnc`. A fix that fails this would add
/// a syntax error (RRF100) and come back round after round: removing the blank in `M98 P "a.g ; note` opens a
/// string that the line never closes (found by fuzzing, fuzz_fix).
inline bool edit_parses(const ParsedFile& pf, uint32_t line, Span edit, std::string_view text, bool cnc) {
  const Span ls = pf.lines.span(line);
  if (edit.begin < ls.begin || edit.end > ls.end || edit.begin > edit.end) return false;
  if (ls.end - ls.begin > kMaxReparsedLine) return false;
  const std::string_view before = pf.source->slice(ls);
  std::string after(before.substr(0, edit.begin - ls.begin));
  after += text;
  after += before.substr(edit.end - ls.begin);
  auto errors = [cnc](std::string bytes) {
    const SourceFile f(0, "line.g", "/sys/line.g", TextBuffer(std::move(bytes)));
    return parse(f, ParseOptions{.cnc_mode = cnc}).errors.size();
  };
  return errors(std::move(after)) <= errors(std::string(before));
}

}  // namespace rrflint::tools
