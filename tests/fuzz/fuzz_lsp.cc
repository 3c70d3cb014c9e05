// libFuzzer target: the language server's message reader (cli/server/protocol.h), on arbitrary bytes as they would
// come from the client. Byte 0 picks how the bytes arrive: bits 0-3 the size of each read (2^(n-1) bytes for
// n = 1..15: 1 byte to 16 KiB; everything at once for 0), bit 4 whether the input ends with a read error rather than
// its end. The reader must read every message, problem and the end without a crash or a hang, each call taking at least
// one byte or ending; every message it returns is JSON that prints and parses back the same. Run it with
// scripts/fuzz.sh (tests/fuzz/RESULTS.md).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "cli/server/protocol.h"

using namespace rrflint::server;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const size_t step = (data[0] & 15) == 0 ? 0 : size_t{1} << ((data[0] & 15) - 1);
  const bool error_at_end = data[0] & 16;
  const char* bytes = reinterpret_cast<const char*>(data + 1);
  const size_t total = size - 1;
  size_t at = 0, calls_after_end = 0;
  MessageReader reader([&](char* buf, size_t n) -> long {
    if (at == total) {
      if (++calls_after_end > 1) __builtin_trap();  // the reader asks again after it was told the input ended
      return error_at_end ? -1 : 0;
    }
    const size_t k = std::min({n, total - at, step == 0 ? total : step});
    std::memcpy(buf, bytes + at, k);
    at += k;
    return static_cast<long>(k);
  });
  json msg;
  std::string problem;
  bool parse_error = false;
  // Each message or problem takes at least one byte of the input, so there are at most `total` of them.
  for (size_t calls = 0;; ++calls) {
    if (calls > total) __builtin_trap();
    const MessageReader::Status st = reader.next(msg, problem, parse_error);
    if (st == MessageReader::Status::End) break;
    if (st == MessageReader::Status::Problem && problem.empty()) __builtin_trap();  // a problem says what it is
    if (st == MessageReader::Status::Message && json::parse(msg.dump(), nullptr, false) != msg) __builtin_trap();
  }
  return 0;
}
