#!/usr/bin/env python3
"""Scaffolds a new rrflint rule (in the spirit of ruff's scripts/add_rule.py and clang-tidy's add_new_check.py).

    scripts/new_rule.py RRF332 tool-offset-too-large [--severity warning] [--kind file|node|end]
                        [--on "G10 M563"] [--root DIR]

Writes rules/<identifier>.cc (identifier: the name with '-' and '.' turned into '_'), appends RULE(<identifier>) to
rules/rules.def and creates fixtures/<name>/ with two positive and two negative skeleton cases. The generated rule
is a placeholder that reports every command of its *marker* code (the first G/M code of --on, M117 by default, or
any T command when --on is only "T"), so the skeleton fixtures pass as generated: replace the check and the
fixtures together (every place to change says TODO). Then regenerate the docs (docs/adding-a-rule.md):

    cmake --build build --target rrflint_docs

Exit status: 0 done, 2 refused (bad code or name, code or name already used, files already there).
Python 3 standard library only.
"""
from __future__ import annotations

import argparse
import pathlib
import re
import sys
from typing import NoReturn

CODE_RE = re.compile(r"^RRF\d{3}$")
NAME_RE = re.compile(r"^[a-z][a-z0-9]*(?:[-.][a-z0-9]+)*$")  # kebab-case; '.' allowed as in m568-before-3.3
TOKEN_RE = re.compile(r"^(?:[GM](\d+)|T)$")
META_RE = re.compile(r'\.(code|name)\s*=\s*"([^"]*)"')

HEADER = {
    "file": "per parsed file",
    "node": "per graph node, with the machine state before it runs",
    "end": "once per machine, with the graph and the end-of-boot state",
}


def refuse(message: str) -> NoReturn:
    print(f"new_rule.py: {message}", file=sys.stderr)
    sys.exit(2)


def existing_meta(root: pathlib.Path) -> tuple[dict[str, pathlib.Path], dict[str, pathlib.Path]]:
    """Codes and names of the rules in the sources (rules/ and the engine's own rules in lint/)."""
    codes: dict[str, pathlib.Path] = {}
    names: dict[str, pathlib.Path] = {}
    files = list((root / "rules").glob("*.cc")) + list((root / "lint").glob("**/*.cc"))
    for f in files:
        text = f.read_text(encoding="utf-8", errors="replace")
        if "RuleMeta" not in text:
            continue
        for key, value in META_RE.findall(text):
            (codes if key == "code" else names).setdefault(value.upper() if key == "code" else value, f)
    return codes, names


def marker(on: list[str]) -> tuple[str, int | None]:
    """The code the placeholder check reports: the first G/M code of the `on` list, else T, else M117."""
    for tok in on:
        if tok != "T":
            return tok[0], int(tok[1:])
    if on:
        return "T", None
    return "M", 117


def marker_text(letter: str, number: int | None) -> str:
    return "T" if number is None else f"{letter}{number}"


def rule_source(code: str, name: str, ident: str, severity: str, kind: str, on: list[str]) -> str:
    letter, number = marker(on)
    mark = marker_text(letter, number)
    what = f"every {mark} command" if number is not None else "every T command"
    meta = f'''// {code} {name}: TODO one line: what the rule reports.
#include <fmt/format.h>

#include "lint/engine/rule.h"

namespace rrflint {{
namespace {{

constexpr RuleMeta kMeta{{
    .code = "{code}",
    .name = "{name}",
    .severity = Severity::{severity.capitalize()},
    .summary = "TODO: one sentence, also the first line of the docs.",
    .docs = R"md(
## What it does
TODO: what the rule looks for, and what it leaves alone (unknown values, `if` branches, standalone macros).

## Why is this bad?
TODO: what RRF does with such a line, in RRF's own words where it answers.

## Example
```gcode
{mark} ; TODO: a line the rule reports
```

## Use instead
```gcode
; TODO: the same line, fixed
```

## Fix safety
TODO: there is no fix (or: why applying it is safe, or when it is not).

## References
- TODO: [our explanation](../firmware-behaviour.md#…), the Duet3D G-code page, the RRF source (file and function)
)md",
}};

'''
    # The placeholder checks: each reports every command of the marker code, so the skeleton fixtures pass.
    if kind == "file":
        body = f'''void check(const FileContext& cx, Sink& out) {{
  const ParsedFile& pf = cx.parsed();
  // TODO: replace this placeholder: it reports {what} so that the skeleton fixtures pass.
  for (const uint32_t i : pf.with_code('{letter}', {number if number is not None else 0})) {{
    const Command c = pf.commands[i];
    out.report(kMeta, cx.at(c.span), fmt::format("TODO: say what is wrong with '{{}}'", pf.text(c.span)));
  }}
}}

}}  // namespace

extern const Rule {ident}{{.meta = kMeta, .check_file = check}};
'''
    elif kind == "node":
        test = (f"!cx.is('{letter}', {number})" if number is not None
                else "!cx.is_command() || cx.parsed().commands.code(cx.node().index).letter != 'T'")
        body = f'''void check(const NodeContext& cx, Sink& out) {{
  // TODO: replace this placeholder: it reports {what} so that the skeleton fixtures pass.
  if ({test}) return;
  const Command c = cx.command();
  out.report(kMeta, cx.at(c.span), fmt::format("TODO: say what is wrong with '{{}}'", cx.parsed().text(c.span)));
}}

}}  // namespace

extern const Rule {ident}{{.meta = kMeta, .check_node = check, .on = "{' '.join(on)}"}};
'''
    else:
        test = (f"c.letter == '{letter}' && c.number == {number}" if number is not None else "c.letter == 'T'")
        body = f'''void check(const EndContext& cx, Sink& out) {{
  // TODO: replace this placeholder: it reports {what} run, so that the skeleton fixtures pass.
  const NodeTable& nodes = cx.graph.nodes;
  nodes.find_if(0, static_cast<NodeId>(nodes.size()), [&](NodeId id, const Node& n) {{
    if (n.kind != NodeKind::Command) return false;
    const ParsedFile& pf = cx.machine.unit(n.unit).parsed;
    const CommandTable::Code c = pf.commands.code(n.index);
    if ({test})
      out.report(kMeta, cx.where(id),
                 fmt::format("TODO: say what is wrong with '{{}}'", pf.text(pf.commands[n.index].span)));
    return false;
  }});
}}

}}  // namespace

extern const Rule {ident}{{.meta = kMeta, .check_end = check}};
'''
    return meta + body + "\n}  // namespace rrflint\n"


def fixtures(name: str, on: list[str]) -> dict[str, str]:
    letter, number = marker(on)
    mark = marker_text(letter, number) if number is not None else "T0"
    # Commands for the negative cases, other than the marker.
    others = [o for o in ("G4 P0", 'M118 S"nothing to report"', "G90", "M83") if o.split()[0] != mark]
    todo = ("; TODO(new_rule.py): a skeleton case for the placeholder check ({m}); replace it with a real case.\n"
            .format(m=f"it reports every {marker_text(letter, number)}"))
    return {
        "todo-reported.g": todo + "; TODO: a line the rule reports, with its expectation at the end of the line.\n"
        f"{mark} ; expect: {name}\n",
        "todo-reported-twice.g": todo + "; TODO: a case that reports twice; an expectation can stand on a line of "
        "its own, before the line it is about.\n"
        f"; expect: {name}\n"
        f"{mark}\n"
        "if true\n"
        f"  {mark} ; expect: {name}\n",
        "todo-not-reported.g": todo + "; TODO: a look-alike the rule must leave alone.\n"
        f"{others[0]}\n",
        "todo-not-reported-comment.g": todo + "; TODO: another case the rule must leave alone (unknown values, "
        "`if` branches, other firmware versions).\n"
        f"; {mark} in a comment is not a command\n"
        f"{others[1]}\n",
    }


def main() -> int:
    ap = argparse.ArgumentParser(description="Scaffold a new rrflint rule: rule file, rules.def line, fixtures.")
    ap.add_argument("code", help="the rule code, RRFnnn")
    ap.add_argument("name", help="the rule name, kebab-case (g10-tool-before-definition)")
    ap.add_argument("--severity", default="warning", choices=["error", "warning", "info"])
    ap.add_argument("--kind", default=None, choices=["file", "node", "end"],
                    help="check_file, check_node or check_end (default: node with --on, else file)")
    ap.add_argument("--on", default=None, help='node rules: the commands check_node is called for ("G10 M563", "T")')
    ap.add_argument("--root", default=None, help="the repository root (default: this script's ..)")
    args = ap.parse_args()

    root = pathlib.Path(args.root) if args.root else pathlib.Path(__file__).resolve().parent.parent
    code, name = args.code, args.name
    if not CODE_RE.match(code):
        refuse(f"'{code}' is not a rule code: RRF and three digits (RRF332)")
    if not NAME_RE.match(name):
        refuse(f"'{name}' is not a kebab-case name (lower-case words joined by '-': tool-offset-too-large)")
    kind = args.kind or ("node" if args.on else "file")
    on = args.on.split() if args.on else []
    for tok in on:
        if not TOKEN_RE.match(tok):
            refuse(f"bad --on token '{tok}': give codes such as G10 or M563, or T for every T command")
    if kind == "node" and not on:
        on = ["M117"]
    if not (root / "rules" / "rules.def").is_file():
        refuse(f"{root} has no rules/rules.def: pass --root, the repository root")

    ident = name.replace("-", "_").replace(".", "_")
    codes, names = existing_meta(root)
    if code in codes:
        refuse(f"code {code} is already used ({codes[code].relative_to(root)})")
    if name in names:
        refuse(f"name '{name}' is already used ({names[name].relative_to(root)})")
    rule_file = root / "rules" / f"{ident}.cc"
    fixture_dir = root / "fixtures" / name
    rules_def = root / "rules" / "rules.def"
    def_text = rules_def.read_text(encoding="utf-8")
    if rule_file.exists():
        refuse(f"{rule_file.relative_to(root)} already exists")
    if re.search(rf"^RULE\({re.escape(ident)}\)", def_text, re.M):
        refuse(f"rules/rules.def already has RULE({ident})")
    if fixture_dir.exists():
        refuse(f"{fixture_dir.relative_to(root)}/ already exists")

    rule_file.write_text(rule_source(code, name, ident, args.severity, kind, on), encoding="utf-8")
    if def_text and not def_text.endswith("\n"):
        def_text += "\n"
    rules_def.write_text(def_text + f"RULE({ident})\n", encoding="utf-8")
    fixture_dir.mkdir(parents=True)
    for fname, text in fixtures(name, on if on else []).items():
        (fixture_dir / fname).write_text(text, encoding="utf-8")

    print(f"wrote rules/{ident}.cc ({HEADER[kind]}), added RULE({ident}) to rules/rules.def,")
    print(f"      fixtures/{name}/ (2 positive and 2 negative skeleton cases).")
    print("next: replace every TODO in the rule and its fixtures, then")
    print("      cmake --build build && cmake --build build --target rrflint_docs && "
          "RRFLINT_UPDATE_SNAPSHOTS=1 build/rrflint_tests \"[snapshots]\" && build/rrflint_tests \"[fixtures],[docs]\"")
    print(f"      and read fixtures/{name}/snapshot.txt (the rendering of the rule's findings) before committing it")
    return 0


if __name__ == "__main__":
    sys.exit(main())
