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

/// Line `line` of `pf` parsed on its own twice, in the mode of `cnc`: as it is, and with the bytes of `edit` (inside
/// the line) replaced by `text`, as RRF would read the edited line. A fix's checks compare the two (edit_parses,
/// append_reads in rules/append_fix.h). Not ok() when the edit is not inside the line or the line is longer than
/// kMaxReparsedLine; then nothing is parsed. Neither copied nor moved: each parse points at its source.
class EditedLine {
 public:
  EditedLine(const ParsedFile& pf, uint32_t line, Span edit, std::string_view text, bool cnc)
      : ls_(pf.lines.span(line)),
        ok_(edit.begin >= ls_.begin && edit.end <= ls_.end && edit.begin <= edit.end &&
            ls_.end - ls_.begin <= kMaxReparsedLine),
        was_(0, "line.g", "/sys/line.g", TextBuffer(ok_ ? std::string(pf.source->slice(ls_)) : std::string())),
        now_(0, "line.g", "/sys/line.g", TextBuffer(ok_ ? edited(pf.source->slice(ls_), edit, text) : std::string())) {
    if (!ok_) return;
    before_ = parse(was_, ParseOptions{.cnc_mode = cnc});
    after_ = parse(now_, ParseOptions{.cnc_mode = cnc});
  }
  EditedLine(const EditedLine&) = delete;
  EditedLine& operator=(const EditedLine&) = delete;
  bool ok() const { return ok_; }
  /// Where the line starts in the file: offsets in the parses are from there.
  uint32_t line_begin() const { return ls_.begin; }
  const ParsedFile& before() const { return before_; }
  const ParsedFile& after() const { return after_; }

 private:
  std::string edited(std::string_view line, Span edit, std::string_view text) const {
    std::string s(line.substr(0, edit.begin - ls_.begin));
    s += text;
    s += line.substr(edit.end - ls_.begin);
    return s;
  }
  Span ls_;
  bool ok_;
  SourceFile was_, now_;
  ParsedFile before_, after_;
};

/// Does line `line` of `pf`, with the bytes of `edit` (inside the line) replaced by `text`, parse with no more
/// errors than it does now? The line is parsed on its own, in the mode of `cnc`. A fix that fails this would add
/// a syntax error (RRF100) and come back round after round: removing the blank in `M98 P "a.g ; note` opens a
/// string that the line never closes (found by fuzzing, fuzz_fix).
inline bool edit_parses(const ParsedFile& pf, uint32_t line, Span edit, std::string_view text, bool cnc) {
  const EditedLine e(pf, line, edit, text, cnc);
  return e.ok() && e.after().errors.size() <= e.before().errors.size();
}

}  // namespace rrflint::tools
