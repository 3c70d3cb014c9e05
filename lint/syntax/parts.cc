// A large file parsed in parts on several threads, and the parts joined.

#include "lint/base/huge_pages.h"
#include "lint/base/parallel.h"
#include "lint/syntax/byte_classes.h"
#include "lint/syntax/parse_internal.h"

namespace rrflint {

namespace {

// The machine mode a line sets, as the parse tracks it (LineParser::note_mode): none, FFF (M451), laser (M452) or
// CNC (M453).
enum class ModeLine : uint8_t { None, Fff, Laser, Cnc };

// Is t[p] the M of a mode command that starts its line (after blanks and a line number), such as `M453` or
// `N20 m452 ; laser`? Commands later in a line and mode words in comments are not seen: a guess, checked after the
// parse.
ModeLine mode_at(std::string_view t, size_t p) {
  if (p + 3 >= t.size() || (t[p] != 'M' && t[p] != 'm') || t[p + 1] != '4' || t[p + 2] != '5') return ModeLine::None;
  const char d = t[p + 3];
  if (d < '1' || d > '3') return ModeLine::None;
  if (p + 4 < t.size() && (is_digit(t[p + 4]) || t[p + 4] == '.')) return ModeLine::None;
  size_t q = p;
  while (q > 0 && is_blank(t[q - 1])) --q;
  if (q > 0 && is_digit(t[q - 1])) {  // a line number
    while (q > 0 && is_digit(t[q - 1])) --q;
    if (q == 0 || (t[q - 1] != 'N' && t[q - 1] != 'n')) return ModeLine::None;
    --q;
    while (q > 0 && is_blank(t[q - 1])) --q;
  }
  if (q > 0 && t[q - 1] != '\n' && t[q - 1] != '\r') return ModeLine::None;
  return d == '1' ? ModeLine::Fff : d == '2' ? ModeLine::Laser : ModeLine::Cnc;
}

// The mode set by the last mode line (mode_at) that starts in [b, e), searched from the end, 16 bytes at a time
// for "M45"/"m45".
ModeLine last_mode_line(std::string_view t, size_t b, size_t e) {
  const char* s = t.data();
  size_t i = e;
#if defined(__SSE2__)
  const __m128i m = _mm_set1_epi8('m'), four = _mm_set1_epi8('4'), five = _mm_set1_epi8('5'),
                lower = _mm_set1_epi8(0x20);
  while (i >= b + 16 && i + 2 <= t.size()) {  // the block [i - 16, i) and the two bytes after it
    const size_t k = i - 16;
    const __m128i v0 = _mm_or_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(s + k)), lower);
    const __m128i v1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + k + 1));
    const __m128i v2 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + k + 2));
    auto hits = static_cast<unsigned>(_mm_movemask_epi8(
        _mm_and_si128(_mm_cmpeq_epi8(v0, m), _mm_and_si128(_mm_cmpeq_epi8(v1, four), _mm_cmpeq_epi8(v2, five)))));
    while (hits) {
      const unsigned top = 31u - static_cast<unsigned>(__builtin_clz(hits));
      if (const ModeLine mode = mode_at(t, k + top); mode != ModeLine::None) return mode;
      hits &= ~(1u << top);
    }
    i = k;
  }
#endif
  while (i > b) {
    --i;
    if (const ModeLine mode = mode_at(t, i); mode != ModeLine::None) return mode;
  }
  return ModeLine::None;
}

}  // namespace

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
  // Each part starts in the mode of the last mode line before it. A part parsed in the wrong mode is parsed again
  // below, but a mode set once for a whole large file (a CNC job) would make that a chain of parts parsed one after
  // the other: so the modes are guessed first, from the mode lines (each part's last, searched backwards, in
  // parallel).
  {
    std::vector<ModeLine> last(parts, ModeLine::None);
    const std::string_view t = file.text();
    run_tasks(parts - 1, opts.threads, [&](size_t j) {
      last[j] = last_mode_line(t, file.line_span(first[j]).begin,
                               first[j + 1] < file.line_count() ? file.line_span(first[j + 1]).begin : file.size());
    });
    for (unsigned j = 1; j < parts; ++j) {
      ps[j].cnc_in = last[j - 1] == ModeLine::None ? ps[j - 1].cnc_in : last[j - 1] == ModeLine::Cnc;
      ps[j].laser_in = last[j - 1] == ModeLine::None ? ps[j - 1].laser_in : last[j - 1] == ModeLine::Laser;
    }
  }
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
    lp.sets_ = &pf.prefilters;
    lp.parse_lines(first[j], first[j + 1], false, any_del);
    p.cnc_out = lp.lex_.cnc;
    p.laser_out = lp.laser_;
  };
  run_tasks(parts, std::min(parts, opts.threads), run);
  // The parts whose guess was wrong, parsed again in the mode the part before them ends in, in rounds (a part
  // parsed again may end in another mode) until every part starts where the one before it ends: part k is right
  // after round k at the latest, as if the parts were parsed one after the other.
  for (;;) {
    std::vector<unsigned> again;
    for (unsigned j = 1; j < parts; ++j)
      if (ps[j].cnc_in != ps[j - 1].cnc_out || ps[j].laser_in != ps[j - 1].laser_out) again.push_back(j);
    if (again.empty()) break;
    for (unsigned j : again) {
      ps[j].cnc_in = ps[j - 1].cnc_out;
      ps[j].laser_in = ps[j - 1].laser_out;
      for (LineSet* set : pf.prefilters.line_sets()) set->clear(first[j], first[j + 1]);
    }
    run_tasks(again.size(), std::min<unsigned>(static_cast<unsigned>(again.size()), opts.threads),
              [&](size_t k) { run(again[k]); });
  }
  for (unsigned j = 1; j < parts; ++j) join_part(pf, std::move(ps[j].out), first[j], first[j + 1]);
}

}  // namespace rrflint
