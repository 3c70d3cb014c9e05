"""What tests/check_layers.py and tests/check_sizes.py share: the repository root they check, its source files,
and how a check reports."""
import os
import sys

# Folders of generated files below the checked ones (bench/out: benchmark inputs and old trees).
IGNORED_DIRS = {"out", "node_modules", "corpus"}


def repo_root(args):
    """The root named on the command line (the first argument that is not an option), else this file's repository."""
    named = [a for a in args if not a.startswith("--")]
    return os.path.abspath(named[0] if named else os.path.join(os.path.dirname(__file__), ".."))


def source_files(root, tops, suffixes):
    """Paths (relative to root, sorted within each folder) of the files below `tops` whose names end in `suffixes`."""
    for top in tops:
        for dirpath, dirs, names in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(d for d in dirs if d not in IGNORED_DIRS)  # generated, not sources
            for name in sorted(names):
                if name.endswith(suffixes):
                    yield os.path.relpath(os.path.join(dirpath, name), root)


def finish(check, root, files, problems):
    """Prints the problems and a summary line; the exit code (1 also when no file was checked at all)."""
    for p in problems:
        print(p)
    if files == 0:
        print(f"{check}: no source file found under", root)
        return 1
    print(f"{check}: {files} files, {len(problems)} problems")
    return 1 if problems else 0
