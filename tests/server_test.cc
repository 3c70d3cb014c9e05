// The language server's parts that need no process: the message reader on in-memory input, UTF-16 positions,
// incremental edits and file URIs (the protocol over real pipes: tests/lsp_test.py).
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/server/protocol.h"
#include "cli/server/text.h"
#include "lint/base/source.h"

using namespace rrflint::server;

namespace {

// A reader over `input`, handing out at most `chunk` bytes per read (messages split across reads).
MessageReader reader_of(const std::string& input, size_t chunk = 7) {
  auto pos = std::make_shared<size_t>(0);
  return MessageReader([input, pos, chunk](char* buf, size_t n) -> long {
    const size_t k = std::min({n, chunk, input.size() - *pos});
    input.copy(buf, k, *pos);
    *pos += k;
    return static_cast<long>(k);
  });
}

std::string framed(const std::string& body) {
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

// What the reader makes of `input`: "M:<method>" per message, "P" per problem ("J" for a JSON one), "E" at the end.
std::vector<std::string> read_all(const std::string& input) {
  MessageReader r = reader_of(input);
  std::vector<std::string> out;
  for (int i = 0; i < 100; ++i) {
    json msg;
    std::string problem;
    bool parse_error = false;
    const auto st = r.next(msg, problem, parse_error);
    if (st == MessageReader::Status::End) {
      out.push_back(problem.empty() ? "E" : "E!");
      return out;
    }
    if (st == MessageReader::Status::Problem) out.push_back(parse_error ? "J" : "P");
    else out.push_back("M:" + msg.value("method", std::string("?")));
  }
  out.push_back("no end");
  return out;
}

const std::string kPing = framed(R"({"jsonrpc":"2.0","id":1,"method":"ping"})");

}  // namespace

TEST_CASE("server: the reader reads framed messages split across reads, other headers ignored", "[server]") {
  const std::string two = kPing + "Content-Type: application/vscode-jsonrpc; charset=utf-8\r\n" + kPing;
  CHECK(read_all(two) == std::vector<std::string>{"M:ping", "M:ping", "E"});
  CHECK(read_all("") == std::vector<std::string>{"E"});
  CHECK(read_all("content-length:  40 \n\n" + std::string(R"({"jsonrpc":"2.0","id":1,"method":"ping"})")) ==
        std::vector<std::string>{"M:ping", "E"});
}

TEST_CASE("server: bad headers are problems and the next message is still read", "[server]") {
  for (const std::string& junk :
       std::vector<std::string>{"Content-Length: abc\r\n\r\n", "no colon\r\n\r\n", "Content-Length: -1\r\n\r\n",
                                "Content-Length: 99999999999999999\r\n\r\n", "Content-Length: 67108865\r\n\r\n",
                                ": empty name\r\n\r\n", std::string(20000, 'x') + "\r\n\r\n"}) {
    INFO(junk.substr(0, 40));
    CHECK(read_all(junk + kPing) == std::vector<std::string>{"P", "M:ping", "E"});
  }
}

TEST_CASE("server: a body that is not JSON is a parse error, a short length resyncs at the next header", "[server]") {
  CHECK(read_all(framed("{oops") + kPing) == std::vector<std::string>{"J", "M:ping", "E"});
  // Content-Length 3 bytes short: the body fails, its tail runs into the next header line, which starts afresh.
  const std::string body = R"({"jsonrpc":"2.0","id":1,"method":"a"})";
  const std::string short_len = "Content-Length: " + std::to_string(body.size() - 3) + "\r\n\r\n" + body;
  CHECK(read_all(short_len + kPing) == std::vector<std::string>{"J", "M:ping", "E"});
  CHECK(read_all("Content-Length: 50\r\n\r\n{\"a\"") == std::vector<std::string>{"E!"});
  CHECK(read_all("Content-Length: 5\r\n") == std::vector<std::string>{"E!"});
}

TEST_CASE("server: Content-Length values", "[server]") {
  size_t n = 0;
  CHECK((parse_length(" 42 ", n) && n == 42));
  CHECK((parse_length("67108864", n) && n == kMaxBody));
  CHECK_FALSE(parse_length("67108865", n));
  CHECK_FALSE(parse_length("", n));
  CHECK_FALSE(parse_length("4 2", n));
  CHECK_FALSE(parse_length("0x10", n));
}

TEST_CASE("server: UTF-16 lengths and offsets", "[server]") {
  const std::string line = "a\xC3\xBC\xF0\x9F\x98\x80z";  // a, ü (2 bytes, 1 unit), 😀 (4 bytes, 2 units), z
  CHECK(utf16_length(line) == 5);
  CHECK(utf16_length("\xFF\xC3") == 2);      // invalid bytes count one each
  CHECK(utf16_length("\xED\xA0\x80") == 3);  // an encoded surrogate is invalid UTF-8: three bytes, three units
  // Inside a character: its start, or rounded up (a range's end) the next one. A range cut inside the emoji
  // once came out backwards, (0, 3) to (0, 2) for a 3-byte cut, as the partial bytes counted one unit each.
  CHECK(utf16_before(line, 2, false) == 1);
  CHECK(utf16_before(line, 2, true) == 2);
  CHECK(utf16_before(line, 6, false) == 2);
  CHECK(utf16_before(line, 6, true) == 4);
  CHECK(utf16_before(line, 7, false) == 4);
  CHECK(utf16_before(line, 99, false) == 5);
  CHECK(offset_of(line, {0, 2}) == 3);
  CHECK(offset_of(line, {0, 3}) == 7);  // inside the surrogate pair: after the emoji
  CHECK(offset_of(line, {0, 4}) == 7);
  CHECK(offset_of(line, {0, 5}) == 8);
  CHECK(offset_of(line, {0, 99}) == 8);  // past the end of the line
  const std::string text = "ab\r\ncd\ref\ngh";
  CHECK(offset_of(text, {1, 1}) == 5);
  CHECK(offset_of(text, {2, 0}) == 7);
  CHECK(offset_of(text, {3, 2}) == 12);
  CHECK(offset_of(text, {0, 9}) == 2);  // not into the CRLF
  CHECK(offset_of(text, {9, 0}) == text.size());
}

TEST_CASE("server: a range that starts or ends inside a character covers it, in order", "[server]") {
  rrflint::SourceManager sm;
  const rrflint::SourceFile& f = sm.add("c.g", "/sys/c.g", "G1 ; \xE2\x82\xAC\xF0\x9F\x98\x80\r\nX");  // euro, emoji
  auto check = [&](uint32_t b, uint32_t e, uint32_t start, uint32_t end) {
    const json r = range_json(f, rrflint::Span{b, e});
    CHECK(r["start"]["character"] == start);
    CHECK(r["end"]["character"] == end);
    // The command line's columns, in code points, 1-based: in order too.
    CHECK(f.position(b).column <= f.position(e, true).column);
  };
  check(6, 7, 5, 6);    // both inside the euro sign: the sign
  check(7, 10, 5, 8);   // from inside the euro sign to inside the emoji
  check(5, 13, 5, 8);   // whole characters stay as they are
  check(12, 13, 8, 8);  // from the CR to between it and the LF: the line's end
  CHECK(f.position(7).column == 6);
  CHECK(f.position(7, true).column == 7);
}

TEST_CASE("server: the UTF-16 columns of many ranges on one line, in any order, are those counted from its start",
          "[server]") {
  // Each thread counts on from its last count on a line (a long line of many findings was walked per finding):
  // the memory must never leak into a count on another line, file or earlier offset.
  const std::string line = "G1 ; \xE2\x82\xAC \xF0\x9F\x98\x80 \xC3 x\xE2\x82 \xC3\xBC";
  rrflint::SourceManager sm;
  const rrflint::SourceFile& f = sm.add("c.g", "/sys/c.g", line + "\n\xC3\xBC\xE2\x82\xAC" + line + "\n");
  const rrflint::SourceFile& g = sm.add("d.g", "/sys/d.g", line + "\n");
  uint32_t seed = 7;
  for (int k = 0; k < 2000; ++k) {
    seed = seed * 1103515245u + 12345u;
    const rrflint::SourceFile& h = (seed >> 20) % 3 ? f : g;
    const auto off = static_cast<uint32_t>((seed >> 8) % h.size());
    const uint32_t line0 = h.line_of(off);
    const rrflint::Span ls = h.line_span(line0);
    if (off > ls.end) continue;
    const json r = range_json(h, rrflint::Span{off, off});
    CHECK(r["start"]["line"] == line0);
    CHECK(r["start"]["character"] == utf16_before(h.slice(ls), off - ls.begin, false));
    CHECK(r["end"]["character"] == utf16_before(h.slice(ls), off - ls.begin, true));
  }
}

TEST_CASE("server: incremental changes", "[server]") {
  std::string t = "M563 P0 S\"D\xC3\xBCse \xF0\x9F\x98\x80 don't\"\nG10\n";
  apply_change(t, {0, 21}, {0, 22}, "");  // the apostrophe, after ü and an emoji
  CHECK(t == "M563 P0 S\"D\xC3\xBCse \xF0\x9F\x98\x80 dont\"\nG10\n");
  apply_change(t, {1, 3}, {1, 3}, " P0");
  apply_change(t, {2, 0}, {2, 0}, "M98\n");
  CHECK(t == "M563 P0 S\"D\xC3\xBCse \xF0\x9F\x98\x80 dont\"\nG10 P0\nM98\n");
  apply_change(t, {1, 0}, {0, 0}, "x");  // an end before the start inserts at the start
  CHECK(t.starts_with("M563 P0 S\"D\xC3\xBCse \xF0\x9F\x98\x80 dont\"\nxG10"));
  apply_change(t, {0, 0}, {99, 0}, "all");
  CHECK(t == "all");
}

TEST_CASE("server: file URIs", "[server]") {
  CHECK(path_of_uri("file:///home/u/sys/config.g") == "/home/u/sys/config.g");
  CHECK(path_of_uri("file://localhost/a%20b/c%C3%BC.g") == "/a b/c\xC3\xBC.g");
  CHECK(path_of_uri("FILE:///x.g?query#frag") == "/x.g");
  CHECK_FALSE(path_of_uri("untitled:Untitled-1"));
  CHECK_FALSE(path_of_uri("file://server/share/x.g"));
  CHECK_FALSE(path_of_uri("file:///a%00b"));
  CHECK(uri_of_path("/a b/c\xC3\xBC.g") == "file:///a%20b/c%C3%BC.g");
  CHECK(path_of_uri(uri_of_path("/x/%25#?.g")) == "/x/%25#?.g");
}
