// libFuzzer target: the parser alone, on one file of arbitrary bytes. Byte 0 picks the parse options (bit 0 CNC
// mode, bit 1 laser mode); the rest is the file. Every parse must keep its records inside the file and agree with
// itself: parameters lexed while parsing and again on demand, block ranges and lines, the short path for simple
// lines and the full lexer, and a parse in parts of a few bytes on three threads and a parse on one.
// Run it with scripts/fuzz.sh (tests/fuzz/RESULTS.md).
#include <cstddef>
#include <cstdint>
#include <string>

#include "lint/syntax/parser.h"
#include "tests/param_check.h"

using namespace rrflint;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  ParseOptions po;
  po.cnc_mode = data[0] & 1;
  po.laser_mode = data[0] & 2;
  const SourceFile file(0, "config.g", "/sys/config.g", std::string(reinterpret_cast<const char*>(data + 1), size - 1));
  const ParsedFile pf = parse(file, po);
  for (const Line& l : pf.lines)
    if (l.code.end > l.span.end || l.comment.end > l.span.end || l.span.end > file.size()) __builtin_trap();
  for (const Command& c : pf.commands)
    if (c.span.end > file.size() || !test::param_mismatch(pf, c).empty()) __builtin_trap();
  if (!test::block_commands_mismatch(pf).empty()) __builtin_trap();
  const std::string dump = test::parse_dump(pf);

  ParseOptions slow = po;
  slow.fast_lines = false;
  if (test::parse_dump(parse(file, slow)) != dump) __builtin_trap();

  ParseOptions parts = po;
  parts.threads = 3;
  parts.part_bytes = 8;
  if (test::parse_dump(parse(file, parts)) != dump) __builtin_trap();
  return 0;
}
