#!/usr/bin/env python3
"""The layering check: no #include points up a layer, every project include is spelt from the repository root, and
no code outside the tests names a rule by its code string ("RRF107").

Layers, lowest first (a file may include its own layer and those below it):
  lint/base  lint/syntax  lint/card  lint/boot  lint/engine  lint/render  rules  frontend  cli  bench/tests
The core (lint/) knows no rule and does no I/O of its own; rules/ sit on the engine; frontend/ (disk reader,
.rrflint.toml) and cli/ sit on the rules. Run from anywhere: tests/check_layers.py [repository root].
"""
import os
import re
import sys

from source_tree import finish, repo_root, source_files

LAYERS = ["lint/base", "lint/syntax", "lint/card", "lint/boot", "lint/engine", "lint/render", "rules",
          "frontend", "cli", "bench", "tests"]
TOP = {"bench": len(LAYERS), "tests": len(LAYERS)}  # test code may include anything
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
# A rule compared with, or looked up by, its code as a string literal: the engine and the front ends name rules by
# their Rule objects (rules/registry.h, lint/engine/suppress.h), never by "RRFnnn".
CODE_LOOKUP = re.compile(r'[!=]=\s*"RRF\d|"RRF\d+"\s*[!=]=|find(_rule)?\("RRF\d')


def layer_of(path):
    for i, name in enumerate(LAYERS):
        if path == name or path.startswith(name + "/"):
            return TOP.get(name, i)
    return None


def main():
    root = repo_root(sys.argv[1:])
    problems = []
    checked = 0
    tops = ["lint", "rules", "frontend", "cli", "bench", "tests"]
    for path in source_files(root, tops, (".h", ".cc", ".inc", ".def")):
        own = layer_of(path)
        if own is None:
            problems.append(f"{path}: not in any layer (add its folder to tests/check_layers.py)")
            continue
        checked += 1
        with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
            for n, line in enumerate(f, 1):
                if not path.startswith(("tests/", "bench/")) and CODE_LOOKUP.search(line):
                    problems.append(f"{path}:{n}: a rule named by its code string (use the Rule object)")
                m = INCLUDE.match(line)
                if not m:
                    continue
                inc = m.group(1)
                if not os.path.isfile(os.path.join(root, inc)):
                    problems.append(f"{path}:{n}: include \"{inc}\" is not spelt from the repository root")
                    continue
                theirs = layer_of(inc)
                if theirs is None:
                    problems.append(f"{path}:{n}: include \"{inc}\" is in no layer")
                elif theirs > own:
                    problems.append(f"{path}:{n}: include \"{inc}\" points up a layer "
                                    f"({LAYERS[min(own, len(LAYERS) - 1)]} -> {LAYERS[min(theirs, len(LAYERS) - 1)]})")
    return finish("check_layers", root, checked, problems)

if __name__ == "__main__":
    sys.exit(main())
