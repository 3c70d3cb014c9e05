#!/usr/bin/env python3
"""Lints every fixture repeated to SIZE/2 and SIZE bytes as a config.g, and lists the slowest and those whose time
grows faster than the input: a look-ahead that walks the nodes for each command is quadratic on such a file, where
the fixtures themselves (a few lines) never show it.

Each fixture file (`fixtures/**/*.g`, not `*.fixed.g`; a macro of a card on its own) is copied into a scratch
`sys/config.g` until it reaches the size, then linted with `--select all --format json -j 1` and RRFLINT_TRACE=1
(the time is the whole run's, from the trace). A fixture is marked GROWS when twice the input takes more than
MAX_RATIO times as long (and at least 100 ms), SLOW when it takes more than LIMIT ms per MB, FAILED when rrflint
exits with neither 0 nor 1; any of these makes the exit status 1. Fixtures that are not text (binary, UTF-16) make
a config.g that rrflint refuses (exit 2, nothing linted): they are listed apart. bench/RESULTS.md ("Fixtures repeated")
records what this found and fixed.

With --vary, each copy renumbers the tools, heaters, fans, probes and sensors it names (P, H, F, K, T, S
followed by a number get k added in the k-th copy): a config of thousands of distinct devices, where a rule that
scans every M563 of the card for each finding is quadratic even though each copy alone is not.

Usage: repeat_fixtures.py [--vary] RRFLINT [SIZE_BYTES=1000000] [LIMIT_MS_PER_MB=1000] [MAX_RATIO=3] [TOP=15]
"""
import math
import os
import re
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
fixtures = os.path.join(os.path.dirname(here), "fixtures")


NUMBERED = re.compile(rb"(?<![A-Za-z'\"{.])([PHFKTS])(\d+)\b")


def repeated(data, size, vary):
    """`data` repeated to `size` bytes; with `vary`, the k-th copy's device numbers raised by k."""
    if not vary:
        return data * max(1, -(-size // len(data)))
    out, k = bytearray(), 0
    while len(out) < size:
        out += NUMBERED.sub(lambda m: m.group(1) + str(int(m.group(2)) + k).encode(), data)
        k += 1
    return bytes(out)


def lint(rrflint, data, size, tmp, vary):
    """(whole run in ms or nan, slowest rule (ms, name), exit status) for `data` repeated to `size` bytes."""
    with open(os.path.join(tmp, "sys", "config.g"), "wb") as f:
        f.write(repeated(data, size, vary))
    run = subprocess.run([rrflint, "check", "-j", "1", "--select", "all", "--format", "json", tmp],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, errors="replace",
                         env=dict(os.environ, RRFLINT_TRACE="1"))
    total = re.findall(r"trace\s+([\d.]+) ms\s+\[\d+\] freed", run.stderr)
    rules = [(float(ms), name) for ms, name in re.findall(r"took\s+([\d.]+) ms\s+(?:node |end )?rule (\S+)", run.stderr)]
    return (float(total[-1]) if total else math.nan), max(rules, default=(0.0, "-")), run.returncode


def main():
    vary = "--vary" in sys.argv
    args = [a for a in sys.argv[1:] if a != "--vary"]
    rrflint = args[0]
    size = int(args[1]) if len(args) > 1 else 1_000_000
    limit = float(args[2]) if len(args) > 2 else 1000.0
    max_ratio = float(args[3]) if len(args) > 3 else 3.0
    top = int(args[4]) if len(args) > 4 else 15
    files = sorted(os.path.join(d, f) for d, _, fs in os.walk(fixtures) for f in fs
                   if f.endswith(".g") and not f.endswith(".fixed.g"))
    rows, refused = [], []
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, "sys"))
        for path in files:
            data = open(path, "rb").read()
            if not data.endswith(b"\n"):
                data += b"\n"
            half, _, rc_half = lint(rrflint, data, size // 2, tmp, vary)
            full, rule, rc = lint(rrflint, data, size, tmp, vary)
            if rc == 2 and rc_half == 2:
                refused.append(os.path.relpath(path, fixtures))
                continue
            marks = []
            if rc not in (0, 1) or rc_half not in (0, 1):
                marks.append(f"FAILED (exit {rc})")
            if not full <= limit * size / 1e6:
                marks.append("SLOW")
            if full >= 100 and half > 0 and full / half > max_ratio:
                marks.append("GROWS")
            rows.append((full, half, os.path.relpath(path, fixtures), rule, marks))
    rows.sort(key=lambda r: (not r[4], -r[0]))
    print(f"{len(rows)} fixtures repeated{' with their device numbers varied' if vary else ''} to {size // 2:,} "
          f"and {size:,} bytes (limits: {limit:.0f} ms per MB, "
          f"x{max_ratio:g} for twice the input); the {min(top, len(rows))} slowest, marked ones first:")
    print(f"| fixture | {size // 2:,} bytes | {size:,} bytes | slowest rule | |")
    print("|---|---|---|---|---|")
    for full, half, name, (rule_ms, rule), marks in rows[:top]:
        print(f"| {name} | {half:.0f} ms | {full:.0f} ms | {rule} {rule_ms:.0f} ms | {' '.join(marks)} |")
    if refused:
        print(f"Not text, refused (exit 2): {', '.join(refused)}")
    bad = [r for r in rows if r[4]]
    if bad:
        print(f"{len(bad)} marked: " + ", ".join(f"{r[2]} ({' '.join(r[4])})" for r in bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
