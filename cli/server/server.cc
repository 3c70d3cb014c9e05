// `rrflint server`: the Language Server Protocol 3.17 over stdin and stdout, with the core library in-process.
//
// What it implements (and so advertises): the lifecycle (initialize, initialized, shutdown, exit), text sync
// (didOpen, full and incremental didChange, didSave, didClose), pushed diagnostics (with the Unnecessary and
// Deprecated tags of the rules that have one), code actions (quickfix: each finding's fix, and suppressing it on
// its line or in its file; source.fixAll.rrflint: every safe fix of a document), hover, completion and signature
// help on commands with the model at that point of the boot (features.h), the editor's settings
// (initializationOptions, workspace/didChangeConfiguration: options.h) and watched files (registered with
// client/registerCapability after `initialized` when the client can register them dynamically).
//
// The loop: messages are handled as they come; lints wait in the workspace (workspace.h) until the input has been
// quiet for the debounce (didChange) or at all (the other events), which poll() on stdin tells. A request that
// reads the machines' snapshots (every textDocument/ request) is queued while a lint waits, and answered once the
// input is quiet and the lint done, in order; `$/cancelRequest` for a queued request answers it with
// RequestCancelled, for any other id it is ignored. Unknown requests get MethodNotFound; unknown notifications are
// ignored; a broken message gets a ParseError response or a log line (stderr and window/logMessage), and the
// server reads on. Responses to the server's own requests are matched by id; an error response is logged.
#include <signal.h>

#include <cerrno>
#include <deque>
#include <iostream>
#include <optional>

#include "cli/cli.h"
#include "cli/server/features.h"
#include "cli/server/protocol.h"
#include "cli/server/text.h"
#include "cli/server/workspace.h"
#include "frontend/disk.h"
#include "frontend/platform.h"

namespace rrflint::server {
namespace {

constexpr int kLogError = 1, kLogWarning = 2;
constexpr const char* kWatchRequest = "rrflint/watch-files";  // the id of the registerCapability request

// What the server watches on disk: G-code files, the extensionless macros of a card's folders, the config file.
json watchers() {
  json w = json::array();
  for (const char* glob : {"**/*.g", "**/sys/**", "**/macros/**", "**/filaments/**", "**/.rrflint.toml"})
    w.push_back({{"globPattern", glob}});
  return w;
}

// Does the request read the machines' snapshots, so that it waits for the lints that wait?
bool reads_snapshot(const std::string& method) { return method.starts_with("textDocument/"); }

class Server {
 public:
  Server() : ws_([this](json m) { send(m); }, [this](int type, const std::string& msg) { log(type, msg); }) {}

  // Runs until exit or the end of the input; the exit code.
  int run() {
    MessageReader reader = MessageReader::of_fd(0);
    json msg;
    std::string problem;
    bool parse_error = false;
    for (;;) {
      if (!reader.buffered() && !wait_for_input()) {
        if (broken_) return 1;
        continue;
      }
      const MessageReader::Status st = reader.next(msg, problem, parse_error);
      if (st == MessageReader::Status::End) {
        if (!problem.empty()) log(kLogError, problem);
        return shutdown_ ? 0 : 1;
      }
      if (st == MessageReader::Status::Problem) {
        log(kLogError, problem);
        if (parse_error) send(error_response(nullptr, kParseError, problem));
        continue;
      }
      if (!problem.empty()) log(kLogWarning, problem);
      if (std::optional<int> code = handle(msg)) return *code;
      if (broken_) return 1;
    }
  }

 private:
  struct Queued {
    json id;
    std::string method;
    json params;
  };

  void send(const json& m) { broken_ = broken_ || !write_message(1, m); }

  // With work waiting (lints, queued requests): waits for input until the work is due. True when there is input
  // to read (or nothing waits); false when the work was done, or is not due yet, instead.
  bool wait_for_input() {
    int timeout = 0;
    if (queued_.empty()) {
      auto due = ws_.due();
      if (!due) return true;
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(*due - Workspace::Clock::now());
      timeout = static_cast<int>(std::max<int64_t>(left.count(), 0));
    }
    const int ready = wait_readable(0, timeout);
    if (ready < 0) return errno != EINTR;  // the wait failed: reading blocks instead
    if (ready > 0) return true;
    if (queued_.empty() && Workspace::Clock::now() < *ws_.due()) return false;
    answer_queued();
    return false;
  }

  // Lints what waits, then answers the queued requests in order.
  void answer_queued() {
    ws_.flush();
    for (Queued& q : std::exchange(queued_, {})) request(q.id, q.method, q.params);
  }

  void cancel(const json& id) {
    auto it = std::find_if(queued_.begin(), queued_.end(), [&](const Queued& q) { return q.id == id; });
    if (it == queued_.end()) return;  // answered already, or never asked: nothing to do
    send(error_response(id, kRequestCancelled, "cancelled"));
    queued_.erase(it);
  }

  // A response to the server's own request.
  void answered(const json& msg) {
    if (msg.at("id") != kWatchRequest) return;
    if (auto e = msg.find("error"); e != msg.end()) log(kLogWarning, "the client refused to watch files: " + e->dump());
  }

  // A line for stderr and, once initialize is answered (LSP allows nothing earlier), for the client's log.
  void log(int type, const std::string& msg) {
    std::cerr << "rrflint server: " << msg << std::endl;
    if (initialized_) send(notification("window/logMessage", {{"type", type}, {"message", msg}}));
  }

  // One message; the exit code when it was `exit`.
  std::optional<int> handle(const json& msg) {
    if (!msg.is_object()) {
      send(error_response(nullptr, kInvalidRequest, "a message must be a JSON object (batches are not supported)"));
      return std::nullopt;
    }
    auto method = msg.find("method");
    auto id = msg.find("id");
    if (method == msg.end()) {
      if (id == msg.end()) send(error_response(nullptr, kInvalidRequest, "a message without method or id"));
      else answered(msg);
      return std::nullopt;
    }
    const bool id_ok = id != msg.end() && (id->is_number_integer() || id->is_string());
    if (!method->is_string() || (id != msg.end() && !id_ok)) {
      send(error_response(id_ok ? *id : json(nullptr), kInvalidRequest,
                          "'method' must be a string and 'id' an integer or a string"));
      return std::nullopt;
    }
    static const json kNone = json::object();
    auto p = msg.find("params");
    // Not copied: didOpen and didChange carry whole files. `exit` and `shutdown` are often sent with null params.
    const json& params = p == msg.end() || p->is_null() ? kNone : *p;
    if (!params.is_object() && !params.is_array()) {
      if (id_ok) send(error_response(*id, kInvalidParams, "'params' must be an object or an array"));
      return std::nullopt;
    }
    const std::string name = method->get<std::string>();
    if (id_ok) {
      if (initialized_ && !shutdown_ && reads_snapshot(name) && (ws_.waiting() || !queued_.empty()))
        queued_.push_back({*id, name, params});
      else {
        if (name == "shutdown") answer_queued();
        request(*id, name, params);
      }
      return std::nullopt;
    }
    if (name == "exit") return shutdown_ ? 0 : 1;
    notify(name, params);
    return std::nullopt;
  }

  void request(const json& id, const std::string& method, const json& params) {
    try {
      if (shutdown_) return send(error_response(id, kInvalidRequest, "the server is shut down"));
      if (method == "initialize") {
        if (initialized_) return send(error_response(id, kInvalidRequest, "initialize was already sent"));
        initialized_ = true;
        caps_ = ClientCaps::of(params.is_object() ? params.value("capabilities", json::object()) : json::object());
        watch_ = params.value("/capabilities/workspace/didChangeWatchedFiles/dynamicRegistration"_json_pointer, false);
        send(response(id, initialize_result()));
        if (auto o = params.find("initializationOptions"); o != params.end() && !o->is_null()) configure(*o, true);
        return;
      }
      if (!initialized_) return send(error_response(id, kServerNotInitialized, "initialize first"));
      if (method == "shutdown") {
        shutdown_ = true;
        return send(response(id, nullptr));
      }
      if (method == "textDocument/codeAction") {
        static const json kNoContext = json::object();
        auto ctx = params.find("context");
        return send(response(id, ws_.code_actions(params.at("textDocument").at("uri").get<std::string>(),
                                                  params.at("range"), ctx == params.end() ? kNoContext : *ctx)));
      }
      if (method == "textDocument/hover") return send(response(id, hover(ws_, caps_, params)));
      if (method == "textDocument/completion") return send(response(id, completion(ws_, caps_, params)));
      if (method == "textDocument/signatureHelp") return send(response(id, signature_help(ws_, caps_, params)));
      send(error_response(id, kMethodNotFound, "unknown method: " + method));
    } catch (const json::exception& e) {
      send(error_response(id, kInvalidParams, std::string("bad params: ") + e.what()));
    } catch (const std::exception& e) {
      send(error_response(id, kInternalError, e.what()));
    }
  }

  static json initialize_result() {
    return {{"capabilities",
             {{"positionEncoding", "utf-16"},
              {"textDocumentSync",
               {{"openClose", true}, {"change", 2 /* incremental */}, {"save", {{"includeText", false}}}}},
              {"codeActionProvider", {{"codeActionKinds", json::array({"quickfix", "source.fixAll.rrflint"})}}},
              {"hoverProvider", true},
              {"completionProvider", {{"triggerCharacters", completion_triggers()}}},
              {"signatureHelpProvider", {{"triggerCharacters", signature_triggers()}}}}},
            {"serverInfo", {{"name", "rrflint"}, {"version", RRFLINT_VERSION}}}};
  }

  void notify(const std::string& method, const json& params) {
    // Before initialize, notifications are dropped (exit aside); after shutdown, nothing is linted any more.
    if (!initialized_ || shutdown_) return;
    try {
      if (method == "textDocument/didOpen") {
        const json& td = params.at("textDocument");
        ws_.open(td.at("uri").get<std::string>(), td.at("text").get<std::string>(), td.value("version", int64_t{0}));
      } else if (method == "textDocument/didChange") {
        const json& td = params.at("textDocument");
        ws_.change(td.at("uri").get<std::string>(), td.value("version", int64_t{0}), params.at("contentChanges"));
      } else if (method == "textDocument/didSave") {
        ws_.save(params.at("textDocument").at("uri").get<std::string>());
      } else if (method == "textDocument/didClose") {
        ws_.close(params.at("textDocument").at("uri").get<std::string>());
      } else if (method == "$/cancelRequest") {
        cancel(params.at("id"));
      } else if (method == "initialized") {
        if (watch_) send(watch_request());
      } else if (method == "workspace/didChangeConfiguration") {
        configure(params.at("settings"), false);
      } else if (method == "workspace/didChangeWatchedFiles") {
        files_changed(params.at("changes"));
      }
      // $/setTrace and the rest: nothing to do.
    } catch (const json::exception& e) {
      log(kLogError, method + ": bad params: " + e.what());
    } catch (const std::exception& e) {
      log(kLogError, method + ": " + e.what());
    }
  }

  static json watch_request() {
    json reg{{"id", "rrflint-watched-files"},
             {"method", "workspace/didChangeWatchedFiles"},
             {"registerOptions", {{"watchers", watchers()}}}};
    return {{"jsonrpc", "2.0"},
            {"id", kWatchRequest},
            {"method", "client/registerCapability"},
            {"params", {{"registrations", json::array({reg})}}}};
  }

  // The editor's settings: initializationOptions (`initial`), then each didChangeConfiguration, whose keys replace
  // those of initializationOptions (a key it does not name keeps its initial value). A bad value is shown and
  // changes nothing.
  void configure(const json& settings, bool initial) {
    json unwrapped = settings.is_object() && settings.contains("rrflint") ? settings.at("rrflint") : settings;
    json merged = initial ? json::object() : initial_settings_;
    if (unwrapped.is_object()) merged.update(unwrapped);
    else if (!unwrapped.is_null()) merged = unwrapped;  // not an object: read_options says so
    ServerOptions o;
    std::string err, warn;
    if (!read_options(merged, o, err, warn)) {
      const std::string why = "rrflint: settings not applied: " + err;
      log(kLogError, why);
      send(notification("window/showMessage", {{"type", kLogError}, {"message", why}}));
      return;
    }
    if (!warn.empty()) log(kLogWarning, "rrflint: " + warn);
    if (initial) initial_settings_ = merged;
    ws_.set_options(o);
  }

  void files_changed(const json& changes) {
    std::vector<std::string> paths;
    for (const json& c : changes)
      if (auto p = path_of_uri(c.at("uri").get<std::string>())) paths.push_back(absolute_normal(*p));
    ws_.files_changed(paths);
  }

  Workspace ws_;
  ClientCaps caps_;
  std::deque<Queued> queued_;  // requests waiting for a lint, in order
  json initial_settings_ = json::object();
  bool initialized_ = false, shutdown_ = false, broken_ = false;
  bool watch_ = false;  // the client registers didChangeWatchedFiles dynamically
};

}  // namespace
}  // namespace rrflint::server

namespace rrflint::cli {

int run_server() {
#ifdef SIGPIPE
  ::signal(SIGPIPE, SIG_IGN);  // a client gone: write() fails and the server stops, rather than being killed
#endif
  // Files are copied, never mapped: in a long-lived process a file cut short on disk while it is read (an editor
  // saving it) would raise SIGBUS and end the server (cli/main.cc turns mapping on for `check`).
  map_large_files(false);
  server::Server s;
  return s.run();
}

}  // namespace rrflint::cli
