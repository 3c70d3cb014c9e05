#!/usr/bin/env bash
# ctest `windows`: scripts/windows.sh (cross build of rrflint.exe, the zip, the example and --format json under
# wine, compared with the native binary) in a folder of the native build. Without MinGW-w64, wine or zip it skips
# (77), or fails under CI=true, where scripts/setup.sh --test has installed them.
#   tests/windows_test.sh SOURCE_DIR NATIVE_BUILD_DIR NATIVE_RRFLINT
set -uo pipefail
SRC=$1 BUILD=$2 NATIVE=$3
missing=()
for t in x86_64-w64-mingw32-g++-posix zip unzip python3; do command -v "$t" >/dev/null || missing+=("$t"); done
command -v wine64 >/dev/null || command -v wine >/dev/null || [[ -x /usr/lib/wine/wine64 ]] || missing+=(wine64)
if [[ ${#missing[@]} -gt 0 ]]; then
  if [[ ${CI:-} == true ]]; then echo "FAIL: ${missing[*]} missing (scripts/setup.sh --test installs them)" >&2; exit 1; fi
  echo "SKIP: the Windows test needs ${missing[*]}" >&2
  exit 77
fi
start=$SECONDS
BUILD_DIR=$BUILD/windows NATIVE=$NATIVE bash "$SRC/scripts/windows.sh"
rc=$?
echo "windows test: $((SECONDS - start)) s in all"
exit $rc
