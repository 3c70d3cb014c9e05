// `rrflint server`: the Language Server Protocol 3.17 over stdin and stdout, with the core library in-process.
//
// What it implements (and so advertises): the lifecycle (initialize, initialized, shutdown, exit), text sync
// (didOpen, full and incremental didChange, didSave, didClose), pushed diagnostics and code actions (quickfix:
// each finding's fix, and suppressing it on its line or in its file). Every request is answered
// at once, in order, so `$/cancelRequest` has nothing to cancel and is accepted and ignored. Unknown requests get
// MethodNotFound; unknown notifications are ignored; a broken message gets a ParseError response or a log line
// (stderr and window/logMessage), and the server reads on.
#include <signal.h>

#include <iostream>
#include <optional>

#include "cli/cli.h"
#include "cli/server/protocol.h"
#include "cli/server/workspace.h"
#include "frontend/disk.h"

namespace rrflint::server {
namespace {

constexpr int kLogError = 1, kLogWarning = 2;

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
  void send(const json& m) { broken_ = broken_ || !write_message(1, m); }

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
      return std::nullopt;  // a response: the server sends no requests, so there is nothing to match it to
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
      request(*id, name, params);
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
        return send(response(id, initialize_result()));
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
              {"codeActionProvider", {{"codeActionKinds", json::array({"quickfix"})}}}}},
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
      }
      // initialized, $/cancelRequest (every request is already answered), $/setTrace and the rest: nothing to do.
    } catch (const json::exception& e) {
      log(kLogError, method + ": bad params: " + e.what());
    } catch (const std::exception& e) {
      log(kLogError, method + ": " + e.what());
    }
  }

  Workspace ws_;
  bool initialized_ = false, shutdown_ = false, broken_ = false;
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
