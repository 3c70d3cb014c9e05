#!/usr/bin/env python3
"""The size check: no source file over 500 lines and no function over 80 lines, tests excepted.

Checks lint/, rules/, frontend/, cli/ and bench/ (C++ sources and headers). A function's length runs from the
first line of its signature to its closing brace; lambdas count towards the function that holds them. The
allow-list below names the functions (file:function) and files that may be longer, each with the reason; an
entry that no longer needs its place is reported too, so the list only shrinks.

  tests/check_sizes.py [repository root]          exit 0 when within the limits, 1 otherwise
  tests/check_sizes.py --report [root]            every file and function over half the limit, longest first
"""
import os
import re
import sys

from source_tree import finish, repo_root, source_files

MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 80
CHECKED = ["lint", "rules", "frontend", "cli", "bench"]

# Hot paths kept whole, and functions still to be split. Keep it short.
ALLOWED_FUNCTIONS = {
    # Hot paths: one pass over every byte or line of a 100 MB file. Kept whole; whether a split costs time is
    # still to be measured (bench/compare.sh on a quiet machine).
    "lint/syntax/fast_lines.cc:simple_line": "hot path: the short parse of a plain line (P3)",
    "lint/syntax/line_parser.cc:parse_logical_line": "hot path: the full parse of one logical line (P3)",
    "lint/syntax/line_parser.cc:parse_commands": "hot path: the commands of a line (P3), to be measured split",
}
ALLOWED_FILES = {
}


def strip(text):
    """Blanks comments, string and character literals (keeping newlines), so braces inside them do not count."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(")" + m.group(1) + '"', i)
                end = n if end < 0 else end + len(m.group(1)) + 2
                out.append(re.sub(r"[^\n]", " ", text[i:end]))
                i = end
            else:
                out.append(c)
                i += 1
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + (c if j - i >= 2 else ""))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(text):
    """(name, first line, last line) of every function body outside another function."""
    s = strip(text)
    s = re.sub(r"^[ \t]*#.*$", lambda m: " " * len(m.group(0)), s, flags=re.M)  # preprocessor lines
    start = 0  # index where the current statement began
    found = []
    line = 1
    line_at = [0] * (len(s) + 1)
    for i, c in enumerate(s):
        line_at[i] = line
        if c == "\n":
            line += 1
    line_at[len(s)] = line
    opened = []  # (kind, function name, first line) of each open brace
    for i, c in enumerate(s):
        if c == "{":
            head = s[start:i]
            stripped = head.strip()
            if any(k == "func" for k, _, _ in opened):
                kind = "other"
            elif re.search(r"\bnamespace\b|\bextern\s*$", stripped) or stripped.startswith("extern"):
                kind = "ns"
            elif re.search(r"\b(class|struct|union|enum)\b", stripped) and "(" not in stripped.split(":")[0]:
                kind = "class"
            elif re.search(r"\)\s*(const|noexcept|override|final|mutable|&|&&|->[^{]*|\s|:[^{]*)*$", stripped) \
                    and not re.match(r"(if|for|while|switch|catch|do)\b", stripped) and "=" not in stripped.split("(")[0]:
                kind = "func"
            else:
                kind = "other"
            first = start + (len(head) - len(head.lstrip()))
            name = ""
            if kind == "func":
                m = re.search(r"([A-Za-z_~][A-Za-z0-9_:~]*|operator\s*[^\s(]+)\s*\(", stripped)
                name = m.group(1).split("::")[-1] if m else "?"
            opened.append((kind, name, line_at[first]))
            start = i + 1
        elif c == "}":
            if opened:
                kind, name, first = opened.pop()
                if kind == "func":
                    found.append((name, first, line_at[i]))
            start = i + 1
        elif c == ";":
            start = i + 1
    return found


def main():
    report = "--report" in sys.argv
    root = repo_root(sys.argv[1:])
    problems, longest, seen_allowed = [], [], set()
    count = 0
    for path in source_files(root, CHECKED, (".h", ".cc")):
        with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
            text = f.read()
        count += 1
        n = text.count("\n")
        longest.append((n, path))
        if n > MAX_FILE_LINES:
            if path in ALLOWED_FILES:
                seen_allowed.add(path)
            else:
                problems.append(f"{path}: {n} lines (limit {MAX_FILE_LINES})")
        for fname, a, b in functions(text):
            length = b - a + 1
            longest.append((length, f"{path}:{a} {fname}()"))
            key = f"{path}:{fname}"
            if length > MAX_FUNCTION_LINES:
                if key in ALLOWED_FUNCTIONS:
                    seen_allowed.add(key)
                else:
                    problems.append(f"{path}:{a}: {fname}() is {length} lines (limit {MAX_FUNCTION_LINES})")
    for key in list(ALLOWED_FUNCTIONS) + list(ALLOWED_FILES):
        if key not in seen_allowed:
            problems.append(f"{key}: allowed to be long, but is within the limit now: remove it from the allow-list")
    if report:
        for n, what in sorted(longest, reverse=True):
            if n > MAX_FUNCTION_LINES // 2 and ("(" in what or n > MAX_FILE_LINES // 2):
                print(f"{n:6} {what}")
    return finish("check_sizes", root, count, problems)


if __name__ == "__main__":
    sys.exit(main())
