#!/usr/bin/env python3
"""Writes the seed inputs of the fuzz targets (tests/fuzz/fuzz_*.cc) into OUT/<target>/, in each target's format.

    tests/fuzz/make_seeds.py [--max N] OUT [CORPUS]

Sources: tests/fuzz/corpus/, the rule fixtures (fixtures/: a <case>.g is a card of one config.g, a <case>/ folder a
whole card) and, read-only, the real configs of CORPUS (default ../shared/corpus, skipped when absent). OUT must
be a scratch folder (scripts/fuzz.sh uses one under its build folder): the seeds are never written into the
repository or the corpus. Formats: `parse` is an option byte and one file; `lint` an option byte, config.g and
optionally 0xFF and /sys/m.g; `card`, `fix` and `render` the card format of tests/fuzz/fuzz_input.h; `lsp` LSP
messages, framed and broken; `session` the operations of tests/fuzz/fuzz_session.cc on a card's files. --max N keeps N seeds per target, spread evenly over them (a short smoke run,
which would spend its time on the seeds alone).
"""
import json
import sys
import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
MAX_CARD = 16384  # bytes of a card seed (files are added, smallest first, while they fit)
MAX_FILES = 16  # the card format keeps 16 files (tests/fuzz/fuzz_input.h)
CARD_DIRS = ("sys", "macros", "filaments")


def sel(name):
    """The option byte of a seed: spread over the targets' choices, the same for the same name on every run."""
    return bytes([zlib.crc32(name.encode()) & 0xFF])


def card_of(files):
    """Card format (without the option byte) of [(sd_path, bytes)], config.g first."""
    config = [b for p, b in files if p == "/sys/config.g"]
    out = config[0] if config else b""
    rest = sorted(((p, b) for p, b in files if p != "/sys/config.g"), key=lambda f: len(f[1]))
    for path, data in rest[: MAX_FILES - 1]:
        part = b"\xff" + path.encode() + b"\n" + data
        if len(out) + len(part) > MAX_CARD:
            break
        out += part
    return out


def card_files(root):
    """[(sd_path, bytes)] of the SD card in folder `root` (its sys/, macros/, filaments/)."""
    files = []
    for d in CARD_DIRS:
        for f in sorted((root / d).rglob("*")) if (root / d).is_dir() else []:
            if f.is_file() and not f.name.endswith(".fixed.g"):
                files.append(("/" + f.relative_to(root).as_posix(), f.read_bytes()))
    return files


def cards():
    """(name, [(sd_path, bytes)]) of every seed card."""
    for f in sorted((HERE / "corpus").iterdir()):
        yield "seed-" + f.name, [("/sys/config.g", f.read_bytes())]
    for rule in sorted((ROOT / "fixtures").iterdir()):
        if not rule.is_dir():
            continue
        for case in sorted(rule.iterdir()):
            name = f"fixture-{rule.name}-{case.stem}"
            if case.is_file() and case.suffix == ".g" and not case.name.endswith(".fixed.g"):
                yield name, [("/sys/config.g", case.read_bytes())]
            elif case.is_dir():
                files = card_files(case)
                if files:
                    yield name, files


def corpus_cards(corpus):
    for sys_dir in sorted(corpus.rglob("sys")):
        if (sys_dir / "config.g").is_file():
            root = sys_dir.parent
            yield "corpus-" + root.relative_to(corpus).as_posix().replace("/", "-"), card_files(root)


def frame(body):
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


def lsp_seeds(texts):
    """LSP sessions: a whole exchange around one fixture, then broken framing."""
    uri = "file:///tmp/card/sys/config.g"

    def msg(**m):
        return json.dumps({"jsonrpc": "2.0", **m}).encode()

    for name, text in texts:
        t = text.decode("utf-8", "replace")
        session = [
            msg(id=1, method="initialize", params={"processId": None, "rootUri": None, "capabilities": {}}),
            msg(method="initialized", params={}),
            msg(method="textDocument/didOpen",
                params={"textDocument": {"uri": uri, "languageId": "gcode", "version": 1, "text": t}}),
            msg(method="textDocument/didChange",
                params={"textDocument": {"uri": uri, "version": 2},
                        "contentChanges": [{"range": {"start": {"line": 0, "character": 0},
                                                      "end": {"line": 0, "character": 1}}, "text": "M"}]}),
            msg(id=2, method="textDocument/codeAction",
                params={"textDocument": {"uri": uri}, "range": {"start": {"line": 0, "character": 0},
                                                                "end": {"line": 0, "character": 0}},
                        "context": {"diagnostics": []}}),
            msg(id=3, method="shutdown"),
            msg(method="exit"),
        ]
        yield name, b"".join(frame(b) for b in session)
    yield "broken-length", b"Content-Length: 99999999999\r\n\r\n{}" + frame(msg(id=1, method="x"))
    yield "broken-json", frame(b'{"id": 1, "method": ') + frame(msg(id=2, method="y"))
    yield "broken-header", b"Content-Type: x\r\n\r\n" + b"garbage Content-Length: 2\r\n\r\n{}"
    yield "cut-body", b"Content-Length: 40\r\n\r\n{\"id\":"


def session_seeds(all_cards):
    """Sessions of tests/fuzz/fuzz_session.cc: open a card's config.g (document 0) and one macro (document 2), lint,
    ask for hover, completion, signature help and code actions, edit a range, lint again, close."""

    def text(data):
        data = data[:2047]
        return bytes([len(data) // 8, len(data) % 8]) + data

    for name, files in all_cards:
        config = dict(files).get("/sys/config.g", b"")
        macro = next((b for p, b in files if p != "/sys/config.g"), b"M98 P\"config.g\"\n")
        # Each operation: its code, the document, its operands (a position: line, character; a range: two
        # positions and a byte that keeps the second one when it is a multiple of 4).
        ops = bytes([0, 0]) + text(config) + bytes([0, 2]) + text(macro)  # open both
        ops += bytes([3, 0])  # lint
        ops += bytes([4, 0, 1, 2, 5, 0, 2, 1, 6, 0, 3, 6])  # hover, completion, signature help
        ops += bytes([7, 0, 1, 0, 0, 4, 0, 0])  # quickfixes for lines 0 to 4
        ops += bytes([2, 0, 0, 1, 0, 1, 0, 1]) + text(b'M563 P0 S"x"\n')  # insert a line at line 1
        ops += bytes([7, 0, 3, 0, 0, 0, 0, 1])  # fix all
        ops += bytes([10, 0, 9, 9, 0, 8, 2, 3, 0])  # settings, save, close, lint
        yield name, sel("session" + name) + ops


def main():
    args = sys.argv[1:]
    most = None
    if args[:1] == ["--max"] and len(args) > 1 and args[1].isdigit() and int(args[1]) > 0:
        most, args = int(args[1]), args[2:]
    if len(args) not in (1, 2):
        sys.exit(__doc__)
    out = Path(args[0])
    corpus = Path(args[1]) if len(args) == 2 else ROOT.parent / "shared" / "corpus"
    all_cards = list(cards())
    if corpus.is_dir():
        all_cards += list(corpus_cards(corpus))
    seeds = {t: {} for t in ("parse", "lint", "card", "fix", "render", "lsp", "session")}
    for name, files in all_cards:
        for path, data in files:
            seeds["parse"][name + path.replace("/", "-")] = sel(name + path) + data
        config = dict(files).get("/sys/config.g", b"")
        macro = next((b for p, b in files if p != "/sys/config.g"), None)
        seeds["lint"][name] = sel(name) + config + (b"\xff" + macro if macro is not None else b"")
        card = card_of(files)
        for t in ("card", "fix", "render"):
            seeds[t][name] = sel(t + name) + card
    small = [(n, dict(f).get("/sys/config.g", b"")) for n, f in all_cards if n.startswith(("seed", "fixture"))]
    for name, data in lsp_seeds(small):
        seeds["lsp"][name] = sel(name) + data
    for name, data in session_seeds(all_cards):
        seeds["session"][name] = data
    for target, items in seeds.items():
        if most is not None and len(items) > most:
            names = sorted(items)
            items = {n: items[n] for n in names[:: -(-len(names) // most)]}
            seeds[target] = items
        d = out / target
        d.mkdir(parents=True, exist_ok=True)
        for name, data in items.items():
            (d / name).write_bytes(data)
    print(f"make_seeds: {', '.join(f'{t} {len(s)}' for t, s in seeds.items())} seeds in {out}")


if __name__ == "__main__":
    main()
