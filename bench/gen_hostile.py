#!/usr/bin/env python3
"""Writes SD cards of shapes no real config has but a hostile or broken one may, for bench/run.sh (P7). Each once
cost far more than its size (bench/RESULTS.md, "Hostile shapes"): the time must stay about that of a normal file of
the same size.

  diamond      20 calls of the next macro in each of 9 macros: the boot sequence runs to millions of commands (the
               graph stops at its node limit) and repeats every too-deep call millions of times
  tools        20,000 M563 and G10 lines over 1,000 tool numbers: each G10 before its tool's next M563
  suppression  20 suppression comments naming 50,000-byte rules
  g10s         20,000 G10 lines of one tool without Z, each with a same-line suppression comment
  ranges       20,000 suppression ranges opened and never closed
  parens       100,000 nested parentheses, braces and '!' in expressions
  devices      20,000 tools that all fail (no extruder), 20,000 M143s of one heater, 10,000 fans re-created,
               20,000 heaters named before their M950, 500 probes re-created 40 times: each finding or check once
               walked every later (or earlier) node
  override     a config-override.g of 60,000 lines loaded by an M501 that 40,000 lines follow: each later line
               walked the whole run (to find its end, and the last line that set the same thing)
  longline     one line of 20,000 G10 commands with a finding each, and a non-ASCII comment: each finding's column,
               snippet and SARIF fingerprint walked the line from its start, and each append fix parsed it again
               (5 s as JSON, 14 s as SARIF for 260 KB); run as JSON and as SARIF

Usage: gen_hostile.py OUT_DIR   (writes OUT_DIR/<shape>/sys/...)
"""
import os
import sys


def card(out, name, files):
    for path, text in files.items():
        p = os.path.join(out, name, "sys", path)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        with open(p, "w") as f:
            f.write(text)


def main():
    out = sys.argv[1]
    depth, width = 9, 20
    diamond = {"config.g": "M584 X0 Y1 Z2\n" + 'M98 P"m0.g"\n' * width}
    for i in range(depth):
        diamond[f"m{i}.g"] = "G1 X1\n" + f'M98 P"m{i + 1}.g"\n' * width
    diamond[f"m{depth}.g"] = "G10 P0 X1\n"
    card(out, "diamond", diamond)
    card(out, "tools", {"config.g": "M584 X0 Y1 Z2 U3 E4:5\n" + "".join(
        f"M563 P{i % 1000} D0 H1 X0:3 F0\nG10 P{i % 1000} X1 Y1 Z0\n" for i in range(20000))})
    word = "a" * 50000
    card(out, "suppression", {"config.g": "".join(f"G28 ; rrflint: disable={word}{i}\n" for i in range(20))})
    card(out, "g10s", {"config.g": "M584 X0 Y1 Z2 E3\nM563 P0 D0\n" + "".join(
        f"G10 P0 X{i} Y0 ; rrflint: disable=g10-missing-z\n" for i in range(20000))})
    card(out, "ranges", {"config.g": "".join(f"; rrflint: disable=line-too-long\nG1 X{i}\n" for i in range(20000))})
    n = 100000
    card(out, "parens", {"config.g": "G1 X{" + "(" * n + "1" + ")" * n + "}\nG1 X" + "{" * n + "1" + "}" * n +
                         "\nif " + "!" * n + "true\n  G1 X1\n"})
    n = 20000
    head = "; rrflint-options: --firmware 3.5\nM584 X0 Y1 Z2\n"
    card(out, "devices", {
        "config.g": head + 'M98 P"tools.g"\nM98 P"monitors.g"\nM98 P"fans.g"\nM98 P"heaters.g"\nM98 P"probes.g"\n',
        "tools.g": "".join(f"M563 P{i} D0\n" for i in range(n)),
        "monitors.g": 'M308 S1 P"temp1" Y"thermistor"\nM950 H1 C"out1" T1\n' +
                      "".join(f"M143 H1 S{200 + i % 50}\n" for i in range(n)),
        "fans.g": "".join(f'M950 F{i} C"out{i}"\nM106 P{i} S0.5\nM950 F{i} C"out{i}"\n' for i in range(n // 2)),
        "heaters.g": "".join(f"M140 H{i}\n" for i in range(2, n)) +
                     "".join(f'M950 H{i} C"out{i}" T1\n' for i in range(2, n)),
        "probes.g": "".join(f'M558 K{i % 500} P5 C"io{i % 500}.in" H5\nG31 K{i % 500} Z{i % 7}\n' for i in range(n)),
    })
    card(out, "override", {
        "config.g": head.replace("M584 X0 Y1 Z2", "M584 X0 Y1 Z2 E3:4") + "M501\n" +
                    "".join(f"M92 X{80 + i % 3} Y80\nM563 P{i % 50} D0\n" for i in range(n)),
        "config-override.g": "".join(f"M307 H{i % 8} R2 K0.3 D5 E1.35 V24\nG10 P{i % 50} X1 Y1 Z0\nM208 X{i} Y200\n"
                                     for i in range(n)),
    })
    card(out, "longline", {"config.g": "M584 X0 Y1 Z2 E3\nM563 P0 D0 H1 S\"Düse\"\n" +
                           "G10 P0 X0 Y0 " * n + "; Düse\n"})


if __name__ == "__main__":
    main()
