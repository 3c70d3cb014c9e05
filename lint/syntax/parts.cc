// A large file parsed in parts on several threads, and the parts joined.

#include "lint/base/huge_pages.h"
#include "lint/base/parallel.h"
#include "lint/syntax/parse_internal.h"

namespace rrflint {

// Appends `part` (lines [first, end) of the file, already in place in pf.lines) to `pf`: its line records are
// re-pointed at the joined command and meta-command tables.
void LineParser::join_part(ParsedFile& pf, ParsedFile&& part, uint32_t first, uint32_t end) {
  const auto cmd_base = static_cast<uint32_t>(pf.commands.size());
  const auto meta_base = static_cast<uint32_t>(pf.lines.metas_.size());
  for (uint32_t i = first; i < end; ++i) {
    detail::LineRec& r = pf.lines.recs_[i];
    const auto kind = static_cast<LineKind>(r.kind_meta & 7);
    if (kind == LineKind::Commands || kind == LineKind::Bad) r.first += cmd_base;
    else if (kind == LineKind::Meta) r.first += meta_base;
  }
  pf.lines.metas_.insert(pf.lines.metas_.end(), part.lines.metas_.begin(), part.lines.metas_.end());
  pf.lines.big_counts_.merge(part.lines.big_counts_);  // keyed by line: already the file's indices
  pf.lines.long_lines_.merge(part.lines.long_lines_);
  pf.commands.append(std::move(part.commands));
  pf.errors.insert(pf.errors.end(), std::make_move_iterator(part.errors.begin()),
                   std::make_move_iterator(part.errors.end()));
  pf.semicolon_cuts.insert(pf.semicolon_cuts.end(), part.semicolon_cuts.begin(), part.semicolon_cuts.end());
}

// A file without NUL bytes has one logical line per editor line, so each part writes its line records in place.
// A part's commands are counted from 0 until it is joined. A part starts in FFF mode (or the caller's mode, for
// the first); if the part before it ends in the other mode, it is parsed again once that is known.
void LineParser::parse_in_parts(ParsedFile& pf, const ParseOptions& opts, unsigned parts, bool any_del) {
  const SourceFile& file = *pf.source;
  std::vector<uint32_t> first(parts + 1, 0);
  first[parts] = file.line_count();
  for (unsigned j = 1; j < parts; ++j)
    first[j] = std::max(first[j - 1], file.line_of(static_cast<uint32_t>(uint64_t{file.size()} * j / parts)));
  reserve_huge(pf.lines.recs_, file.line_count());
  pf.lines.recs_.resize(file.line_count());  // not initialised (DefaultInit): each part writes its lines
  struct Part {
    ParsedFile out;
    bool cnc_in = false, cnc_out = false, laser_in = false, laser_out = false;
  };
  std::vector<Part> ps(parts);
  ps[0].cnc_in = opts.cnc_mode;
  ps[0].laser_in = opts.laser_mode;
  auto run = [&](size_t j) {
    Part& p = ps[j];
    ParsedFile& out = j == 0 ? pf : p.out;  // the first part goes straight into the result
    if (j > 0) {
      out = ParsedFile{};
      out.source = &file;
      out.lines.source_ = &file;
    }
    reserve_huge(out.commands.recs_, first[j + 1] - first[j] + 1);
    LineParser lp(out, p.cnc_in, p.laser_in, pf.lines.recs_.data(), first[j]);
    lp.fast_lines = opts.fast_lines;
    lp.rich_ = &pf.prefilters.rich_lines;
    lp.parens_ = &pf.prefilters.paren_lines;
    lp.apostrophes_ = &pf.prefilters.apostrophe_lines;
    lp.colon_comments_ = &pf.prefilters.colon_comment_lines;
    lp.parse_lines(first[j], first[j + 1], false, any_del);
    p.cnc_out = lp.lex_.cnc;
    p.laser_out = lp.laser_;
  };
  run_tasks(parts, std::min(parts, opts.threads), run);
  for (unsigned j = 1; j < parts; ++j) {
    if (ps[j].cnc_in != ps[j - 1].cnc_out || ps[j].laser_in != ps[j - 1].laser_out) {
      ps[j].cnc_in = ps[j - 1].cnc_out;
      ps[j].laser_in = ps[j - 1].laser_out;
      pf.prefilters.rich_lines.clear(first[j], first[j + 1]);
      for (LineSet* set :
           {&pf.prefilters.paren_lines, &pf.prefilters.apostrophe_lines, &pf.prefilters.colon_comment_lines})
        set->clear(first[j], first[j + 1]);
      run(j);
    }
  }
  for (unsigned j = 1; j < parts; ++j) join_part(pf, std::move(ps[j].out), first[j], first[j + 1]);
}

}  // namespace rrflint
