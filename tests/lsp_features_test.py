#!/usr/bin/env python3
"""The protocol test of `rrflint server`'s hover, completion and signature help, on a fresh copy of
tests/lsp/features (a card with tools, a heater, a fan, a sensor, globals and vars), through tests/lsp_test.py's
harness.

  tests/lsp_features_test.py path/to/rrflint [test-name…]
"""
import os
import sys

from lsp_test import Server, check, line_of, main, uri_of, utf16  # noqa: F401 (Server: the harness's)

CARD = os.path.join(os.path.dirname(os.path.abspath(__file__)), "lsp", "features")
GCODES = "https://docs.duet3d.com/User_manual/Reference/Gcodes#"
MARKDOWN = {"textDocument": {"hover": {"contentFormat": ["markdown", "plaintext"]},
                             "completion": {"completionItem": {"documentationFormat": ["markdown"]}}}}


def start(s, card, path="sys/config.g", caps=None):
    """Initializes the server, opens a file of the card and waits for its diagnostics; its path and text."""
    s.request("initialize", {"processId": None, "rootUri": None, "capabilities": MARKDOWN if caps is None else caps})
    s.notify("initialized", {})
    path = os.path.join(card, path)
    text = s.open(path)
    s.diagnostics(uri_of(path))
    return path, text


def at(s, method, path, line, character):
    r = s.request(method, {"textDocument": {"uri": uri_of(path)}, "position": {"line": line, "character": character}})
    check("result" in r, f"{method}: {r}")
    return r["result"]


def rng(line, start, end):
    return {"start": {"line": line, "character": start}, "end": {"line": line, "character": end}}


def lines(first, end):
    """The range of lines [first, end)."""
    return {"start": {"line": first, "character": 0}, "end": {"line": end, "character": 0}}


def edit(s, path, version, changes):
    """Changes the document and waits for the lint of that version (the model answers are for the text linted)."""
    s.change(path, version, changes)
    s.wait(lambda m: m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri_of(path)
           and m["params"].get("version") == version, f"the lint of version {version}")


def insert(s, path, line, new_text, version=2):
    """Inserts `new_text` as a line before `line`, and waits for its lint."""
    edit(s, path, version, [{"range": rng(line, 0, 0), "text": new_text + "\n"}])


def labels(result):
    return [i["label"] for i in result["items"]]


def test_hover_g10(s, card):
    config, text = start(s, card)
    n, _ = line_of(text, "G10 P1 X-0.35")
    h = at(s, "textDocument/hover", config, n, 1)
    check(h["range"] == rng(n, 0, 3), f"the range of the code word {h['range']}")
    v = h["contents"]["value"]
    check(h["contents"]["kind"] == "markdown" and v.startswith("**G10**: "), f"markdown {h['contents']}")
    check(f"]({GCODES}g10-" in v, f"the Duet link in {v!r}")
    m, _ = line_of(text, 'M563 P1 S"Right"')
    created = f"[sys/config.g:{m + 1}]({uri_of(config)}#L{m + 1})"
    check(f'- tool 1 `"Right"` (created at {created})' in v, f"the tool and where it is created in {v!r}")
    check("  - axis map: X→U Y→Y Z→Z" in v and "  - offsets: X0 Y0 Z0 U0\n" not in v and v.endswith(
        "  - offsets: X0 Y0 Z0 U0"), f"the map and the offsets before the G10 in {v!r}")
    # The next G10 of tool 1 sees the offsets the first one set.
    n2, _ = line_of(text, "G10 P1 U0")
    v = at(s, "textDocument/hover", config, n2, 0)["contents"]["value"]
    check(f"offsets: X-0.35 Y0.2 Z0 U0 (last set at [sys/config.g:{n + 1}]" in v, f"the offsets after it in {v!r}")


def test_hover_plaintext(s, card):
    config, text = start(s, card, caps={})
    n, _ = line_of(text, "G10 P1 X-0.35")
    c = at(s, "textDocument/hover", config, n, 2)["contents"]
    check(c["kind"] == "plaintext" and c["value"].startswith("G10: ") and "**" not in c["value"]
          and "[" not in c["value"] and f"\n{GCODES}g10-" in c["value"], f"plain text {c}")
    m, _ = line_of(text, 'M563 P1 S"Right"')
    check(f'tool 1 "Right" (created at sys/config.g:{m + 1})' in c["value"], f"the tool in {c['value']!r}")


def test_hover_m563(s, card):
    config, text = start(s, card)
    first, _ = line_of(text, 'M563 P1 S"Right"')
    v = at(s, "textDocument/hover", config, first, 3)["contents"]["value"]
    check(v.startswith("**M563**: ") and "\n- creates tool 1\n- heater 1, sensor 1 (created at [sys/config.g:" in v
          and "\n- fan 0 (created at [sys/config.g:" in v, f"the first M563 P1, its heater and fan {v!r}")
    again, _ = line_of(text, 'M563 P1 S"Again"')
    v = at(s, "textDocument/hover", config, again, 0)["contents"]["value"]
    check(f'- re-creates tool 1 `"Right"` (created at [sys/config.g:{first + 1}]' in v
          and "): its offsets and temperatures are reset\n" in v, f"the second {v!r}")


def test_hover_devices(s, card):
    config, text = start(s, card, caps={})
    n, _ = line_of(text, 'M950 H1 C"e0heat" T1')
    sensor, _ = line_of(text, "M308 S1")
    v = at(s, "textDocument/hover", config, n, 0)["contents"]["value"]
    check(f"  creates heater 1\n  sensor 1 thermistor (created at sys/config.g:{sensor + 1})" in v, f"M950 {v!r}")
    end = len(text.splitlines())
    edit(s, config, 2, [{"text": text + "G10 P7 S200\nM569 P0.3 S1\nM584 X0 W5\nM143 H4 S1\nT1\n"}])
    v = at(s, "textDocument/hover", config, end, 0)["contents"]["value"]
    check(v.endswith("At this point of the boot:\n  tool 7 does not exist here"), f"a tool that does not exist {v!r}")
    axes, _ = line_of(text, "M584")
    again, _ = line_of(text, 'M563 P1 S"Again"')
    for k, want in ((1, "\n  driver 0.3: moves axis U"),
                    (2, f"\n  axis X exists: drivers 0 (set at sys/config.g:{axes + 1})\n  creates axis W"),
                    (3, "\n  heater 4 does not exist here"),
                    (4, f'\n  tool 1 "Again" (created at sys/config.g:{again + 1})\n    axis map: X→U Y→Y Z→Z')):
        h = at(s, "textDocument/hover", config, end + k, 0)
        check(h is not None and want in h["contents"]["value"], f"line {end + k}: {h} (want {want!r})")


def test_hover_none(s, card):
    config, text = start(s, card)
    check(at(s, "textDocument/hover", config, 0, 3) is None, "a comment line")
    n, line = line_of(text, "tool 1 again")
    check(at(s, "textDocument/hover", config, n, utf16(line[:line.index("again")])) is None, "a plain comment")
    n, _ = line_of(text, "M1234")
    check(at(s, "textDocument/hover", config, n, 1) is None, "an undocumented code")
    n, _ = line_of(text, "G10 P1 X-0.35")
    check(at(s, "textDocument/hover", config, n, 5) is None, "a parameter")
    check(at(s, "textDocument/hover", config, n, 3) is None, "the blank after the word")


def test_hover_rule(s, card):
    config, text = start(s, card)
    n, line = line_of(text, "disable=tool-redefined,RRF320")
    for word in ("RRF320", "tool-redefined"):
        start_at = utf16(line[:line.index(word)])  # after the emoji (two UTF-16 units) and the 'ü'
        h = at(s, "textDocument/hover", config, n, start_at + 1)
        check(h is not None and h["range"] == rng(n, start_at, start_at + len(word)), f"{word}'s range {h}")
        v = h["contents"]["value"]
        check(v.startswith("**RRF320** `tool-redefined` (warning)\n\n") and v.endswith("/tool-redefined.md)"),
              f"the rule's hover {v!r}")
    check(at(s, "textDocument/hover", config, n, utf16(line[:line.index("rrflint:")]) + 1) is None,
          "the directive's keyword")


def test_hover_entry_and_unrun(s, card):
    park, text = start(s, card, "macros/Park.g")
    n, _ = line_of(text, "G10 P1 Y0")
    v = at(s, "textDocument/hover", park, n, 0)["contents"]["value"]
    check('- tool 1 `"Again"`' in v and "offsets: X0 Y0 Z0 U0" in v, f"an entry starts from the end of boot: {v!r}")
    notes = os.path.join(card, "macros", "notes.txt")
    s.open(notes)
    s.diagnostics(uri_of(notes))
    v = at(s, "textDocument/hover", notes, 0, 0)["contents"]["value"]
    check(v.startswith("**G10**: ") and "At this point" not in v, f"a file that does not run: the summary only {v!r}")


def test_no_model(s, card):
    config, text = start(s, card)
    with open(os.path.join(card, ".rrflint.toml"), "w", encoding="utf-8") as f:
        f.write("select = [\n")  # broken: the card is not linted, so there is no model to answer from
    s.notify("textDocument/didSave", {"textDocument": {"uri": uri_of(config)}})
    s.wait(lambda m: m.get("method") == "window/showMessage", "the message about the broken config file")
    n, _ = line_of(text, "G10 P1 X-0.35")
    v = at(s, "textDocument/hover", config, n, 0)["contents"]["value"]
    check(v.startswith("**G10**: ") and "At this point" not in v, f"the summary alone {v!r}")
    check(labels(at(s, "textDocument/completion", config, n, len("G10 P"))) == [], "no tool numbers without a model")
    check("M563" in labels(at(s, "textDocument/completion", config, n, 0)), "the codes still")


def test_completion_codes(s, card):
    config, text = start(s, card)
    insert(s, config, 1, "")
    items = at(s, "textDocument/completion", config, 1, 0)["items"]
    by = {i["label"]: i for i in items}
    check("G10" in by and "M563" in by, f"the codes {list(by)}")
    g10 = by["G10"]
    check(g10["kind"] == 3 and g10["detail"]
          and g10["documentation"]["kind"] == "markdown" and GCODES in g10["documentation"]["value"], f"G10 {g10}")
    edit(s, config, 3, [{"range": rng(1, 0, 0), "text": "m5"}])
    got = {i["label"]: i for i in at(s, "textDocument/completion", config, 1, 2)["items"]}
    check("M563" in got and all(g.startswith("M5") for g in got), f"after 'm5': {list(got)}")
    check(got["M563"]["textEdit"] == {"range": rng(1, 0, 2), "newText": "M563"}, f"the edit {got['M563']}")


def test_completion_letters(s, card):
    config, text = start(s, card)
    n, line = line_of(text, "G10 P1 X-0.35")
    got = at(s, "textDocument/completion", config, n, len("G10 P1 "))
    got = labels(got)  # G10's letters from lint/boot/command_docs.h, but those written
    check("L" in got and not set(got) & set("PXYZ") and all(len(g) == 1 for g in got), f"letters not written {got}")
    check(at(s, "textDocument/completion", config, n, len("G10 P1 X-0"))["items"] == [], "inside a value")


def test_completion_tools(s, card):
    config, text = start(s, card)
    n, _ = line_of(text, 'M563 P1 S"Right"')
    insert(s, config, n, "G10 P")
    got = at(s, "textDocument/completion", config, n, 5)
    check(labels(got) == ["P0"], f"before tool 1's M563: {labels(got)}")
    check(got["items"][0]["textEdit"] == {"range": rng(n, 4, 5), "newText": "P0"} and "tool 0" in got["items"][0][
        "detail"], f"the item {got['items'][0]}")
    edit(s, config, 3, [{"range": lines(n, n + 1), "text": ""}])  # the line moves after the M563 P1
    insert(s, config, n + 1, "T", 4)
    check(labels(at(s, "textDocument/completion", config, n + 1, 1)) == ["T0", "T1"], "T after tool 1's M563")


def test_completion_devices(s, card):
    config, text = start(s, card)
    end = len(text.splitlines())
    for version, (typed, want) in enumerate((("M143 H", ["H1"]), ("M308 S", ["S1"]), ("M106 P", ["P0"]),
                                              ("M950 H2 C\"x\" T", ["T1"]), ("M106 X", [])), start=2):
        edit(s, config, version, [{"text": text + typed + "\n"}])
        got = labels(at(s, "textDocument/completion", config, end, len(typed)))
        check(got == want, f"after {typed!r}: {got} (want {want})")


def test_completion_utf16(s, card):
    config, text = start(s, card)
    n, line = line_of(text, "Düse 😀")
    at_f = utf16(line[:line.index(" F0 ") + 1])  # after the emoji (two UTF-16 units) and the 'ü'
    got = at(s, "textDocument/completion", config, n, at_f + 2)
    check(labels(got) == ["F0"] and got["items"][0]["textEdit"]["range"] == rng(n, at_f, at_f + 2),
          f"the fans of M563 F, replacing F0: {got}")


def test_completion_names(s, card):
    homeall, text = start(s, card, "sys/homeall.g")
    n, _ = line_of(text, "G1 X0")
    insert(s, homeall, n, "echo var.sp")
    got = at(s, "textDocument/completion", homeall, n, len("echo var.sp"))
    check(labels(got) == ["speed"], f"vars in scope {labels(got)} (inner's block has ended)")
    check(got["items"][0]["textEdit"] == {"range": rng(n, 9, 11), "newText": "speed"}, f"{got['items'][0]}")
    edit(s, homeall, 3, [{"range": rng(n, 5, 11), "text": "global."}])
    check(labels(at(s, "textDocument/completion", homeall, n, 12)) == ["bedTemp", "toolsReady"],
          "globals of the boot, not the one declared below")
    config = os.path.join(card, "sys", "config.g")
    ctext = s.open(config)
    m, _ = line_of(ctext, 'M98 P"tools.g"')
    insert(s, config, m, "if global.", 2)
    check(labels(at(s, "textDocument/completion", config, m, 10)) == ["bedTemp"], "before tools.g runs")
    edit(s, config, 3, [{"range": lines(m, m + 1), "text": ""}])
    insert(s, config, m + 1, "if global.", 4)
    check(labels(at(s, "textDocument/completion", config, m + 1, 10)) == ["bedTemp", "toolsReady"], "after")


def test_completion_macro_paths(s, card):
    config, text = start(s, card)
    end = len(text.splitlines())
    edit(s, config, 2, [{"text": text + 'M117 "😀" M98 P"\n'}])
    check(labels(at(s, "textDocument/completion", config, end, 10)) == [], "M98 after another command's string")
    edit(s, config, 3, [{"text": text + 'M98 P"\n'}])
    got = labels(at(s, "textDocument/completion", config, end, 6))
    check({"config.g", "homeall.g", "tools.g"} <= set(got) and not any("/" in g for g in got), f"relative {got}")
    edit(s, config, 4, [{"text": text + 'M98 P"/mac\n'}])
    got = at(s, "textDocument/completion", config, end, 10)
    check(labels(got) == ["/macros/Park.g"], f"from the root {labels(got)}")
    check(got["items"][0]["textEdit"] == {"range": rng(end, 6, 10), "newText": "/macros/Park.g"}, f"{got['items']}")


def test_completion_comment(s, card):
    config, text = start(s, card)
    n, line = line_of(text, "tool 1 again")
    check(at(s, "textDocument/completion", config, n, len(line))["items"] == [], "nothing in a comment")


def test_signature_help(s, card):
    config, text = start(s, card)
    n, line = line_of(text, "G10 P1 X-0.35")
    h = at(s, "textDocument/signatureHelp", config, n, line.index("X") + 2)
    sig = h["signatures"][0]
    # G10's letters and title from lint/boot/command_docs.h: "G10 P L X …: <title>".
    letters = [sig["label"][p["label"][0]:p["label"][1]] for p in sig["parameters"]]
    check(sig["label"] == "G10 " + " ".join(letters) + ": " + sig["label"].split(": ", 1)[1] and "X" in letters
          and letters[0] == "P" and sig["parameters"][0]["documentation"], f"the signature {sig}")
    check(h["activeParameter"] == letters.index("X") and sig["activeParameter"] == letters.index("X"), f"X: {h}")
    h = at(s, "textDocument/signatureHelp", config, n, len("G10 P1 "))
    check("activeParameter" not in h, f"after a blank no letter is active: {h}")
    check(at(s, "textDocument/signatureHelp", config, n, 2) is None, "on the word")
    m, _ = line_of(text, "M1234")
    check(at(s, "textDocument/signatureHelp", config, m, 7) is None, "an undocumented code")


def test_odd_positions(s, card):
    config, text = start(s, card)
    end = len(text.splitlines())
    for line, character in ((end + 5, 0), (2, 10000), (0, 10 ** 9)):  # past the end of a line: at its end
        check(at(s, "textDocument/hover", config, line, character) is None, f"hover at {line}:{character}")
        sig = at(s, "textDocument/signatureHelp", config, line, character)
        check(sig is None or line == 2, f"signature at {line}:{character}")
        at(s, "textDocument/completion", config, line, character)
    long = 'M98 P"' + "a" * 300000  # no completion (and no stack overflow in a regular expression)
    edit(s, config, 2, [{"text": text + long + "\n" + "G10 P" + "0" * 2030 + "\n"}])
    check(at(s, "textDocument/completion", config, end, len(long))["items"] == [], "a line too long")
    check(labels(at(s, "textDocument/completion", config, end + 1, 2035)) == ["P0", "P1"], "a long line within limits")
    for line, character in ((end, len(long)), (end + 1, 2035)):
        at(s, "textDocument/hover", config, line, character)
        at(s, "textDocument/signatureHelp", config, line, character)
    other = os.path.join(card, "sys", "tools.g")  # not open
    check(at(s, "textDocument/hover", other, 1, 0) is None, "a document that is not open")
    check(at(s, "textDocument/completion", other, 1, 0)["items"] == [], "completion in a document not open")
    r = s.request("textDocument/hover", {"textDocument": {"uri": uri_of(config)}})
    check(r.get("error", {}).get("code") == -32602, f"no position: {r}")
    r = s.request("textDocument/completion", {"textDocument": {"uri": uri_of(config)}, "position": {"line": -1,
                                                                                                 "character": 0}})
    check(r.get("error", {}).get("code") == -32602, f"a negative line: {r}")


TESTS = [v for k, v in list(globals().items()) if k.startswith("test_")]

if __name__ == "__main__":
    sys.exit(main(TESTS, CARD, __doc__, "lsp_features_test"))
