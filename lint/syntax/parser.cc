// parse(): one file, on one thread or in parts, then blocks and the code index.

#include <algorithm>
#include <atomic>

#include "lint/base/huge_pages.h"
#include "lint/base/parallel.h"
#include "lint/base/trace.h"
#include "lint/syntax/parse_internal.h"

namespace rrflint {

ParsedFile parse(const SourceFile& file, const ParseOptions& opts) {
  static std::atomic<uint64_t> serials{0};
  ParsedFile pf;
  pf.serial = ++serials;
  pf.source = &file;
  pf.lines.source_ = &file;
  // NUL bytes add logical lines: insert() grows a set then.
  for (LineSet* set : pf.prefilters.line_sets()) set->resize(file.line_count() + 1);
  const bool any_nul = file.any_nul();
  const bool any_del = file.any_del();
  // Four parts per thread, so that a thread slowed down (another process, a part with longer lines) is made up
  // for by the others taking more parts.
  const size_t parts = any_nul || opts.threads < 2 || opts.part_bytes == 0
                           ? 1
                           : std::min<size_t>(size_t{4} * opts.threads, file.size() / opts.part_bytes);
  if (parts > 1) {
    LineParser::parse_in_parts(pf, opts, static_cast<unsigned>(parts), any_del);
  } else {
    // Exact for lines (plus NUL splits); a config has about one command per line. Reserved, untouched pages
    // cost no memory, and no vector is copied while it grows on large files.
    reserve_huge(pf.lines.recs_, file.line_count() + 1);
    reserve_huge(pf.commands.recs_, file.line_count() + 1);
    LineParser lp(pf, opts.cnc_mode, opts.laser_mode);
    lp.fast_lines = opts.fast_lines;
    lp.parse_lines(0, file.line_count(), any_nul, any_del);
  }
  // Only a file of some size is traced: a rule's fix check parses single lines, one per finding, and a trace line
  // (which reads the process's memory use) for each made RRFLINT_TRACE's times ten times the real ones.
  const bool traced = file.size() >= (size_t{1} << 16);
  if (traced) trace::mark("parse: lines");
  mark_written(pf);
  // Blocks (the lines) and the code index (the commands) touch different fields: a large file does both at once.
  run_tasks(2, parts > 1 ? 2u : 1u, [&](size_t k) {
    const trace::Scope time(!traced ? nullptr : k == 0 ? "blocks" : "code index");
    k == 0 ? compute_blocks(pf) : index_codes(pf);
  });
  for (const ParseError& e : pf.errors) pf.error_starts_.push_back(e.span.begin);
  for (const Span& s : pf.semicolon_cuts) pf.cut_starts_.push_back(s.begin);
  std::sort(pf.error_starts_.begin(), pf.error_starts_.end());
  std::sort(pf.cut_starts_.begin(), pf.cut_starts_.end());
  if (opts.no_prefilters) {  // every prefilter lets everything through (the contract on ParsedFile::Prefilters)
    ParsedFile::Prefilters& p = pf.prefilters;
    for (LineSet* set : p.line_sets()) set->fill(pf.lines.size());
    p.any_exponent = p.any_blank_before_colon = p.any_repeated_letter = true;
    p.any_line_number = p.any_tab_indent = true;
    p.off = true;
  }
  return pf;
}

std::vector<uint32_t> ParsedFile::Prefilters::commands_with(const CommandTable& table, CommandTable::Flag f) const {
  if (!off) return table.with_flag(f);
  std::vector<uint32_t> all(table.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<uint32_t>(i);
  return all;
}

}  // namespace rrflint
