// libFuzzer target: a whole language-server session at the level of its documents (cli/server/workspace.h) and
// requests (hover, completion, signature help, code actions), driven by arbitrary bytes: documents of a card are
// opened, edited by full texts and by ranges anywhere (past the end of a line or of the file, inside a UTF-16
// surrogate pair), saved, closed and linted, the settings change, and requests ask about any position. Everything
// the server would send must be JSON that prints (valid UTF-8), every published diagnostic's range must be in
// order, and every code action's edits must apply to the document they name. Byte 0 picks the client's
// capabilities; then each operation is one byte and its operands. Run it with scripts/fuzz.sh
// (tests/fuzz/RESULTS.md).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/server/features.h"
#include "cli/server/model_at.h"
#include "cli/server/workspace.h"

using namespace rrflint;
using namespace rrflint::server;

namespace {

// A broken invariant: says which, with the JSON at fault, and stops.
[[noreturn]] void fail(const char* why, const json& at) {
  std::fprintf(stderr, "fuzz_session: %s: %s\n", why, at.dump(-1, ' ', false, json::error_handler_t::replace).c_str());
  __builtin_trap();
}

// The card lies in a folder that does not exist: everything the documents do not hold is missing on disk.
const char* const kUris[] = {
    "file:///nonexistent-rrflint-fuzz/card/sys/config.g",
    "file:///nonexistent-rrflint-fuzz/card/sys/tpost0.g",
    "file:///nonexistent-rrflint-fuzz/card/macros/probe.g",
    "file:///nonexistent-rrflint-fuzz/lone.g",
    "untitled:Untitled-1",
};
constexpr size_t kDocs = sizeof kUris / sizeof *kUris;

struct Input {
  const uint8_t* p;
  const uint8_t* end;
  bool done() const { return p >= end; }
  uint8_t byte() { return p < end ? *p++ : 0; }
  // A text of up to 2 KiB as JSON would carry it: invalid UTF-8 replaced, as the client's JSON could not hold it.
  std::string text() {
    const size_t n = std::min<size_t>(static_cast<size_t>(byte()) * 8 + byte() % 8, static_cast<size_t>(end - p));
    std::string raw(reinterpret_cast<const char*>(p), n);
    p += n;
    return json::parse(json(raw).dump(-1, ' ', false, json::error_handler_t::replace)).get<std::string>();
  }
  // A position: mostly near the start, sometimes far past any end.
  json position() {
    // Unsigned, as the JSON parser reads a number without a sign.
    const uint8_t l = byte(), c = byte();
    return {{"line", uint64_t{l == 255 ? 100000u : l % 40u}}, {"character", uint64_t{c == 255 ? 100000u : c % 90u}}};
  }
  json range() {
    json a = position(), b = position();
    return {{"start", a}, {"end", byte() % 4 == 0 ? b : a}};
  }
};

// UTF-16 length of a UTF-8 line: what an LSP character offset counts.
size_t utf16_length(std::string_view s) {
  size_t n = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const auto b = static_cast<unsigned char>(s[i]);
    if ((b & 0xC0) != 0x80) n += b >= 0xF0 ? 2 : 1;
  }
  return n;
}

// Is the LSP range in order (start before end, nothing negative)?
bool in_order(const json& r) {
  const json& a = r.at("start");
  const json& b = r.at("end");
  const auto al = a.at("line").get<int64_t>(), ac = a.at("character").get<int64_t>();
  const auto bl = b.at("line").get<int64_t>(), bc = b.at("character").get<int64_t>();
  return al >= 0 && ac >= 0 && bl >= 0 && bc >= 0 && (al < bl || (al == bl && ac <= bc));
}

// Every message must print as JSON (dump throws on invalid UTF-8), and diagnostics' ranges, with those of their
// related information, must be in order.
void check_message(const json& m) {
  try {
    (void)m.dump();
  } catch (const json::type_error&) {
    fail("a message that is not valid UTF-8 (a text cut inside a character?)", m);
  }
  if (m.value("method", "") != "textDocument/publishDiagnostics") return;
  for (const json& d : m.at("params").at("diagnostics")) {
    if (!in_order(d.at("range"))) fail("a published range out of order", d);
    if (auto r = d.find("relatedInformation"); r != d.end())
      for (const json& n : *r)
        if (!in_order(n.at("location").at("range"))) fail("a related information's range out of order", d);
  }
}

// A hover's range, when it has one, is in order.
void check_hover(const json& h) {
  if (h.is_object())
    if (auto r = h.find("range"); r != h.end() && !in_order(*r)) fail("a hover's range out of order", h);
}

// A code action's edits name open documents and lie inside them (a line past the end is the end of the file).
void check_actions(const Workspace& ws, const json& actions) {
  (void)actions.dump();
  for (const json& a : actions) {
    auto e = a.find("edit");
    if (e == a.end()) continue;
    const json changes = e->value("changes", json::object());
    for (const auto& [uri, edits] : changes.items()) {
      const std::string* text = ws.text(uri);
      if (!text) fail("an edit of a document that is not open", a);
      // Lines as LSP counts them: ended by "\n", "\r\n" or a lone "\r".
      std::vector<std::string_view> lines;
      const std::string_view t = *text;
      size_t b = 0;
      for (size_t i = 0; i < t.size(); ++i)
        if (t[i] == '\n' || t[i] == '\r') {
          lines.push_back(t.substr(b, i - b));
          if (t[i] == '\r' && i + 1 < t.size() && t[i + 1] == '\n') ++i;
          b = i + 1;
        }
      lines.push_back(t.substr(b));
      for (const json& ed : edits) {
        const json& r = ed.at("range");
        if (!in_order(r)) fail("an edit's range out of order", json{{"edit", ed}, {"text", *text}});
        for (const char* end : {"start", "end"}) {
          const auto l = r.at(end).at("line").get<size_t>(), c = r.at(end).at("character").get<size_t>();
          if (l > lines.size() || (l < lines.size() && c > utf16_length(lines[l])))
            fail("an edit outside its document", json{{"edit", ed}, {"text", *text}});
        }
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  Input in{data + 1, data + size};
  const json caps_json = {
      {"textDocument",
       {{"hover", {{"contentFormat", data[0] & 1 ? json{"markdown"} : json{"plaintext"}}}},
        {"completion", {{"completionItem", {{"documentationFormat", data[0] & 2 ? json{"markdown"} : json::array()}}}}},
        {"signatureHelp",
         {{"signatureInformation", {{"documentationFormat", data[0] & 4 ? json{"markdown"} : json::array()}}}}}}}};
  const ClientCaps caps = ClientCaps::of(caps_json);
  Workspace ws([](json m) { check_message(m); }, [](int, const std::string&) {});
  int64_t version = 1;
  // A request the server answers with an error (bad params: json::exception) is no failure here either.
  auto request = [](auto&& answer) {
    try {
      answer();
    } catch (const json::exception&) {
    }
  };
  for (int ops = 0; !in.done() && ops < 64; ++ops) {
    const uint8_t op = in.byte();
    const std::string uri = kUris[in.byte() % kDocs];
    const json td = {{"uri", uri}};
    switch (op % 12) {
      case 0: ws.open(uri, in.text(), version++); break;
      case 1: ws.change(uri, version++, json::array({{{"text", in.text()}}})); break;
      case 2: {  // one to three range edits, in order
        json changes = json::array();
        for (int k = in.byte() % 3; k >= 0; --k) changes.push_back({{"range", in.range()}, {"text", in.text()}});
        ws.change(uri, version++, changes);
        break;
      }
      case 3: ws.flush(); break;
      case 4:
      case 5:
      case 6: {
        const json params = {{"textDocument", td}, {"position", in.position()}};
        request([&] {
          const json answer = op % 12 == 4   ? hover(ws, caps, params)
                              : op % 12 == 5 ? completion(ws, caps, params)
                                             : signature_help(ws, caps, params);
          (void)answer.dump();
          if (op % 12 == 4) check_hover(answer);
        });
        break;
      }
      case 7: {
        ws.flush();  // as the server answers a request that reads a snapshot: after the waiting lints
        const uint8_t k = in.byte();
        json context = {{"diagnostics", json::array()}};
        if (k & 1) context["only"] = json::array({k & 2 ? "source.fixAll.rrflint" : "quickfix"});
        const json range = in.range();
        request([&] { check_actions(ws, ws.code_actions(uri, range, context)); });
        break;
      }
      case 8: ws.close(uri); break;
      case 9: ws.save(uri); break;
      case 10: {  // the editor's settings
        static const char* const kFirmware[] = {"3.5", "3.4", "3.3", "3.0", "2.05", "auto"};
        const uint8_t k = in.byte();
        json s = {{"debounce", 0}, {"firmware", kFirmware[k % 6]}};
        if (k & 8) s["select"] = json::array({"RRF3"});
        if (k & 16) s["ignore"] = json::array({"RRF104", "line-too-long"});
        ServerOptions o;
        std::string err, warn;
        if (read_options(s, o, err, warn)) ws.set_options(o);
        break;
      }
      case 11: ws.files_changed({"/nonexistent-rrflint-fuzz/card/sys/config.g"}); break;
    }
  }
  ws.flush();
  return 0;
}
