// What the fuzz targets share: how an input's first byte picks the lint options, the card format that packs the
// files of an SD card into one buffer, and the checks every lint must pass. A violated check ends the run with
// __builtin_trap(), which libFuzzer records as a crash (with the input that caused it).
//
// Card format (fuzz_card, fuzz_fix, fuzz_render): byte 0 picks the options (options_of); the rest is
// /sys/config.g, then any number of further files, each as the byte 0xFF, its SD path, a line feed, its bytes:
//
//   <sel> G28 \n M98 P"a.g" \n  0xFF /sys/a.g \n M98 P"b.g" \n  0xFF /sys/b.g \n M98 P"a.g"
//
// A path not starting with '/' is taken as relative to /sys ("tpost0.g", "config-override.g", "../macros/m.g"), so
// the fuzzer can build M98 graphs and cycles, config-override.g, tool-change macros and files outside /sys from
// the dictionary's words. A path is at most 64 bytes (longer: truncated) and at most 16 files are kept (the rest
// joins the last file). tests/fuzz/make_seeds.py writes fixtures and corpus cards in this format.
#pragma once

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lint/engine/linter.h"
#include "lint/render/render.h"
#include "rules/registry.h"
#include "tests/param_check.h"

namespace rrflint::fuzz {

inline constexpr Version kVersions[] = {Version(2, 5, 1), Version(3, 0, 0), Version(3, 2, 2), Version(3, 3, 0),
                                        Version(3, 4, 6), kRrf3_5_0_beta2,  Version(3, 5, 4), kLatestVersion};
inline constexpr Board kBoards[] = {Board::Unknown, Board::Duet2, Board::Duet3_6HC, Board::Duet3_Mini, Board::Maestro};

/// Every rule on; bit 7 fixes the firmware target (bits 0-2 choose it), else it is inferred from the text; bits
/// 3-5 the board; bit 6 the tool-changer setting.
inline LintOptions options_of(uint8_t sel) {
  LintOptions o;
  o.select = {"ALL"};
  if (sel & 0x80) o.firmware = kVersions[sel & 7];
  o.board = kBoards[(sel >> 3) % 5];
  o.tool_changer = sel & 0x40;
  return o;
}

using Files = std::vector<std::pair<std::string, std::string>>;  // SD path, bytes

inline constexpr size_t kMaxFiles = 16, kMaxPath = 64;

/// The files of a card-format buffer (without its option byte): config.g first.
inline Files split_card(std::string_view s) {
  Files files;
  std::string name = "/sys/config.g";
  for (;;) {
    size_t cut = files.size() + 1 < kMaxFiles ? s.find('\xff') : std::string_view::npos;
    files.emplace_back(name, std::string(s.substr(0, cut)));
    if (cut == std::string_view::npos) return files;
    s.remove_prefix(cut + 1);
    const size_t eol = s.find('\n');
    name = std::string(s.substr(0, std::min({eol, s.size(), kMaxPath})));
    if (name.empty() || name[0] != '/') name = "/sys/" + name;
    s.remove_prefix(eol == std::string_view::npos ? s.size() : eol + 1);
  }
}

/// A card-format input (with its option byte; size > 0), linted with the options it picks.
struct LintedCard {
  MemoryReader reader;
  LintOptions options;
  SourceManager sources;
  MachineResult result;
  LintedCard(const uint8_t* data, size_t size) {
    for (const auto& [path, bytes] : split_card(std::string_view(reinterpret_cast<const char*>(data + 1), size - 1)))
      reader.add(path, bytes);
    options = options_of(data[0]);
    result = lint_machine(sources, reader, builtin_rules(), options);
  }
};

/// The checks on every parse of a lint: parameters lexed twice agree, line spans lie inside the file, block
/// ranges agree with the lines, and the short path for simple lines records what the full lexer records.
inline void check_parses(const Machine& m) {
  for (uint32_t u = 0; u < m.unit_count(); ++u) {
    const ParsedFile& pf = m.unit(u).parsed;
    for (const Command& c : pf.commands)
      if (!test::param_mismatch(pf, c).empty()) __builtin_trap();
    for (const Line& l : pf.lines)
      if (l.code.end > l.span.end || l.comment.end > l.span.end || l.span.end > pf.source->size()) __builtin_trap();
    if (!test::block_commands_mismatch(pf).empty()) __builtin_trap();
    if (test::parse_dump(pf) != test::parse_dump(parse(*pf.source, ParseOptions{.fast_lines = false})))
      __builtin_trap();
  }
}

/// Every finding, note and edit lies inside a file of the lint (or names no file), with its span the right way round.
inline void check_locations(const SourceManager& sm, const std::vector<Diagnostic>& diags) {
  auto check = [&](const Location& l) {
    if (l.file == kNoFile) return;
    if (l.file >= sm.size() || l.span.begin > l.span.end || l.span.end > sm.get(l.file).size()) __builtin_trap();
  };
  for (const Diagnostic& d : diags) {
    check(d.loc);
    for (const Note& n : d.notes) check(n.loc);
    if (d.fix)
      for (const Edit& e : d.fix->edits) check(e.loc);
  }
}

/// Threads and prefilters change nothing: the same card linted with files parsed in parts of a few bytes, the file
/// rules beside the forward pass and every prefilter off reports the same findings, byte for byte.
inline void check_threads_agree(FileReader& reader, const LintOptions& o, const SourceManager& sources,
                                const MachineResult& r) {
  LintOptions split = o;
  split.threads = 3;
  split.part_bytes = 8;
  // And with every prefilter off (ParsedFile::Prefilters): a prefilter may only let more through, never change a
  // finding, so the two runs must still agree.
  split.no_prefilters = true;
  SourceManager split_sources;
  MachineResult sr = lint_machine(split_sources, reader, builtin_rules(), split);
  std::ostringstream a, b;
  RenderOptions ro;
  render_json(a, sources, r.diagnostics, ro);
  render_json(b, split_sources, sr.diagnostics, ro);
  if (a.str() != b.str()) __builtin_trap();
}

}  // namespace rrflint::fuzz
