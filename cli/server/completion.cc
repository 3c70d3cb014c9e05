// textDocument/completion (features.h). What the text before the cursor on its line asks for:
//   a command word at the start of the line     the G/M codes of lint/boot/command_docs.h (T: the tools that exist)
//   a blank after a command's word or a value   its parameter letters not written yet
//   a letter that names a tool/heater/fan/sensor  the numbers that exist at that point of the boot (G10 P, M143 H…)
//   `global.` / `var.`                          the names in scope there (model_at.h)
//   inside `M98 P"`                             the macros of the card (graph.h's machine_files), relative to /sys
//                                               or from the root as typed
// Nothing in a comment, and nothing the text does not clearly ask for.
#include <fmt/format.h>

#include <regex>

#include "cli/server/features.h"
#include "cli/server/objects.h"

namespace rrflint::server {
namespace {

constexpr size_t kMaxLine = 2048;  // bytes before the cursor on its line

enum Kind : int { kFunction = 3, kField = 5, kVariable = 6, kValue = 12, kFile = 17 };

json item(std::string label, int kind, std::string detail) {
  return {{"label", std::move(label)}, {"kind", kind}, {"detail", std::move(detail)}};
}

// `it` replaces the cursor's last `typed` bytes with `text`.
void replace(const DocAt& d, json& it, size_t typed, const std::string& text) {
  it["textEdit"] = {{"range", d.range(Span{d.offset() - static_cast<uint32_t>(typed), d.offset()})}, {"newText", text}};
  it["filterText"] = text;
}

bool starts_with_ci(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && to_lower(s.substr(0, prefix.size())) == to_lower(prefix);
}

// The G and M codes documented, matching the typed prefix ("M5", "g1").
void codes(const DocAt& d, const ClientCaps& caps, std::string_view typed, json& out) {
  for (const CommandDoc& doc : command_docs()) {
    const std::string name = command_name(doc);
    if (doc.letter == 'T' || !starts_with_ci(name, typed)) continue;
    json it = item(name, kFunction, std::string(doc.title));
    it["documentation"] = markup(caps.completion_markdown, doc_text(doc, caps.completion_markdown));
    replace(d, it, typed.size(), name);
    out.push_back(std::move(it));
  }
}

// The objects of kind k at the cursor, as `<letter><n>` items that replace the `typed` bytes.
void objects(const DocAt& d, ObjKind k, char letter, size_t typed, json& out) {
  const MachineState* s = d.state();
  if (!s) return;
  for (int n : object_numbers(*s, k)) {
    const std::string text = fmt::format("{}{}", letter, n);
    json it = item(text, kValue, describe(d, *s, k, n, false).value_or(""));
    replace(d, it, typed, text);
    out.push_back(std::move(it));
  }
}

// The parameter letters of command c not written yet.
void letters(const DocAt& d, const Command& c, json& out) {
  const CommandDoc* doc = doc_of(c);
  if (!doc) return;
  std::string written;
  for (const Param& p : d.parsed().params(c)) written += p.letter;
  int order = 0;
  for (const ParamDoc& p : doc->params) {
    if (written.find(p.letter) != std::string::npos) continue;
    json it = item(std::string(1, p.letter), kField, std::string(p.text));
    it["sortText"] = fmt::format("{:02}", order++);
    out.push_back(std::move(it));
  }
}

void names(const DocAt& d, bool global, size_t typed, json& out) {
  for (const DocAt::Name& n : global ? d.globals() : d.vars()) {
    json it = item(n.name, kVariable, fmt::format("{}, declared at {}", global ? "global" : "var", n.declared));
    replace(d, it, typed, n.name);
    out.push_back(std::move(it));
  }
}

// The card's macros for `M98 P"<typed>`: from the root when the typed text starts with `/` or `0:/`, else relative
// to /sys.
void macro_paths(const DocAt& d, const std::string& typed, json& out) {
  Snapshot* snap = d.view().snap;
  if (!snap || !snap->result.machine) return;
  const bool rooted = typed.starts_with("/") || starts_with_ci(typed, "0:/");
  const std::string volume = rooted && typed.starts_with("0") ? typed.substr(0, 2) : "";
  for (const std::string& p : machine_files(snap->reader, "/sys")) {
    std::string text = volume + p;
    if (!rooted) {
      if (!starts_with_ci(p, "/sys/")) continue;
      text = p.substr(5);
    }
    if (!starts_with_ci(text, typed)) continue;
    json it = item(text, kFile, p);
    replace(d, it, typed.size(), text);
    out.push_back(std::move(it));
  }
}

// The last command of the cursor's line whose word ends before the cursor.
std::optional<Command> command_before(const DocAt& d) {
  const Line l = d.parsed().lines[d.line()];
  std::optional<Command> out;
  for (uint32_t i = l.first_command; i < l.first_command + l.command_count; ++i) {
    const Command c = d.parsed().commands[i];
    if (c.word.end < d.offset()) out = c;
  }
  return out;
}

void parameters(const DocAt& d, const Command& c, std::string_view before, json& out) {
  const uint32_t line_start = d.offset() - static_cast<uint32_t>(before.size());
  const std::string_view tail = before.substr(std::min<size_t>(before.size(), c.word.end - line_start));
  if (std::count(tail.begin(), tail.end(), '"') % 2 || tail.find('{') != std::string_view::npos) return;
  static const std::regex kLetterValue(R"(\s([A-Za-z])([0-9]*)$)");
  std::cmatch m;
  if (std::isblank(static_cast<unsigned char>(tail.empty() ? 'x' : tail.back()))) return letters(d, c, out);
  if (!std::regex_search(tail.data(), tail.data() + tail.size(), m, kLetterValue)) return;
  const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(m[1].str()[0])));
  if (const ObjectParam* op = object_param(d.parsed(), c, letter))
    objects(d, op->kind, letter, static_cast<size_t>(m[0].length() - 1), out);
}

}  // namespace

json completion(const Workspace& ws, const ClientCaps& caps, const json& params) {
  json items = json::array();
  std::unique_ptr<DocAt> d = doc_at(ws, params);
  if (!d || d->in_comment() || d->parsed().lines.size() == 0) return {{"isIncomplete", false}, {"items", items}};
  const std::string_view before = d->before_cursor();
  // std::regex recurses once per byte it matches: a line longer than any RRF accepts gets no completion rather
  // than a stack overflow.
  if (before.size() > kMaxLine) return {{"isIncomplete", false}, {"items", items}};
  const std::string b(before);
  static const std::regex kPath(R"(^\s*(N\d+\s*)?[Mm]0*98\b[^;]*\s[Pp]"([^"]*)$)");
  static const std::regex kName(R"((^|[^A-Za-z0-9_.])(global|var)\.([A-Za-z0-9_]*)$)");
  static const std::regex kWord(R"(^\s*(N\d+\s+)?([GgMmTt]\d*(\.\d*)?)?$)");
  std::smatch m;
  if (std::regex_search(b, m, kPath)) macro_paths(*d, m[2].str(), items);
  else if (std::regex_search(b, m, kName)) names(*d, m[2].str() == "global", m[3].length(), items);
  else if (std::regex_match(b, m, kWord)) {
    const std::string typed = m[2].str();
    if (!typed.empty() && std::toupper(static_cast<unsigned char>(typed[0])) == 'T') {
      if (typed.find('.') == std::string::npos) objects(*d, ObjKind::Tool, 'T', typed.size(), items);
    } else {
      codes(*d, caps, typed, items);
    }
  } else if (std::optional<Command> c = command_before(*d)) {
    parameters(*d, *c, before, items);
  }
  return {{"isIncomplete", false}, {"items", std::move(items)}};
}

json completion_triggers() { return json::array({" ", ".", "\"", "/"}); }

}  // namespace rrflint::server
