#!/usr/bin/env python3
"""Planted-mistake recall: each rule's mistake, planted into copies of real corpus configs, must be found there.

Rows live in tests/planted/*.tsv, tab-separated, '#' starts a comment line:

    CODE <TAB> corpus-folder <TAB> file-in-folder <TAB> anchor <TAB> text

The folder ../shared/corpus/<corpus-folder> is copied to a scratch directory (the corpus is never written).
`text` (a literal backslash-n separates lines) is inserted before the first line of the file that the Python
regular expression `anchor` matches (searched with re.search); `$END` appends at the end of the file, and `$NEW`
creates the file, which must not exist yet (a mistake that is a file: a config-override.g nothing loads). The
inserted line that must carry the finding starts with '>' (removed before insertion); without one, the first
inserted line. The copy is linted with `rrflint check DIR --isolated --select CODE --format json`, and a
finding of CODE in that file at that line is required.

Exits 77 (skipped) when the corpus is absent.   usage: planted_check.py RRFLINT_BINARY [--verbose]
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
corpus = os.path.normpath(os.path.join(here, "..", "..", "shared", "corpus"))


def read_rows():
    rows = []
    for path in sorted(glob.glob(os.path.join(here, "planted", "*.tsv"))):
        with open(path, encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                line = line.rstrip("\n")
                if not line.strip() or line.lstrip().startswith("#"):
                    continue
                parts = line.split("\t")
                if len(parts) != 5 or not re.fullmatch(r"RRF\d{3}", parts[0]):
                    raise SystemExit(f"{path}:{n}: expected CODE, folder, file, anchor, text (5 tab-separated fields)")
                rows.append((f"{os.path.relpath(path, here)}:{n}", *parts))
    return rows


def plant(root, rel, anchor, text):
    """Inserts text into root/rel; returns the 1-based line number that must carry the finding."""
    path = os.path.join(root, rel)
    if anchor == "$NEW":
        if os.path.exists(path):
            raise LookupError(f"{rel} exists already: $NEW creates a file")
        lines = []
    else:
        with open(path, encoding="utf-8", errors="surrogateescape", newline="") as f:
            lines = f.read().splitlines(keepends=True)
    new = text.split("\\n")
    mark = next((i for i, l in enumerate(new) if l.startswith(">")), 0)
    new = [l[1:] if l.startswith(">") else l for l in new]
    eol = "\r\n" if lines and lines[0].endswith("\r\n") else "\n"
    if anchor in ("$END", "$NEW"):
        at = len(lines)
        if lines and not lines[-1].endswith("\n"):
            lines[-1] += eol
    else:
        rx = re.compile(anchor)
        at = next((i for i, l in enumerate(lines) if rx.search(l)), None)
        if at is None:
            raise LookupError(f"anchor {anchor!r} matches no line of {rel}")
    lines[at:at] = [l + eol for l in new]
    with open(path, "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
        f.write("".join(lines))
    return at + mark + 1


def main():
    if len(sys.argv) < 2:
        print("usage: planted_check.py RRFLINT [--verbose]", file=sys.stderr)
        return 2
    rrflint, verbose = sys.argv[1], "--verbose" in sys.argv
    if not os.path.isdir(corpus):
        print("planted: SKIPPED: ../shared/corpus not found")
        return 77
    rows = read_rows()
    failed = 0
    per_code = {}
    for where, code, folder, rel, anchor, text in rows:
        src = os.path.join(corpus, folder)
        if not os.path.isdir(src):
            print(f"planted: {where}: corpus folder {folder} not found")
            failed += 1
            continue
        with tempfile.TemporaryDirectory(prefix="rrflint-planted-") as tmp:
            root = os.path.join(tmp, folder)
            shutil.copytree(src, root, symlinks=True)
            try:
                line = plant(root, rel, anchor, text)
            except (LookupError, OSError) as e:
                print(f"planted: {where}: {e}")
                failed += 1
                continue
            out = subprocess.run([rrflint, "check", root, "--isolated", "--select", code, "--format", "json"],
                                 capture_output=True, text=True, timeout=120)
            if out.returncode not in (0, 1):
                print(f"planted: {where}: rrflint exited {out.returncode}: {out.stderr.strip()}")
                failed += 1
                continue
            diagnostics = json.loads(out.stdout)["diagnostics"]
            hits = [d for d in diagnostics
                    if d["code"] == code and os.path.abspath(d["file"]) == os.path.abspath(os.path.join(root, rel))
                    and d["line"] == line]
            ok = bool(hits)
            per_code.setdefault(code, [0, 0])[0 if ok else 1] += 1
            if not ok:
                failed += 1
                got = [f"{d['code']} {d['file']}:{d['line']}" for d in diagnostics]
                print(f"planted: {where}: {code} NOT found at {folder}/{rel}:{line} (found: {got or 'nothing'})")
            elif verbose:
                print(f"planted: {where}: {code} found at {folder}/{rel}:{line}: {hits[0]['message']}")
    for code in sorted(per_code):
        found, missed = per_code[code]
        print(f"planted: {code}: {found}/{found + missed} found")
    print(f"{len(rows) - failed} passed, {failed} failed")
    return 1 if failed or not rows else 0


if __name__ == "__main__":
    sys.exit(main())
