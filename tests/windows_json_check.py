#!/usr/bin/env python3
"""Compares the JSON report of rrflint.exe (under wine) with the native binary's on the same input: the same
findings (code, severity, message, file, positions, notes, fixes), summary and firmware targets. The rule links
differ by design (each points at its own installed pages) and are left out, as are absolute paths.
   tests/windows_json_check.py WINDOWS_JSON NATIVE_JSON"""
import json
import sys


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def strip(value):
    if isinstance(value, dict):
        return {k: strip(v) for k, v in value.items() if k != "url"}
    if isinstance(value, list):
        return [strip(v) for v in value]
    return value


def main():
    try:
        win, native = load(sys.argv[1]), load(sys.argv[2])
    except (OSError, ValueError) as e:
        print(f"FAIL: the JSON does not parse: {e}")
        return 1
    problems = []
    if win.get("version") != 1:
        problems.append(f"version {win.get('version')!r}, not 1")
    wd, nd = strip(win.get("diagnostics", [])), strip(native.get("diagnostics", []))
    if not nd:
        problems.append("the native report has no findings: nothing to compare")
    if wd != nd:
        for i, (w, n) in enumerate(zip(wd, nd)):
            if w != n:
                problems.append(f"diagnostic {i} differs:\n  windows {w}\n  native  {n}")
                break
        if len(wd) != len(nd):
            problems.append(f"{len(wd)} findings under wine, {len(nd)} native")
    if win.get("summary") != native.get("summary"):
        problems.append(f"summary {win.get('summary')} != {native.get('summary')}")
    if strip(win.get("machines")) != strip(native.get("machines")):
        problems.append(f"machines differ:\n  windows {win.get('machines')}\n  native  {native.get('machines')}")
    for p in problems:
        print("FAIL:", p)
    if not problems:
        print(f"windows: the JSON matches the native binary's ({len(wd)} findings)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
