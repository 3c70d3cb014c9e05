// Whether a fix's edit of one line leaves the line parsing as well as before it (the unquoted-string fixes).
#pragma once

#include <string>
#include <string_view>

#include "lint/base/source.h"
#include "lint/syntax/parser.h"

namespace rrflint::tools {

/// Does line `line` of `pf`, with the bytes of `edit` (inside the line) replaced by `text`, parse with no more
/// errors than it does now? The line is parsed on its own, in the mode of `cnc`. A fix that fails this would add
/// a syntax error (RRF100) and come back round after round: removing the blank in `M98 P "a.g ; note` opens a
/// string that the line never closes (found by fuzzing, fuzz_fix).
inline bool edit_parses(const ParsedFile& pf, uint32_t line, Span edit, std::string_view text, bool cnc) {
  const Span ls = pf.lines.span(line);
  if (edit.begin < ls.begin || edit.end > ls.end || edit.begin > edit.end) return false;
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
