#!/usr/bin/env python3
"""Golden firmware targets: the target rrflint infers for every ../shared/corpus folder, with its source, floor and
evidence, must match tests/corpus_targets.tsv. A change in inference (docs/firmware-behaviour.md#firmware-target)
therefore shows up in review, folder by folder. Exits 77 (skipped) when the corpus is absent.

usage: corpus_targets_check.py RRFLINT_BINARY [--write]   (--write prints the current table to stdout)
"""
import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
corpus = os.path.normpath(os.path.join(here, "..", "..", "shared", "corpus"))
golden_path = os.path.join(here, "corpus_targets.tsv")
HEADER = ("# Golden firmware targets of ../shared/corpus, checked by tests/corpus_targets_check.py (ctest corpus_targets).\n"
          "# Columns: folder <TAB> target <TAB> source (hint|newest) <TAB> floor <TAB> evidence (kind version file:line, '; '-separated)\n"
          "# Regenerate with: python3 tests/corpus_targets_check.py build/rrflint --write > tests/corpus_targets.tsv\n")


def row(rrflint, folder):
    path = os.path.join(corpus, folder)
    out = subprocess.run([rrflint, "check", path, "--isolated", "--select", "RRF100", "--format", "json"],
                         capture_output=True, text=True)
    if out.returncode not in (0, 1):
        return f"{folder}\tERROR rc={out.returncode}: {out.stderr.strip()[:200]}"
    machines = json.loads(out.stdout)["machines"]
    if not machines:
        return f"{folder}\tERROR: no machine"
    fw = machines[0]["firmware"]
    ev = "; ".join(f"{e['kind']} {e['version']} {os.path.relpath(e['file'], path)}:{e['line']}" for e in fw["evidence"])
    return "\t".join([folder, fw["version"], fw["source"], fw["floor"], ev or "-"])


def main():
    if len(sys.argv) < 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    if not os.path.isdir(corpus):
        print("corpus_targets: SKIPPED: ../shared/corpus not found")
        return 77
    folders = sorted(d for d in os.listdir(corpus) if os.path.isdir(os.path.join(corpus, d)))
    rows = [row(sys.argv[1], f) for f in folders]
    if "--write" in sys.argv:
        sys.stdout.write(HEADER + "\n".join(rows) + "\n")
        return 0
    with open(golden_path, encoding="utf-8") as f:
        golden = [l.rstrip("\n") for l in f if l.strip() and not l.startswith("#")]
    want = {r.split("\t")[0]: r for r in golden}
    have = {r.split("\t")[0]: r for r in rows}
    bad = 0
    for folder in sorted(set(want) | set(have)):
        if want.get(folder) != have.get(folder):
            bad += 1
            print(f"corpus_targets: {folder}\n  golden:  {want.get(folder, '(none)')}\n  now:     {have.get(folder, '(none)')}")
    print(f"corpus_targets: {len(have)} folders, {bad} differ from tests/corpus_targets.tsv")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
