// What the requests about a position in a document read (hover, completion, signature help): the document's text
// as parsed now, the command or comment under the cursor, and the machine model at that point of the boot.
//
// The syntax always comes from the current text. The model comes from the machine's last lint, and only when that
// lint read exactly the current text of the document (a lint that is pending or failed gives no model facts, never
// facts for another text). "At that point of the boot" is the state before the node of the command: the forward
// pass (ModelBuilder, as lint/engine/linter.cc runs it) is replayed from the start of the node's segment, or from the
// end-of-boot state for an entry, up to that node. One replay per request: linear in the nodes before the point
// (a 10,000-line config.g replays in well under a millisecond; most of its commands change nothing and are skipped).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/server/text.h"
#include "cli/server/workspace.h"

namespace rrflint::server {

/// The client's capabilities that change how answers are written.
struct ClientCaps {
  bool hover_markdown = false;       // textDocument.hover.contentFormat holds "markdown"
  bool completion_markdown = false;  // textDocument.completion.completionItem.documentationFormat
  bool signature_markdown = false;   // textDocument.signatureHelp.signatureInformation.documentationFormat
  static ClientCaps of(const json& capabilities);
};

/// A document at a cursor position.
class DocAt {
 public:
  /// Null when the document is not open.
  static std::unique_ptr<DocAt> make(const Workspace& ws, const std::string& uri, Position pos);

  const SourceFile& file() const { return *file_; }
  const ParsedFile& parsed() const { return *parsed_; }
  uint32_t offset() const { return offset_; }  // the cursor, in bytes
  /// The logical line holding the cursor (an index into parsed().lines).
  uint32_t line() const { return line_; }
  /// The line's text from its start to the cursor.
  std::string_view before_cursor() const;
  /// The index of the command whose span holds the cursor (or ends right before it), if any.
  std::optional<uint32_t> command() const;
  /// Is the cursor inside the line's comment?
  bool in_comment() const;
  /// An LSP range for a span of the file.
  json range(Span s) const { return range_json(*file_, s); }
  /// The rules' docs link base of the machine's last lint.
  const std::string& docs_base() const { return view_.docs_base; }
  const Workspace::View& view() const { return view_; }

  /// The model: the last lint, when it read this text, and the unit of the document in it; null otherwise.
  const Snapshot* snapshot() const { return unit_ ? view_.snap : nullptr; }
  const FileUnit* unit() const { return unit_; }
  /// The node where the cursor stands in the file's first run (the command it is on, or the next one of the run,
  /// or the run's Leave), and how many runs the file has; kNoNode when the file does not run.
  NodeId point() const { return point_; }
  int runs() const { return runs_; }
  /// The state before point() (the replay); null without a model or a point.
  const MachineState* state() const;
  /// Does point() run? (No: a tool-change macro of a tool that does not exist; Maybe: inside an if/while.)
  Runs point_runs() const;
  /// Where a node's command is (its call site for other nodes), as "sys/config.g:12" by its SD path; as Markdown
  /// (`markdown`), a link to that line of the file when it is on disk. "default" for kNoNode (a power-on fact).
  std::string where(NodeId id, bool markdown) const;
  /// The `global` names declared before the cursor on its boot path, and the `var` names of the file in scope
  /// there, each with the line that declares it (sorted by name; a name declared twice is listed once).
  struct Name {
    std::string name, declared;
  };
  std::vector<Name> globals() const;
  std::vector<Name> vars() const;

 private:
  DocAt() = default;
  void locate();
  void replay() const;
  Workspace::View view_;
  std::unique_ptr<SourceManager> own_sm_;  // a fresh parse when the model is for another text
  std::optional<ParsedFile> own_parse_;
  const SourceFile* file_ = nullptr;
  const ParsedFile* parsed_ = nullptr;
  const FileUnit* unit_ = nullptr;
  uint32_t offset_ = 0, line_ = 0;
  NodeId point_ = kNoNode;
  int runs_ = 0;
  mutable std::optional<MachineState> state_;
  mutable Runs point_runs_ = Runs::Yes;
  mutable bool replayed_ = false;
};

/// The unit of the first file of a snapshot's machine that `is_it` accepts (by FileId), or null.
template <class Pred>
const FileUnit* find_unit(const Snapshot& s, Pred is_it) {
  if (!s.result.machine) return nullptr;
  for (uint32_t i = 0; i < s.result.machine->unit_count(); ++i)
    if (is_it(s.result.machine->unit(i).source->id())) return &s.result.machine->unit(i);
  return nullptr;
}
/// The unit of a file in a snapshot's machine, or null.
inline const FileUnit* unit_of(const Snapshot& s, FileId file) {
  return find_unit(s, [&](FileId f) { return f == file; });
}

}  // namespace rrflint::server
