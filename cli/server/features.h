// The language server's requests about a position in a document: hover (hover.cc), completion (completion.cc) and
// signature help (signature.cc). Each reads the document at the position and the model there (model_at.h); an
// answer the server cannot give rightly is null (hover), an empty list (completion) or null (signature help).
#pragma once

#include "cli/server/model_at.h"
#include "lint/boot/command_docs.h"

namespace rrflint::server {

/// The document and position of a TextDocumentPositionParams.
std::unique_ptr<DocAt> doc_at(const Workspace& ws, const json& params);

json hover(const Workspace& ws, const ClientCaps& caps, const json& params);
json completion(const Workspace& ws, const ClientCaps& caps, const json& params);
json signature_help(const Workspace& ws, const ClientCaps& caps, const json& params);
/// The characters after which the client asks for completion and signature help of its own accord.
json completion_triggers();
json signature_triggers();

/// The documentation of a command (for T: the table's T entry), or null.
const CommandDoc* doc_of(const Command& c);
/// A command's summary and its Duet documentation link, in the client's format.
std::string doc_text(const CommandDoc& d, bool markdown);
/// Text in the client's format: Markdown, or plain text.
json markup(bool markdown, std::string value);

}  // namespace rrflint::server
