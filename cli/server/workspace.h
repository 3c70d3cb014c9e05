// The language server's documents and machines: open buffers, which machine each belongs to, linting a machine
// with its open buffers over the disk, and publishing the diagnostics of every file of it.
//
// A document belongs to the machine `rrflint check FILE` would put it in (place_file: the nearest SD root or sys
// folder); a file outside any card, and a document that is no file (an "untitled:" buffer), is a lone machine of its
// own.
//
// Lints wait: an event marks its machine as waiting and sets when it is due (didChange: the debounce after the
// last change; didOpen, didSave, didClose, the settings and watched files: at once), and the server's loop calls
// flush() once the input has been quiet until then, or before it answers a request that reads a snapshot. A lint
// reads the current text of every open buffer and publishes with each document's current version, so a result
// for an older version of a document is never published.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "cli/cli.h"
#include "cli/server/options.h"
#include "cli/server/protocol.h"

namespace rrflint::server {

/// A FileReader that serves open buffers and falls back to another reader (the disk) for everything else.
class OverlayReader : public FileReader {
 public:
  explicit OverlayReader(FileReader& base) : base_(base) {}
  /// Serves `bytes` for `sd_path` (case-insensitive), shown as `display`.
  void add(const std::string& sd_path, std::string display, std::string bytes);
  ReadResult read(std::string_view sd_path) override;
  std::vector<std::string> list(std::string_view sd_dir) override;

 private:
  struct Buffer {
    std::string sd_path, display, bytes;
  };
  FileReader& base_;
  std::map<std::string, Buffer> buffers_;  // by lower-cased SD path
};

/// The last lint of a machine, kept whole for the requests about it (code actions): the result, the files it read
/// and the URI of each file. Not movable: the result refers to the sources and the reader.
struct Snapshot {
  explicit Snapshot(cli::Job j) : job(std::move(j)), disk(job), reader(disk) {}
  Snapshot(const Snapshot&) = delete;
  Snapshot& operator=(const Snapshot&) = delete;
  /// The URI of a file of the result, if it has one (a file excluded by the settings has none).
  std::optional<std::string> uri_of(FileId id) const;

  cli::Job job;
  cli::JobReader disk;
  OverlayReader reader;
  SourceManager sm;
  MachineResult result;
  std::map<FileId, std::optional<std::string>> uris;  // filled by the lint for every file with a finding or note
};

/// One finding as an LSP Diagnostic; notes in files with a URI become its related information.
json diagnostic_json(const SourceManager& sm, const Diagnostic& d, const std::string& docs_base,
                     const std::function<std::optional<std::string>(FileId)>& uri_of);

class Workspace {
 public:
  /// `send`: sends a notification to the client; `log`: a line for the client's log.
  Workspace(std::function<void(json)> send, std::function<void(int type, const std::string&)> log)
      : send_(std::move(send)), log_(std::move(log)) {}

  void open(const std::string& uri, std::string text, int64_t version);
  /// `changes`: the contentChanges of didChange (a full text, or a range and its replacement, in order).
  void change(const std::string& uri, int64_t version, const json& changes);
  void save(const std::string& uri);
  void close(const std::string& uri);
  bool is_open(const std::string& uri) const { return docs_.count(uri) > 0; }
  const std::string* text(const std::string& uri) const;
  /// The code actions for the findings of an open document that meet `range` (textDocument/codeAction), and
  /// source.fixAll.rrflint for all its safe fixes.
  json code_actions(const std::string& uri, const json& range, const json& context) const;
  /// What a request about a position in a document reads (hover, completion, signature help: model_at.h): its
  /// text (null when it is not open), its SD path ("" for a lone document), the last lint of its machine (null when
  /// there is none; not const: completion lists the card through its reader) and that lint's docs link base.
  struct View {
    const std::string* text = nullptr;
    std::string sd_path;
    Snapshot* snap = nullptr;
    std::string docs_base;
  };
  View view(const std::string& uri) const;  // defined in model_at.cc

  using Clock = std::chrono::steady_clock;
  /// The editor's settings: every machine is linted again.
  void set_options(const ServerOptions& o);
  const ServerOptions& options() const { return options_; }
  /// When the waiting lints are due; none when no machine waits.
  std::optional<Clock::time_point> due() const;
  bool waiting() const { return !waiting_.empty(); }
  /// Lints every machine that waits.
  void flush();
  /// workspace/didChangeWatchedFiles: files (absolute, normal) created, changed or deleted on disk. The machines
  /// they belong to are linted again (every machine for a `.rrflint.toml`), and open documents placed again.
  void files_changed(const std::vector<std::string>& paths);

 private:
  struct Document {
    std::string uri;
    std::optional<std::string> path;  // absolute, normal; none for a URI that names no file
    std::string text;
    int64_t version = 0;
    std::string machine;  // key into machines_
    std::string sd_path;  // in its card ("" for a lone machine)
  };
  struct MachineEntry {
    std::optional<CardLocation> card;  // none: a lone document
    std::string lone_uri;
    std::set<std::string> published;  // URIs last published with findings
    std::unique_ptr<Snapshot> last;   // the last lint (none after a configuration error)
    std::string docs_base;            // of the last lint
    bool truncated = false;           // the last lint's graph stopped at its node limit (and the user was told)
  };

  void place(Document& doc);    // finds the document's machine (and creates its entry)
  void replace(Document& doc);  // places it again (a card made or gone on disk), re-linting what it left
  void schedule(const std::string& key, bool now);  // the machine waits: due now, or after the debounce
  cli::Job job_of(const MachineEntry& m, const Document* lone) const;
  void lint(const std::string& key);
  void publish_all(const std::string& key, MachineEntry& m, std::map<std::string, json>& found);
  void publish(const std::string& uri, json diagnostics);
  void clear(const std::string& key);  // publishes no findings for every file of the machine, and forgets it

  std::function<void(json)> send_;
  std::function<void(int, const std::string&)> log_;
  std::string shown_;                             // the last configuration error shown to the user
  ServerOptions options_;                         // the editor's settings, beneath .rrflint.toml
  std::set<std::string> waiting_;                 // machines to lint
  Clock::time_point due_{};                       // when they are due
  std::map<std::string, Document> docs_;          // by URI as the client sent it
  std::map<std::string, MachineEntry> machines_;  // by key: the card's sys folder, or "lone:" + URI
};

}  // namespace rrflint::server
