// textDocument/hover (features.h): on a command word, what the command does (lint/boot/command_docs.h), its Duet
// page, and the model facts it touches at that point of the boot; on a rule named in a suppression comment, the
// rule's summary and docs link. Anything else: null.
#include <fmt/format.h>

#include "cli/server/features.h"
#include "cli/server/objects.h"
#include "lint/boot/commands.h"
#include "lint/engine/suppress.h"
#include "lint/render/render.h"
#include "rules/registry.h"

namespace rrflint::server {
namespace {

// What one object parameter of the command touches, as lines.
void object_facts(const DocAt& d, const MachineState& s, const Command& c, const ObjectParam& op, bool md,
                  std::vector<std::string>& out) {
  const ParsedFile& pf = d.parsed();
  const std::string_view kind = obj_kind_name(op.kind);
  std::vector<int64_t> numbers;
  if (c.letter == 'T') {
    if (!c.has_number || c.number_expr) return out.push_back("the tool is an expression: not known here");
    if (c.number < 0) return out.push_back("deselects the current tool");
    numbers.push_back(c.number);
  } else {
    const Val<std::vector<int64_t>> v = get_int_list(pf, c, op.param);
    if (v.unknown()) return out.push_back(fmt::format("{}: an expression, not known here", kind));
    if (!v.known()) return;
    numbers = v.value;
  }
  for (const int64_t n64 : numbers) {
    const int n = static_cast<int>(n64);
    const std::optional<std::string> desc = describe(d, s, op.kind, n, md);
    if (op.creates) {
      const bool reports = c.is('M', 563) ? !m563_defines(pf, c) : c.is('M', 308) && !pf.find(c, 'Y');
      if (reports)
        out.push_back(desc ? (c.is('M', 308) ? "configures " : "reports ") + *desc
                           : fmt::format("{} {} does not exist here", kind, n));
      else if (desc)
        out.push_back(fmt::format("re-creates {}{}", *desc,
                                  op.kind == ObjKind::Tool ? ": its offsets and temperatures are reset" : ""));
      else out.push_back(fmt::format("creates {} {}", kind, n));
      continue;
    }
    if (!desc) {
      out.push_back(objects_known(s, op.kind) ? fmt::format("{} {} does not exist here", kind, n)
                                              : fmt::format("{} {} is not known to exist here", kind, n));
      continue;
    }
    out.push_back(*desc);
    if (op.kind == ObjKind::Tool)
      for (std::string& l : tool_details(d, s, n, md)) out.push_back("  " + l);
  }
}

// The model facts of the command at the cursor: empty without a model (a file that does not run, a pending lint).
std::vector<std::string> facts(const DocAt& d, const Command& c, bool md) {
  const MachineState* s = d.state();
  if (!s) return {};
  std::vector<std::string> out;
  if (d.point_runs() == Runs::No) return {"never runs here: a tool-change macro of a tool that does not exist"};
  const std::vector<const ObjectParam*> params = object_params(d.parsed(), c);
  for (const ObjectParam* op : params) object_facts(d, *s, c, *op, md, out);
  for (std::string& l : drive_facts(d, *s, c, md)) out.push_back(std::move(l));
  if (params.empty() && c.is('G', 10) && is_tool_form(g10_form(d.parsed(), c, s, s->firmware))) {
    const ToolRef t = addressed_tool(d.parsed(), c, *s);  // no P: the current tool
    if (!t.known) out.push_back("the current tool is not known here");
    else if (t.none()) out.push_back("no tool is selected here");
    else if (auto desc = describe(d, *s, ObjKind::Tool, t.number, md)) {
      out.push_back("the current tool: " + *desc);
      for (std::string& l : tool_details(d, *s, t.number, md)) out.push_back("  " + l);
    }
  }
  if (out.empty()) return out;
  std::string head = "At this point of the boot";
  if (d.point_runs() == Runs::Maybe) head += " (inside an if/while: it may not run)";
  if (d.runs() > 1) head += fmt::format(" (the first of the {} runs of this file)", d.runs());
  out.insert(out.begin(), head + ":");
  return out;
}

json command_hover(const DocAt& d, const Command& c, bool md) {
  const CommandDoc* doc = doc_of(c);
  if (!doc) return nullptr;
  std::string text = fmt::format(fmt::runtime(md ? "**{}**: {}\n\n{}" : "{}: {}\n\n{}"), command_name(*doc), doc->title,
                                 doc_text(*doc, md));
  const std::vector<std::string> lines = facts(d, c, md);
  for (size_t i = 0; i < lines.size(); ++i) {
    if (i == 0) text += "\n\n" + lines[i];
    else if (lines[i].starts_with("  ")) text += (md ? "\n  - " : "\n    ") + lines[i].substr(2);
    else text += (md ? "\n- " : "\n  ") + lines[i];
  }
  return {{"contents", markup(md, std::move(text))}, {"range", d.range(c.word)}};
}

// A rule named in a suppression comment under the cursor.
json rule_hover(const DocAt& d, bool md) {
  for (const Directive& dir : parse_directives(d.parsed(), builtin_rules()))
    for (const SuppressionEntry& e : dir.entries) {
      if (!e.rule || d.offset() < e.span.begin || d.offset() >= e.span.end) continue;
      const RuleMeta& m = e.rule->meta;
      const std::string url = rule_url(d.docs_base(), m.name);
      std::string text =
          md ? fmt::format("**{}** `{}` ({})\n\n{}\n\n[rule documentation]({})", m.code, m.name,
                           severity_name(m.severity), m.summary, url)
             : fmt::format("{} {} ({})\n\n{}\n\n{}", m.code, m.name, severity_name(m.severity), m.summary, url);
      return {{"contents", markup(md, std::move(text))}, {"range", d.range(e.span)}};
    }
  return nullptr;
}

}  // namespace

std::unique_ptr<DocAt> doc_at(const Workspace& ws, const json& params) {
  const json& p = params.at("position");
  auto count = [&](const char* key) {  // a uinteger: nlohmann would take -1 as 2^32 - 1
    const json& v = p.at(key);
    if (!v.is_number_unsigned() || v.get<uint64_t>() > UINT32_MAX)
      throw json::type_error::create(302, fmt::format("position.{} must be a uinteger", key), &v);
    return v.get<uint32_t>();
  };
  return DocAt::make(ws, params.at("textDocument").at("uri").get<std::string>(),
                     Position{count("line"), count("character")});
}

const CommandDoc* doc_of(const Command& c) {
  if (c.letter != 'T') return c.number < 0 ? nullptr : command_doc(c.letter, c.number, c.fraction);
  for (const CommandDoc& d : command_docs())
    if (d.letter == 'T') return &d;
  return nullptr;
}

std::string doc_text(const CommandDoc& d, bool markdown) {
  return markdown
             ? fmt::format("{}\n\n[{} in the Duet documentation]({})", d.summary, command_name(d), command_doc_url(d))
             : fmt::format("{}\n\n{}", d.summary, command_doc_url(d));
}

json markup(bool markdown, std::string value) {
  return {{"kind", markdown ? "markdown" : "plaintext"}, {"value", std::move(value)}};
}

json hover(const Workspace& ws, const ClientCaps& caps, const json& params) {
  std::unique_ptr<DocAt> d = doc_at(ws, params);
  if (!d) return nullptr;
  if (d->in_comment()) return rule_hover(*d, caps.hover_markdown);
  const std::optional<uint32_t> ci = d->command();
  if (!ci) return nullptr;
  const Command c = d->parsed().commands[*ci];
  if (d->offset() < c.word.begin || d->offset() >= c.word.end) return nullptr;
  return command_hover(*d, c, caps.hover_markdown);
}

}  // namespace rrflint::server
