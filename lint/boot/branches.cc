#include "lint/boot/branches.h"

#include <algorithm>

namespace rrflint {
namespace {

bool is_code(LineKind k) { return k == LineKind::Commands || k == LineKind::Meta || k == LineKind::Bad; }

// The first command on or after a line, for lines asked in increasing order (a chain's lines come in order): a
// gallop from the last answer, so the chains of a file cost about one pass over its commands, not a binary search
// of all of them for each line.
class FirstCommand {
 public:
  explicit FirstCommand(const ParsedFile& pf) : pf_(pf), n_(static_cast<uint32_t>(pf.commands.size())) {}
  uint32_t operator()(uint32_t line) {
    if (line < last_line_) at_ = 0;  // not in order: search from the start
    last_line_ = line;
    if (at_ >= n_ || line_of(at_) >= line) return at_;
    uint32_t below = at_, step = 1;  // line_of(below) < line
    while (below + step < n_ && line_of(below + step) < line) {
      below += step;
      step *= 2;
    }
    uint32_t lo = below + 1, hi = std::min(below + step, n_);  // the answer is in [lo, hi]
    while (lo < hi) {
      const uint32_t mid = lo + (hi - lo) / 2;
      if (line_of(mid) < line) lo = mid + 1;
      else hi = mid;
    }
    return at_ = lo;
  }

 private:
  uint32_t line_of(uint32_t i) const { return pf_.commands.code(i).line; }
  const ParsedFile& pf_;
  const uint32_t n_;
  uint32_t at_ = 0, last_line_ = 0;
};

// The body of the branch on line `head`: the lines after it indented deeper, up to the next code line that is not.
Branch body(const ParsedFile& pf, FirstCommand& first_command_from, uint32_t head, uint32_t* next) {
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
  b.commands.first = first_command_from(head + 1);
  b.commands.second = first_command_from(l);
  *next = l;
  return b;
}

}  // namespace

std::vector<Chain> top_level_chains(const ParsedFile& pf) {
  std::vector<Chain> out;
  const LineTable& lines = pf.lines;
  FirstCommand first_command_from(pf);
  for (uint32_t l = 0; l < lines.size();) {
    if (lines.kind(l) != LineKind::Meta || lines.in_block(l) || lines[l].meta != MetaKind::If || lines[l].indent != 0) {
      ++l;
      continue;
    }
    Chain chain;
    chain.first_command = first_command_from(l);
    uint32_t next = l;
    chain.branches.push_back(body(pf, first_command_from, l, &next));
    // elif/else at indent 0 continue the chain.
    while (next < lines.size() && lines.kind(next) == LineKind::Meta && lines[next].indent == 0 &&
           (lines[next].meta == MetaKind::Elif || lines[next].meta == MetaKind::Else)) {
      const uint32_t head = next;
      chain.branches.push_back(body(pf, first_command_from, head, &next));
    }
    out.push_back(std::move(chain));
    l = next;
  }
  return out;
}

}  // namespace rrflint
