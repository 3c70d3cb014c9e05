#!/usr/bin/env python3
"""Corpus baseline check: every finding of the baselined rules on ../shared/corpus must be in
tests/corpus_baseline.tsv (judged TP/FP with a reason), and every baseline row must still be found.

A change in what a rule reports on real configs therefore shows up in review. Exits 77 (skipped) when the
corpus is absent.   usage: corpus_baseline_check.py RRFLINT_BINARY [--write]
"""
import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
corpus = os.path.normpath(os.path.join(here, "..", "..", "shared", "corpus"))
baseline_path = os.path.join(here, "corpus_baseline.tsv")


def main():
    if len(sys.argv) < 2:
        print("usage: corpus_baseline_check.py RRFLINT [--write]", file=sys.stderr)
        return 2
    rrflint = sys.argv[1]
    if not os.path.isdir(corpus):
        print("corpus_baseline: SKIPPED: ../shared/corpus not found")
        return 77
    rows = {}
    codes = set()
    tally_line = None
    with open(baseline_path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                if line.startswith("# codes:"):
                    codes.update(line.split(":", 1)[1].split())
                if line.startswith("# tally:"):
                    tally_line = line.strip()
                continue
            parts = line.rstrip("\n").split("\t")
            if len(parts) != 5 or parts[3] not in ("TP", "FP") or not parts[4].strip():
                print(f"{baseline_path}:{n}: expected folder, file:line, code, TP|FP, reason", file=sys.stderr)
                return 1
            rows[(parts[0], parts[1], parts[2])] = parts
    found = set()
    severity = {}
    for folder in sorted(os.listdir(corpus)):
        path = os.path.join(corpus, folder)
        if not os.path.isdir(path):
            continue
        out = subprocess.run([rrflint, "check", path, "--format", "json", "--isolated", "--select", ",".join(sorted(codes))],
                             capture_output=True, text=True, timeout=120)
        if out.returncode not in (0, 1):
            print(f"corpus_baseline: {folder}: exit {out.returncode}: {out.stderr.strip()}")
            return 1
        for d in json.loads(out.stdout)["diagnostics"]:
            rel = os.path.relpath(os.path.join(os.getcwd(), d["file"]), path) if not os.path.isabs(d["file"]) else os.path.relpath(d["file"], path)
            key = (folder, f"{rel}:{d['line']}", d["code"])
            found.add(key)
            # One row may stand for several findings on a line: the most severe counts.
            order = ("info", "warning", "error")
            if order.index(d["severity"]) >= order.index(severity.get(key, "info")):
                severity[key] = d["severity"]
    new = sorted(found - set(rows))
    gone = sorted(set(rows) - found)
    if "--write" in sys.argv:
        for k in new:
            print("\t".join(k) + f"\t?\t? ({severity[k]})")
        return 0
    for k in new:
        print("corpus_baseline: NEW finding not in the baseline (judge it, add a row): " + "\t".join(k))
    for k in gone:
        print("corpus_baseline: baseline row NO LONGER found (update the baseline): " + "\t".join(k))
    tp = sum(1 for r in rows.values() if r[3] == "TP")
    tally = {sev: {"TP": 0, "FP": 0} for sev in ("error", "warning", "info")}
    for k in found & set(rows):
        tally[severity[k]][rows[k][3]] += 1
    want = "# tally: " + "; ".join(f"{sev} TP {t['TP']} FP {t['FP']}" for sev, t in tally.items())
    bad_tally = tally_line != want
    if bad_tally:
        print(f"corpus_baseline: the header's tally line is stale; it must read:\n{want}")
    low = []
    for sev, floor in (("error", 0.98), ("warning", 0.95)):
        n = tally[sev]["TP"] + tally[sev]["FP"]
        if n and tally[sev]["TP"] / n < floor:
            low.append(f"{sev}s {tally[sev]['TP']}/{n} true, below {floor:.0%}")
    for m in low:
        print(f"corpus_baseline: precision too low: {m}")
    print(f"corpus_baseline: {len(found)} findings of {len(codes)} rules; baseline {len(rows)} rows "
          f"({tp} TP, {len(rows) - tp} FP); {len(new)} new, {len(gone)} gone")
    print(f"{len(found) - len(new)} passed, {len(new) + len(gone)} failed")
    return 1 if new or gone or bad_tally or low else 0


if __name__ == "__main__":
    sys.exit(main())
