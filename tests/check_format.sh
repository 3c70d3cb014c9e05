#!/usr/bin/env bash
# The format check: every C++ file of the repository (tracked, or new and not ignored: a file not yet added is
# checked and fixed too) is formatted as .clang-format says (clang-format 14).
# Skips (exit 77) when clang-format-14 is not installed; scripts/setup.sh --test installs it.
#   tests/check_format.sh            check;  tests/check_format.sh --fix   reformat in place
set -uo pipefail
cd "$(dirname "$0")/.."
cf=$(command -v clang-format-14 || true)
if [[ -z "$cf" ]]; then
  echo "check_format: SKIPPED: clang-format-14 not found (scripts/setup.sh --test installs it)"
  exit 77
fi
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard '*.cc' '*.h')  # new files too
else
  mapfile -t files < <(find lint rules frontend cli tests bench -name '*.cc' -o -name '*.h')
fi
if [[ ${#files[@]} -eq 0 ]]; then
  echo "check_format: no C++ file found"
  exit 1
fi
if [[ "${1:-}" == "--fix" ]]; then
  "$cf" -i --style=file "${files[@]}"
  exit 0
fi
if ! "$cf" --dry-run --Werror --style=file "${files[@]}" 2>/tmp/check_format.$$; then
  head -40 /tmp/check_format.$$
  echo "check_format: files differ from .clang-format; run tests/check_format.sh --fix"
  rm -f /tmp/check_format.$$
  exit 1
fi
rm -f /tmp/check_format.$$
echo "check_format: ${#files[@]} files formatted"
