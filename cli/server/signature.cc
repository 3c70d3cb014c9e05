// textDocument/signatureHelp (features.h): inside the parameters of a documented command, one signature: the
// command, its parameter letters and its title, each letter a parameter with its phrase; the active parameter is
// the one under the cursor (none after a blank).
#include <fmt/format.h>

#include "cli/server/features.h"
#include "cli/server/text.h"

namespace rrflint::server {

json signature_help(const Workspace& ws, const ClientCaps& caps, const json& params) {
  std::unique_ptr<DocAt> d = doc_at(ws, params);
  if (!d || d->in_comment() || d->parsed().lines.size() == 0) return nullptr;
  const ParsedFile& pf = d->parsed();
  const Line l = pf.lines[d->line()];
  std::optional<Command> cmd;  // the last command of the line whose word ends before the cursor
  for (uint32_t i = l.first_command; i < l.first_command + l.command_count; ++i)
    if (pf.commands[i].word.end < d->offset()) cmd = pf.commands[i];
  if (!cmd) return nullptr;
  const CommandDoc* doc = doc_of(*cmd);
  if (!doc) return nullptr;
  // "G10 P L X Y Z R S: Set tool offsets…": each parameter is a range of the label, in UTF-16 units.
  std::string label = command_name(*doc);
  json ps = json::array();
  const bool md = caps.signature_markdown;
  for (const ParamDoc& p : doc->params) {
    label += ' ';
    const uint32_t at = utf16_length(label);
    label += p.letter;
    ps.push_back({{"label", json::array({at, at + 1})}, {"documentation", std::string(p.text)}});
  }
  label += fmt::format(": {}", doc->title);
  json sig{{"label", label}, {"documentation", markup(md, doc_text(*doc, md))}, {"parameters", std::move(ps)}};
  json out{{"signatures", json::array()}, {"activeSignature", 0}};
  for (const Param& p : pf.params(*cmd))
    if (p.span.begin < d->offset() && d->offset() <= p.span.end)
      for (size_t i = 0; i < doc->params.size(); ++i)
        if (std::toupper(static_cast<unsigned char>(p.letter)) == doc->params[i].letter) {
          sig["activeParameter"] = i;
          out["activeParameter"] = i;
        }
  out["signatures"].push_back(std::move(sig));
  return out;
}

json signature_triggers() { return json::array({" "}); }

}  // namespace rrflint::server
