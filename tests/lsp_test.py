#!/usr/bin/env python3
"""The protocol test of `rrflint server`: starts the server, speaks raw LSP over its pipes, checks what comes back.

  tests/lsp_test.py path/to/rrflint [test-name…]

Each test runs its own server on a fresh copy of tests/lsp/card (a card whose findings are listed in its config.g)
and has a deadline: a server that hangs fails the test, it does not block the run. Exit 0 when every test passes.
"""
import json
import os
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse

HERE = os.path.dirname(os.path.abspath(__file__))
CARD = os.path.join(HERE, "lsp", "card")
WAIT = 10.0  # seconds any one answer may take
TEST_DEADLINE = 60.0


class Failure(Exception):
    pass


def check(cond, what):
    if not cond:
        raise Failure(what)


def frame(obj):
    body = json.dumps(obj).encode()
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


def read_message(out):
    """The next message the server wrote to `out` (a binary stream), parsed; None at the end of it."""
    length = None
    while True:
        line = out.readline()
        if not line:
            return None
        line = line.strip()
        if not line:
            break
        name, _, value = line.partition(b":")
        if name.lower() == b"content-length":
            length = int(value)
    body = out.read(length)
    return None if len(body) < length else json.loads(body)


def uri_of(path):
    return "file://" + urllib.parse.quote(path)


def utf16(s):
    return len(s.encode("utf-16-le")) // 2


class Server:
    """One `rrflint server` process; a thread parses what it writes into a queue of messages."""

    def __init__(self, binary, env=None):
        self.proc = subprocess.Popen([binary, "server"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, env=dict(os.environ, **env) if env else None)
        self.messages = queue.Queue()
        self.next_id = 0
        self.stderr = []
        threading.Thread(target=self._read, daemon=True).start()
        threading.Thread(target=lambda: self.stderr.extend(self.proc.stderr), daemon=True).start()

    def _read(self):
        while True:
            m = read_message(self.proc.stdout)
            self.messages.put(m)
            if m is None:
                return

    def write(self, data):
        self.proc.stdin.write(data)
        self.proc.stdin.flush()

    def send(self, obj):
        self.write(frame(obj))

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request(self, method, params=None, msg_id=None):
        if msg_id is None:
            self.next_id += 1
            msg_id = self.next_id
        msg = {"jsonrpc": "2.0", "id": msg_id, "method": method}
        if params is not None:
            msg["params"] = params
        self.send(msg)
        return self.wait(lambda m: "method" not in m and m.get("id") == msg_id, f"the answer to {method}")

    def wait(self, pred, what):
        """The next message that `pred` accepts (others are dropped); fails after WAIT seconds or at EOF."""
        deadline = time.monotonic() + WAIT
        while True:
            left = deadline - time.monotonic()
            try:
                m = self.messages.get(timeout=max(left, 0.01))
            except queue.Empty:
                raise Failure(f"no {what} within {WAIT} s")
            if m is None:
                raise Failure(f"the server closed its output before {what}")
            if pred(m):
                return m

    def diagnostics(self, uri, what="diagnostics"):
        m = self.wait(lambda m: m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri,
                      f"{what} for {uri}")
        return m["params"]

    def initialize(self):
        r = self.request("initialize", {"processId": os.getpid(), "rootUri": None, "capabilities": {}})
        self.notify("initialized", {})
        return r

    def open(self, path, version=1):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        self.notify("textDocument/didOpen", {"textDocument": {"uri": uri_of(path), "languageId": "rrf-gcode",
                                                              "version": version, "text": text}})
        return text

    def change(self, path, version, changes):
        self.notify("textDocument/didChange", {"textDocument": {"uri": uri_of(path), "version": version},
                                               "contentChanges": changes})

    def finish(self, timeout=WAIT):
        try:
            return self.proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            raise Failure(f"the server did not exit within {timeout} s")

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def codes(params):
    return [d["code"] for d in params["diagnostics"]]


def line_of(text, needle):
    for n, line in enumerate(text.splitlines()):
        if needle in line:
            return n, line
    raise Failure(f"no line with {needle!r}")


# ---- the tests: each gets a server and the folder of a fresh copy of the card ----

def test_initialize(s, card):
    r = s.request("initialize", {"processId": None, "rootUri": None, "capabilities": {}})
    caps = r["result"]["capabilities"]
    check(caps == {"positionEncoding": "utf-16",
                   "textDocumentSync": {"openClose": True, "change": 2, "save": {"includeText": False}},
                   "codeActionProvider": {"codeActionKinds": ["quickfix", "source.fixAll.rrflint"]},
                   "hoverProvider": True,
                   "completionProvider": {"triggerCharacters": [" ", ".", "\"", "/"]},
                   "signatureHelpProvider": {"triggerCharacters": [" "]}},
          f"capabilities: {caps}")
    check(r["result"]["serverInfo"]["name"] == "rrflint", "serverInfo")
    again = s.request("initialize", {"processId": None, "rootUri": None, "capabilities": {}})
    check(again.get("error", {}).get("code") == -32600, f"a second initialize: {again}")


def test_before_initialize(s, card):
    r = s.request("shutdown")
    check(r.get("error", {}).get("code") == -32002, f"shutdown before initialize: {r}")
    s.initialize()
    check("result" in s.request("shutdown"), "shutdown after initialize")


def test_card_diagnostics(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    text = s.open(config)
    p = s.diagnostics(uri_of(config))
    check(p.get("version") == 1, f"version {p.get('version')}")
    check(codes(p) == ["RRF104", "RRF320", "RRF301"], f"codes {codes(p)}")
    n, line = line_of(text, "don't")
    d = p["diagnostics"][0]
    start = utf16(line[:line.index("'t")])
    check(d["range"] == {"start": {"line": n, "character": start}, "end": {"line": n, "character": start + 2}},
          f"RRF104 range {d['range']} (want line {n}, characters {start}-{start + 2})")
    check(d["severity"] == 2 and d["source"] == "rrflint", f"severity/source {d}")
    check(d["codeDescription"]["href"].endswith("/apostrophe-in-string.md"), f"href {d['codeDescription']}")
    rel = p["diagnostics"][1]["relatedInformation"]
    created = line[:line.index(" ;")]
    check(rel[0]["location"] == {"uri": uri_of(config), "range": {"start": {"line": n, "character": 0},
                                                                  "end": {"line": n, "character": utf16(created)}}},
          f"RRF320's first note {rel[0]}")
    check(rel[0]["message"] == "tool 0 is created here", f"note message {rel[0]['message']!r}")
    check(p["diagnostics"][2]["severity"] == 1, "RRF301 is an error")
    tpost = s.diagnostics(uri_of(os.path.join(card, "sys", "tpost0.g")))
    check(codes(tpost) == ["RRF301"] and "version" not in tpost, f"tpost0.g: {tpost}")


def test_incremental_fix(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    text = s.open(config)
    s.diagnostics(uri_of(config))
    n, line = line_of(text, "don't")
    at = utf16(line[:line.index("'t")])
    # Deletes the apostrophe: the range is in UTF-16 units, after an emoji (two units) and a 'ü' (one).
    s.change(config, 2, [{"range": {"start": {"line": n, "character": at}, "end": {"line": n, "character": at + 1}},
                          "text": ""}])
    p = s.diagnostics(uri_of(config), "diagnostics after the fix")
    check(p["version"] == 2, f"version {p['version']}")
    check(codes(p) == ["RRF320", "RRF301"], f"codes after the fix {codes(p)}")
    end = p["diagnostics"][0]["relatedInformation"][0]["location"]["range"]["end"]
    check(end == {"line": n, "character": utf16(line[:line.index(" ;")]) - 1}, f"the note's end after the edit {end}")
    # A full-text change brings the finding back.
    s.change(config, 3, [{"text": text}])
    p = s.diagnostics(uri_of(config), "diagnostics after a full change")
    check(p["version"] == 3 and codes(p) == ["RRF104", "RRF320", "RRF301"], f"after a full change {p}")


def test_macro_edit_changes_config(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    tools = os.path.join(card, "sys", "tools.g")
    s.open(config)
    check("RRF301" in codes(s.diagnostics(uri_of(config))), "RRF301 before the edit")
    s.open(tools)
    check(codes(s.diagnostics(uri_of(tools))) == [], "tools.g has no finding")
    s.change(tools, 2, [{"range": {"start": {"line": 1, "character": 0}, "end": {"line": 1, "character": 0}},
                         "text": 'M563 P1 S"two" D0 H1\n'}])
    p = s.diagnostics(uri_of(config), "config.g's diagnostics after the unsaved edit of tools.g")
    check(codes(p) == ["RRF104", "RRF320"] and p["version"] == 1, f"config.g after the edit: {p}")
    # Closing tools.g: config.g stays open in the machine, so it is linted with tools.g as on disk again.
    s.notify("textDocument/didClose", {"textDocument": {"uri": uri_of(tools)}})
    p = s.diagnostics(uri_of(config), "config.g's diagnostics after closing tools.g")
    check(codes(p) == ["RRF104", "RRF320", "RRF301"], f"config.g after closing tools.g: {p}")


def test_config_edit_updates_macro(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    tpost = uri_of(os.path.join(card, "sys", "tpost0.g"))
    text = s.open(config)
    check(codes(s.diagnostics(tpost)) == ["RRF301"], "tpost0.g before")
    end = len(text.splitlines())
    s.change(config, 2, [{"range": {"start": {"line": end, "character": 0}, "end": {"line": end, "character": 0}},
                          "text": 'M563 P2 S"three" D0 H1\n'}])
    check(codes(s.diagnostics(tpost, "tpost0.g after the edit of config.g")) == [], "tpost0.g's finding cleared")


def test_close_clears(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    tpost = uri_of(os.path.join(card, "sys", "tpost0.g"))
    s.open(config)
    s.diagnostics(tpost)
    s.notify("textDocument/didClose", {"textDocument": {"uri": uri_of(config)}})
    check(codes(s.diagnostics(uri_of(config), "config.g cleared")) == [], "config.g cleared on close")
    check(codes(s.diagnostics(tpost, "tpost0.g cleared")) == [], "tpost0.g cleared on close")


def test_lone_macro(s, card):
    s.initialize()
    lone = os.path.join(card, "lone.g")
    with open(lone, "w", encoding="utf-8") as f:
        f.write("M563 P0 S\"it's\" D0\n")
    s.open(lone)
    p = s.diagnostics(uri_of(lone))
    check(codes(p) == ["RRF104"], f"the lone macro: {p}")
    s.notify("textDocument/didSave", {"textDocument": {"uri": uri_of(lone)}})
    check(codes(s.diagnostics(uri_of(lone), "after didSave")) == ["RRF104"], "relinted on save")


def test_untitled_buffer(s, card):
    s.initialize()
    s.notify("textDocument/didOpen", {"textDocument": {"uri": "untitled:Untitled-1", "languageId": "rrf-gcode",
                                                       "version": 4, "text": "M563 P0 S\"it's\" D0\n"}})
    p = s.diagnostics("untitled:Untitled-1")
    check(codes(p) == ["RRF104"] and p["version"] == 4, f"an untitled buffer: {p}")


def test_rrflint_toml(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    with open(os.path.join(card, ".rrflint.toml"), "w", encoding="utf-8") as f:
        f.write('ignore = ["apostrophe-in-string"]\n')
    s.open(config)
    check(codes(s.diagnostics(uri_of(config))) == ["RRF320", "RRF301"], "the config file's ignore is applied")
    with open(os.path.join(card, ".rrflint.toml"), "w", encoding="utf-8") as f:
        f.write('ignore = ["apostrophe-in-string"\n')  # broken: the next lint says so and clears
    s.notify("textDocument/didSave", {"textDocument": {"uri": uri_of(config)}})
    shown = s.wait(lambda m: m.get("method") == "window/showMessage", "the message about the broken config file")
    check(shown["params"]["type"] == 1 and ".rrflint.toml" in shown["params"]["message"], f"message: {shown}")
    check(codes(s.diagnostics(uri_of(config), "config.g cleared")) == [], "cleared while the config is broken")


def test_method_not_found(s, card):
    s.initialize()
    r = s.request("textDocument/definition", {"textDocument": {"uri": "file:///x.g"}, "position": {"line": 0,
                                                                                              "character": 0}})
    check(r.get("error", {}).get("code") == -32601, f"definition: {r}")
    r = s.request("rrflint/unknown", {}, msg_id="a string id")
    check(r.get("error", {}).get("code") == -32601 and r["id"] == "a string id", f"string id: {r}")
    s.notify("rrflint/unknownNotification", {})
    s.notify("$/cancelRequest", {"id": 1})
    check("result" in s.request("shutdown"), "still answering after unknown notifications")


def test_malformed_headers(s, card):
    s.initialize()
    for junk in (b"Content-Length: abc\r\n\r\n", b"no colon here\r\n\r\n", b"Content-Length: 99999999999999\r\n\r\n",
                 b"Content-Length: -5\r\n\r\n", b"\xff\xfe binary \x00 junk\r\n\r\n", b"X" * 100000 + b"\r\n\r\n"):
        s.write(junk)
        r = s.request("rrflint/ping")
        check(r.get("error", {}).get("code") == -32601, f"after {junk[:30]!r}: {r}")


def test_invalid_json(s, card):
    s.initialize()
    for body in (b"{not json", b"[1, 2", b"\"\xff\""):
        s.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        e = s.wait(lambda m: "error" in m, f"the error for {body!r}")
        check(e["error"]["code"] == -32700 and e["id"] is None, f"parse error for {body!r}: {e}")
    s.send([1, 2])
    e = s.wait(lambda m: "error" in m, "the error for a batch")
    check(e["error"]["code"] == -32600, f"a batch: {e}")
    s.send({"jsonrpc": "2.0", "id": 1.5, "method": "shutdown"})
    e = s.wait(lambda m: "error" in m, "the error for a fractional id")
    check(e["error"]["code"] == -32600, f"a fractional id: {e}")
    # A body cut short by a Content-Length too small: the rest is garbage, the next message is still read.
    body = json.dumps({"jsonrpc": "2.0", "id": 99, "method": "x"}).encode()
    s.write(b"Content-Length: %d\r\n\r\n" % (len(body) - 3) + body)
    s.wait(lambda m: m.get("error", {}).get("code") == -32700, "the error for a short Content-Length")
    check("result" in s.request("shutdown"), "answers after broken messages")


def test_shutdown_exit(s, card):
    s.initialize()
    r = s.request("shutdown")
    check("result" in r and r["result"] is None, f"shutdown: {r}")
    r = s.request("initialize", {"processId": None, "rootUri": None, "capabilities": {}})
    check(r.get("error", {}).get("code") == -32600, f"a request after shutdown: {r}")
    s.notify("exit", None)
    check(s.finish() == 0, "exit code after shutdown")


def test_exit_without_shutdown(s, card):
    s.initialize()
    s.notify("exit", None)
    check(s.finish() == 1, "exit code without shutdown")


def test_eof_exits(s, card):
    s.initialize()
    s.proc.stdin.close()
    check(s.finish() == 1, "exit code at the end of the input")


def test_truncated_body_then_eof(s, card):
    s.initialize()
    s.write(b"Content-Length: 100\r\n\r\n{\"jsonrpc\"")
    s.proc.stdin.close()
    check(s.finish() == 1, "exit code at the end of the input inside a body")


def offset_of(text, pos):
    lines = text.splitlines(keepends=True)
    at = sum(len(x) for x in lines[:pos["line"]])
    line, units = (lines[pos["line"]] if pos["line"] < len(lines) else ""), 0
    for ch in line:
        if units >= pos["character"] or ch in "\r\n":
            break
        units += utf16(ch)
        at += 1
    return at


def apply_edits(text, edits):
    """`text` with LSP TextEdits applied (last first, so earlier offsets hold)."""
    spans = [(offset_of(text, e["range"]["start"]), offset_of(text, e["range"]["end"]), e["newText"]) for e in edits]
    for start, end, new in sorted(spans, key=lambda x: x[0], reverse=True):
        text = text[:start] + new + text[end:]
    return text


def code_action(s, path, title, line):
    r = s.request("textDocument/codeAction", {
        "textDocument": {"uri": uri_of(path)},
        "range": {"start": {"line": line, "character": 0}, "end": {"line": line, "character": 0}},
        "context": {"diagnostics": []}})
    actions = r["result"]
    found = [a for a in actions if a["title"] == title]
    check(len(found) == 1, f"one action {title!r} in {[a['title'] for a in actions]}")
    a = found[0]
    check(a["kind"] == "quickfix" and [d["code"] for d in a["diagnostics"]] == [title.split()[1]]
          if title.startswith("suppress") else a["kind"] == "quickfix", f"kind/diagnostics {a}")
    return a


def apply_action(s, path, text, a, version):
    edits = a["edit"]["changes"][uri_of(path)]
    fixed = apply_edits(text, edits)
    s.change(path, version, [{"text": fixed}])
    return fixed


def test_code_action_fix(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    text = s.open(config)
    s.diagnostics(uri_of(config))
    n, line = line_of(text, "don't")
    a = code_action(s, config, "double the apostrophe", n)
    check(a.get("isPreferred") is True and [d["code"] for d in a["diagnostics"]] == ["RRF104"], f"the fix {a}")
    at = utf16(line[:line.index("'t")])
    want = [{"range": {"start": {"line": n, "character": at}, "end": {"line": n, "character": at}}, "newText": "'"}]
    check(a["edit"]["changes"] == {uri_of(config): want}, f"the fix's edit {a['edit']}")
    for kind, want_kinds in (("source.fixAll", ["source.fixAll.rrflint"]), ("refactor", [])):
        only = s.request("textDocument/codeAction", {"textDocument": {"uri": uri_of(config)}, "range": a["diagnostics"][
            0]["range"], "context": {"diagnostics": [], "only": [kind]}})
        check([x["kind"] for x in only["result"]] == want_kinds, f"only {kind}: {only}")
    fixed = apply_action(s, config, text, a, 2)
    check("don''t" in fixed, "the apostrophe doubled")
    p = s.diagnostics(uri_of(config), "diagnostics after the code action")
    check(p["version"] == 2 and codes(p) == ["RRF320", "RRF301"], f"codes after the code action {codes(p)}")


def test_code_action_suppress(s, card):
    s.initialize()
    config = os.path.join(card, "sys", "config.g")
    text = s.open(config)
    s.diagnostics(uri_of(config))
    n, line = line_of(text, "G10 P1")
    a = code_action(s, config, "suppress RRF301 on this line", n)
    check(not a.get("isPreferred"), "a suppression is not preferred")
    edits = a["edit"]["changes"][uri_of(config)]
    check(len(edits) == 1 and edits[0]["newText"].startswith(" ; rrflint: disable=")
          and edits[0]["range"]["start"] == {"line": n, "character": utf16(line)}, f"the suppression's edit {edits}")
    fixed = apply_action(s, config, text, a, 2)
    check(fixed.splitlines()[n].startswith("G10 P1 X0 Y0 Z0 ; rrflint: disable="), f"line {fixed.splitlines()[n]!r}")
    p = s.diagnostics(uri_of(config), "diagnostics after the suppression")
    check(codes(p) == ["RRF104", "RRF320"], f"codes after suppressing on the line {codes(p)}")
    f = code_action(s, config, "suppress RRF104 in this file", n - 4)
    check(f["edit"]["changes"][uri_of(config)][0]["range"]["start"] == {"line": 0, "character": 0}, f"file-wide {f}")
    s.change(config, 3, [{"text": apply_edits(fixed, f["edit"]["changes"][uri_of(config)])}])
    check(codes(s.diagnostics(uri_of(config), "after the file-wide one")) == ["RRF320"], "RRF104 suppressed")


TESTS = [v for k, v in list(globals().items()) if k.startswith("test_")]


def run_one(binary, test, card_source=CARD):
    card = tempfile.mkdtemp(prefix="rrflint-lsp-")
    shutil.copytree(card_source, card, dirs_exist_ok=True)
    s = Server(binary, getattr(test, "env", None))  # a test may set environment variables for its server
    result = {}

    def body():
        try:
            test(s, card)
        except Failure as e:
            result["failure"] = str(e)
        except Exception as e:  # noqa: BLE001 (a broken test is a failure too)
            result["failure"] = f"{type(e).__name__}: {e}"

    t = threading.Thread(target=body, daemon=True)
    t.start()
    t.join(TEST_DEADLINE)
    if t.is_alive():
        result["failure"] = f"did not finish within {TEST_DEADLINE} s"
    s.kill()
    shutil.rmtree(card, ignore_errors=True)
    if "failure" in result and s.stderr:
        result["failure"] += "\n    server stderr: " + b"".join(s.stderr[-20:]).decode(errors="replace")
    return result.get("failure")


def main(tests=TESTS, card_source=CARD, doc=__doc__, title="lsp_test"):
    if len(sys.argv) < 2:
        print(doc)
        return 2
    binary, names = sys.argv[1], sys.argv[2:]
    failed = 0
    for test in tests:
        if names and test.__name__ not in names and test.__name__[5:] not in names:
            continue
        failure = run_one(binary, test, card_source)
        print(f"{'ok  ' if failure is None else 'FAIL'} {test.__name__}" + (f": {failure}" if failure else ""))
        failed += failure is not None
    print(f"{title}: {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
