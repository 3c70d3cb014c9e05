#include "lint/boot/branches.h"

#include <algorithm>

namespace rrflint {
namespace {

bool is_code(LineKind k) { return k == LineKind::Commands || k == LineKind::Meta || k == LineKind::Bad; }

// The first command on or after line `line`.
uint32_t first_command_from(const ParsedFile& pf, uint32_t line) {
  uint32_t lo = 0, hi = static_cast<uint32_t>(pf.commands.size());
  while (lo < hi) {
    const uint32_t mid = lo + (hi - lo) / 2;
    if (pf.commands.code(mid).line < line) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// The body of the branch on line `head`: the lines after it indented deeper, up to the next code line that is not.
Branch body(const ParsedFile& pf, uint32_t head, uint32_t* next) {
  const LineTable& lines = pf.lines;
  Branch b;
  b.kind = lines[head].meta;
  b.line = head;
  uint32_t l = head + 1, body_indent = 0;
  for (; l < lines.size(); ++l) {
    if (!is_code(lines.kind(l))) continue;
    const Line line = lines[l];
    if (line.indent == 0) break;
    if (!body_indent) body_indent = line.indent;
    if (line.kind == LineKind::Commands && line.indent == body_indent && line.command_count) {
      const uint32_t c = line.first_command, e = c + line.command_count;
      if (!b.direct.empty() && b.direct.back().second == c) b.direct.back().second = e;
      else b.direct.push_back({c, e});
    }
  }
  b.commands = {first_command_from(pf, head + 1), first_command_from(pf, l)};
  *next = l;
  return b;
}

}  // namespace

std::vector<Chain> top_level_chains(const ParsedFile& pf) {
  std::vector<Chain> out;
  const LineTable& lines = pf.lines;
  for (uint32_t l = 0; l < lines.size();) {
    if (lines.kind(l) != LineKind::Meta || lines.in_block(l) || lines[l].meta != MetaKind::If || lines[l].indent != 0) {
      ++l;
      continue;
    }
    Chain chain;
    chain.first_command = first_command_from(pf, l);
    uint32_t next = l;
    chain.branches.push_back(body(pf, l, &next));
    // elif/else at indent 0 continue the chain.
    while (next < lines.size() && lines.kind(next) == LineKind::Meta && lines[next].indent == 0 &&
           (lines[next].meta == MetaKind::Elif || lines[next].meta == MetaKind::Else)) {
      const uint32_t head = next;
      chain.branches.push_back(body(pf, head, &next));
    }
    out.push_back(std::move(chain));
    l = next;
  }
  return out;
}

}  // namespace rrflint
