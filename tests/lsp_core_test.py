#!/usr/bin/env python3
"""The protocol test of `rrflint server`'s loop and settings: debounce, cancellation, the editor's settings against
.rrflint.toml, watched files, source.fixAll, diagnostic tags and several machines at once.

  tests/lsp_core_test.py path/to/rrflint [test-name…]

Each test runs its own server on a fresh copy of tests/lsp/machine (its findings are listed in its config.g), with
the helpers of tests/lsp_test.py. Exit 0 when every test passes.
"""
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lsp_test  # noqa: E402
from lsp_test import Server, apply_edits, check, codes, frame, line_of, uri_of  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
MACHINE = os.path.join(HERE, "lsp", "machine")
ALL = ["RRF104", "RRF104", "RRF328", "RRF307", "RRF116", "RRF501"]


def init(s, options=None, caps=None, folders=None):
    params = {"processId": os.getpid(), "rootUri": None, "capabilities": caps or {}}
    if options is not None:
        params["initializationOptions"] = options
    if folders is not None:
        params["workspaceFolders"] = [{"uri": uri_of(f), "name": os.path.basename(f)} for f in folders]
    r = s.request("initialize", params)
    check("result" in r, f"initialize: {r}")
    s.notify("initialized", {})
    return r


def collect(s, pred, what):
    """Every message up to and including the first that `pred` accepts."""
    seen = []

    def take(m):
        seen.append(m)
        return pred(m)

    s.wait(take, what)
    return seen


def publishes(messages, uri):
    return [m["params"] for m in messages
            if m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri]


def sync(s):
    """A request the server answers once everything before it is handled and linted (a textDocument/ request waits
    for the lints that wait): the messages up to its answer."""
    s.next_id += 1
    msg_id = s.next_id
    s.send(action_request(msg_id, "file:///not/open.g"))
    return collect(s, lambda m: m.get("id") == msg_id and "method" not in m, "the answer to the sync request")


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def frame_all(msgs):
    return b"".join(frame(m) for m in msgs)


def config_of(card):
    return os.path.join(card, "sys", "config.g")


def apostrophe_change(text, version, uri):
    """A didChange that deletes the apostrophe of "it's" (fixing the first RRF104)."""
    n, line = line_of(text, "it's")
    at = line.index("'s")
    return {"jsonrpc": "2.0", "method": "textDocument/didChange",
            "params": {"textDocument": {"uri": uri, "version": version}, "contentChanges": [
                {"range": {"start": {"line": n, "character": at}, "end": {"line": n, "character": at + 1}},
                 "text": ""}]}}


def action_request(msg_id, uri, only=None, line=0):
    ctx = {"diagnostics": []}
    if only is not None:
        ctx["only"] = only
    return {"jsonrpc": "2.0", "id": msg_id, "method": "textDocument/codeAction",
            "params": {"textDocument": {"uri": uri}, "context": ctx,
                       "range": {"start": {"line": line, "character": 0}, "end": {"line": line, "character": 0}}}}


# ---- debounce ----

def test_debounce_only_latest_version(s, card):
    init(s, {"debounce": 400})
    config = config_of(card)
    text = s.open(config)
    check(codes(s.diagnostics(uri_of(config))) == ALL, "the findings at open")
    for v in range(2, 6):  # four changes in a row: only the last is linted, after the quiet time
        s.change(config, v, [{"text": text + f"; edit {v}\n"}])
    sent = time.monotonic()
    seen = collect(s, lambda m: m.get("method") == "textDocument/publishDiagnostics"
                   and m["params"]["uri"] == uri_of(config), "diagnostics after the changes")
    waited = time.monotonic() - sent
    check(waited >= 0.3, f"published {waited:.3f} s after the last change, before the 400 ms debounce")
    check([p["version"] for p in publishes(seen, uri_of(config))] == [5], f"versions published: {seen}")
    later = publishes(sync(s), uri_of(config))
    check(later == [], f"nothing more published: {later}")


def test_debounce_zero(s, card):
    init(s, {"debounce": 0})
    config = config_of(card)
    text = s.open(config)
    s.diagnostics(uri_of(config))
    s.send(apostrophe_change(text, 2, uri_of(config)))
    p = s.diagnostics(uri_of(config), "diagnostics after the change")
    check(p["version"] == 2 and codes(p) == ALL[1:], f"after the change: {p}")


def test_request_waits_for_fresh_lint(s, card):
    init(s, {"debounce": 8000})
    config = config_of(card)
    text = s.open(config)
    s.diagnostics(uri_of(config))
    n, _ = line_of(text, "it's")
    s.send(apostrophe_change(text, 2, uri_of(config)))
    start = time.monotonic()
    s.send(action_request(50, uri_of(config), ["quickfix"], n))
    seen = collect(s, lambda m: m.get("id") == 50, "the code action's answer")
    check(time.monotonic() - start < 5, "the request waited for the debounce instead of linting at once")
    pub = publishes(seen, uri_of(config))
    check(len(pub) == 1 and pub[0]["version"] == 2, f"the fresh lint is published before the answer: {pub}")
    titles = [a["title"] for a in seen[-1]["result"]]
    check("double the apostrophe" not in titles, f"the answer is for the new text: {titles}")


# ---- cancellation ----

def test_cancel_queued_request(s, card):
    init(s, {"debounce": 8000})
    config = config_of(card)
    text = s.open(config)
    s.diagnostics(uri_of(config))
    cancel = {"jsonrpc": "2.0", "method": "$/cancelRequest", "params": {"id": 7}}
    s.write(frame_all([apostrophe_change(text, 2, uri_of(config)), action_request(7, uri_of(config)), cancel,
                       action_request(8, uri_of(config))]))
    seen = collect(s, lambda m: m.get("id") == 8, "the answer to the request that was not cancelled")
    answers = {m["id"]: m for m in seen if "id" in m and "method" not in m}
    check(answers[7].get("error", {}).get("code") == -32800, f"the cancelled request: {answers.get(7)}")
    check("result" in answers[8], f"the other request: {answers[8]}")
    # Cancels for an answered id and an unknown one are ignored: no answer, and the server carries on.
    s.notify("$/cancelRequest", {"id": 8})
    s.notify("$/cancelRequest", {"id": "never sent"})
    extra = [m for m in sync(s) if "id" in m and m["id"] in (8, "never sent")]
    check(extra == [], f"answers to ignored cancels: {extra}")


# ---- settings ----

def test_initialization_options(s, card):
    init(s, {"ignore": ["RRF104", "duplicate-parameter"], "firmware": "3.5"})
    config = config_of(card)
    s.open(config)
    check(codes(s.diagnostics(uri_of(config))) == ["RRF307", "RRF501"], "ignore and firmware applied")


def test_did_change_configuration(s, card):
    init(s)
    config = config_of(card)
    s.open(config)
    check(codes(s.diagnostics(uri_of(config))) == ALL, "the defaults")
    s.notify("workspace/didChangeConfiguration", {"settings": {"rrflint": {"select": "RRF104,RRF116"}}})
    check(codes(s.diagnostics(uri_of(config), "after the settings")) == ["RRF104", "RRF104", "RRF116"],
          "select applied")
    s.notify("workspace/didChangeConfiguration", {"settings": {"select": None, "firmware": "3.2"}})
    check(codes(s.diagnostics(uri_of(config), "after the second settings")) == ["RRF104", "RRF104", "RRF328",
                                                                               "RRF116", "RRF501"],
          "the bare settings object, the select unset")


def test_bad_settings(s, card):
    init(s, {"ignore": ["RRF104"]})
    config = config_of(card)
    s.open(config)
    s.diagnostics(uri_of(config))
    for bad, word in (({"firmware": "banana"}, "firmware"), ({"select": ["RRF999"]}, "RRF999"),
                      ({"debounce": -1}, "debounce"), ({"ignore": 5}, "ignore"), ("not an object", "object")):
        s.notify("workspace/didChangeConfiguration", {"settings": {"rrflint": bad}})
        shown = s.wait(lambda m: m.get("method") == "window/showMessage", f"the message about {bad}")
        check(shown["params"]["type"] == 1 and word in shown["params"]["message"], f"message for {bad}: {shown}")
    check(publishes(sync(s), uri_of(config)) == [], "bad settings change nothing")
    s.notify("textDocument/didSave", {"textDocument": {"uri": uri_of(config)}})
    check(codes(s.diagnostics(uri_of(config), "after a save")) == ALL[2:], "the good settings still apply")
    r = s.request("initialize", {"processId": None, "capabilities": {}})
    check(r.get("error", {}).get("code") == -32600, "still serving")


def test_toml_wins(s, card):
    write(os.path.join(card, ".rrflint.toml"), 'select = ["RRF116", "RRF501"]\nfirmware = "3.2"\n')
    init(s, {"select": ["RRF104"], "firmware": "3.5"})
    config = config_of(card)
    s.open(config)
    check(codes(s.diagnostics(uri_of(config))) == ["RRF116", "RRF501"], "the config file's select wins")
    # The config file sets ignore but no select: the editor's select stays, the file's ignore applies to it; the
    # editor's firmware applies too.
    write(os.path.join(card, ".rrflint.toml"), 'ignore = ["RRF104"]\n')
    s.notify("workspace/didChangeConfiguration", {"settings": {"select": ["RRF104", "RRF307", "RRF328"],
                                                               "ignore": ["RRF307"]}})
    check(codes(s.diagnostics(uri_of(config), "after the settings")) == ["RRF307"],
          "the editor's select beneath the file's ignore (the editor's ignore replaced by the file's), at 3.5")


# ---- watched files ----

WATCH_CAPS = {"workspace": {"didChangeWatchedFiles": {"dynamicRegistration": True}}}


def test_watched_files(s, card):
    init(s, caps=WATCH_CAPS)
    reg = s.wait(lambda m: m.get("method") == "client/registerCapability", "the registration of watched files")
    r = reg["params"]["registrations"][0]
    globs = [w["globPattern"] for w in r["registerOptions"]["watchers"]]
    check(r["method"] == "workspace/didChangeWatchedFiles" and "**/*.g" in globs and "**/.rrflint.toml" in globs,
          f"the registration {reg}")
    s.send({"jsonrpc": "2.0", "id": reg["id"], "result": None})
    config = config_of(card)
    s.open(config)
    check("RRF501" in codes(s.diagnostics(uri_of(config))), "new.g missing")
    macro = os.path.join(card, "sys", "new.g")
    write(macro, "M117 \"hello\"\n")
    s.notify("workspace/didChangeWatchedFiles", {"changes": [{"uri": uri_of(macro), "type": 1}]})
    check("RRF501" not in codes(s.diagnostics(uri_of(config), "after new.g appeared")), "new.g found")
    os.remove(macro)
    s.notify("workspace/didChangeWatchedFiles", {"changes": [{"uri": uri_of(macro), "type": 3}]})
    check("RRF501" in codes(s.diagnostics(uri_of(config), "after new.g vanished")), "new.g missing again")
    toml = os.path.join(card, ".rrflint.toml")
    write(toml, 'ignore = ["RRF501"]\n')
    s.notify("workspace/didChangeWatchedFiles", {"changes": [{"uri": uri_of(toml), "type": 1}]})
    check("RRF501" not in codes(s.diagnostics(uri_of(config), "after .rrflint.toml appeared")), "toml applied")


def test_no_watch_without_capability(s, card):
    init(s, caps={"workspace": {"didChangeWatchedFiles": {"dynamicRegistration": False}}})
    asked = [m for m in sync(s) if m.get("method") == "client/registerCapability"]
    check(asked == [], f"a registration the client cannot take: {asked}")


def test_registration_refused(s, card):
    init(s, caps=WATCH_CAPS)
    reg = s.wait(lambda m: m.get("method") == "client/registerCapability", "the registration")
    s.send({"jsonrpc": "2.0", "id": reg["id"], "error": {"code": -32601, "message": "no thanks"}})
    logged = s.wait(lambda m: m.get("method") == "window/logMessage", "the log line about the refusal")
    check("no thanks" in logged["params"]["message"], f"log {logged}")
    s.send({"jsonrpc": "2.0", "id": "unknown", "result": 1})  # a response to nothing: ignored
    check("result" in s.request("shutdown"), "still serving")


# ---- fix all, tags ----

def test_fix_all(s, card):
    init(s, {"firmware": "3.5"})
    config = config_of(card)
    text = s.open(config)
    s.diagnostics(uri_of(config))
    r = s.request("textDocument/codeAction", action_request(0, uri_of(config), ["source.fixAll.rrflint"])["params"])
    check([a["kind"] for a in r["result"]] == ["source.fixAll.rrflint"], f"one fix-all action: {r}")
    fixed = apply_edits(text, r["result"][0]["edit"]["changes"][uri_of(config)])
    check("it''s" in fixed and "don''t" in fixed and "M568 P0 R0 S200" in fixed and "M92 X80 X81" in fixed,
          f"the fixed text:\n{fixed}")
    s.change(config, 2, [{"text": fixed}])
    p = s.diagnostics(uri_of(config), "after fixing all")
    check(codes(p) == ["RRF116", "RRF501"], f"what is left: {codes(p)}")
    again = s.request("textDocument/codeAction", action_request(0, uri_of(config), ["source"])["params"])
    check(again["result"] == [], f"no fix-all without a safe fix: {again}")


def test_fix_at_end_of_file(s, card):
    """An edit that ends after the file's last line ending ends at the start of the line after it: a character
    past the end of a line is taken back to the line's end, which would leave the last CR in place."""
    init(s, {"firmware": "3.5"})
    path = os.path.join(card, "macros", "cr-only.g")
    text = "M83\rG1 X10\rM400\r"
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8", newline="") as f:
        f.write(text)
    s.notify("textDocument/didOpen", {"textDocument": {"uri": uri_of(path), "languageId": "rrf-gcode",
                                                       "version": 1, "text": text}})
    p = s.diagnostics(uri_of(path))
    check("RRF107" in codes(p), f"the CR-only file is reported: {codes(p)}")
    r = s.request("textDocument/codeAction", action_request(0, uri_of(path), ["source.fixAll.rrflint"])["params"])
    edits = r["result"][0]["edit"]["changes"][uri_of(path)]
    check(edits[-1]["range"]["end"] == {"line": 3, "character": 0}, f"the edit ends at (3, 0): {edits}")
    fixed = apply_edits(text, edits)
    check(fixed == "M83\nG1 X10\nM400\n", f"every CR replaced: {fixed!r}")


def test_tags(s, card):
    init(s)
    config = config_of(card)
    p = (s.open(config), s.diagnostics(uri_of(config)))[1]
    tags = {d["code"]: d.get("tags") for d in p["diagnostics"]}
    check(tags == {"RRF104": None, "RRF328": [1], "RRF307": [2], "RRF116": [1], "RRF501": None}, f"tags {tags}")


# ---- several machines ----

def test_two_workspace_folders(s, card):
    a, b = os.path.join(card, "a"), os.path.join(card, "b")
    shutil.copytree(MACHINE, a)
    shutil.copytree(MACHINE, b)
    write(os.path.join(b, "sys", "new.g"), "M117 \"b\"\n")
    init(s, folders=[a, b])
    s.open(config_of(a))
    s.open(config_of(b))
    check(codes(s.diagnostics(uri_of(config_of(a)))) == ALL, "folder a")
    check(codes(s.diagnostics(uri_of(config_of(b)))) == ALL[:-1], "folder b has new.g")
    s.notify("textDocument/didClose", {"textDocument": {"uri": uri_of(config_of(a))}})
    check(codes(s.diagnostics(uri_of(config_of(a)), "a cleared")) == [], "a cleared")
    late = publishes(sync(s), uri_of(config_of(b)))
    check(late == [], f"closing a leaves b alone: {late}")


def test_two_cards_in_one_folder(s, card):
    one, two = os.path.join(card, "printers", "one"), os.path.join(card, "printers", "two")
    shutil.copytree(MACHINE, one)
    write(config_of(two), "M563 P0 S\"x\" D0\nG10 P0 X0 Y0 Z0\nM98 P\"new.g\"\n")
    write(os.path.join(two, "sys", "new.g"), "G10 P3 X0 Y0 Z0\n")
    init(s, folders=[os.path.join(card, "printers")])
    s.open(config_of(one))
    s.open(config_of(two))
    check(codes(s.diagnostics(uri_of(config_of(one)))) == ALL, "card one")
    check(codes(s.diagnostics(uri_of(os.path.join(two, "sys", "new.g")))) == ["RRF301"], "card two's macro")
    # An unsaved edit in card one does not touch card two.
    s.change(config_of(one), 2, [{"text": "M92 X1 X2\n"}])
    seen = collect(s, lambda m: m.get("method") == "textDocument/publishDiagnostics"
                   and m["params"]["uri"] == uri_of(config_of(one)), "card one after the edit")
    seen += sync(s)
    check(all("/printers/two/" not in m["params"]["uri"] for m in seen if m.get("method", "").endswith("Diagnostics")),
          "nothing published for card two")


def test_lone_macro_beside_cards(s, card):
    lone = os.path.join(card, "notes", "probe.g")
    write(lone, "M98 P\"elsewhere.g\"\nM92 X1 X2\n")
    init(s, folders=[card])
    s.open(lone)
    s.open(config_of(card))
    seen = sync(s)
    check([codes(p) for p in publishes(seen, uri_of(lone))] == [["RRF501", "RRF116"]],
          "the lone macro alone, as the CLI lints it")
    check([codes(p) for p in publishes(seen, uri_of(config_of(card)))] == [ALL], "the card beside it")


def test_graph_cut_at_node_limit(s, card):
    # new.g calls leaf.g 50 times: 500 commands, past the limit of 200 this test's server has (RRFLINT_MAX_NODES).
    write(os.path.join(card, "sys", "new.g"), 'M98 P"leaf.g"\n' * 50)
    write(os.path.join(card, "sys", "leaf.g"), "G4 P0\n" * 10)
    init(s)
    config = config_of(card)
    s.open(config)
    shown = s.wait(lambda m: m.get("method") == "window/showMessage", "the message about the node limit")
    check(shown["params"]["type"] == 2 and "more than 200 commands in all" in shown["params"]["message"],
          f"a warning: {shown}")
    s.notify("textDocument/didSave", {"textDocument": {"uri": uri_of(config)}})
    seen = sync(s)
    check(publishes(seen, uri_of(config)) != [], "linted again")
    check(not [m for m in seen if m.get("method") == "window/showMessage"], "said once, not at every lint")


test_graph_cut_at_node_limit.env = {"RRFLINT_MAX_NODES": "200"}

TESTS = [v for k, v in list(globals().items()) if k.startswith("test_")]


def main():
    return lsp_test.main(TESTS, MACHINE, __doc__, "lsp_core_test")


if __name__ == "__main__":
    sys.exit(main())
