#!/usr/bin/env bash
# The Windows build: cross-compiles rrflint.exe with Debian's MinGW-w64 (cmake/mingw-w64.cmake; fmt,
# nlohmann-json, toml++ and CLI11 header-only; libstdc++, libgcc and winpthread linked in), packages
# rrflint-<version>-windows-x86_64.zip (rrflint.exe, README.md, the rule pages under docs/), and tests it under
# wine: the bundled example in the text format, and --format json compared with the native binary's findings.
#   scripts/windows.sh               build, package, test
#   scripts/windows.sh --no-test     build and package only
# BUILD_DIR (default build-windows) is the cross build's folder; NATIVE (default build/rrflint) the native binary
# the JSON is compared with (built if missing). Tools: scripts/setup.sh --test installs them.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$(pwd)
BUILD=${BUILD_DIR:-build-windows}
mkdir -p "$BUILD" && BUILD=$(cd "$BUILD" && pwd)
NATIVE=${NATIVE:-build/rrflint}
test=1
[[ ${1:-} == --no-test ]] && test=0
for t in x86_64-w64-mingw32-g++-posix zip; do
  command -v "$t" >/dev/null || { echo "windows: $t is missing (scripts/setup.sh --test)" >&2; exit 3; }
done
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
start=$SECONDS
# -O2, as the .deb is built (CMake's Release would be -O3), and the standard and fmt headers precompiled: together
# 418 s instead of 503 s for this build on two cores (session 23).
cmake -S . -B "$BUILD" -DCMAKE_TOOLCHAIN_FILE="$src/cmake/mingw-w64.cmake" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DRRFLINT_PCH=ON -DBUILD_TESTING=OFF "${launcher[@]}" >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target rrflint
echo "windows: cross build $((SECONDS - start)) s"
version=$(sed -n 's/^project(rrflint VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
name=rrflint-$version-windows-x86_64
stage=$BUILD/$name
rm -rf "$stage" "$BUILD/$name.zip"
cmake --install "$BUILD" --prefix "$stage" --strip >/dev/null
cp README.md "$stage/"
[[ -f LICENSE ]] && cp LICENSE "$stage/"
(cd "$BUILD" && zip -qr "$name.zip" "$name")
echo "windows: $BUILD/$name.zip ($(du -k "$BUILD/$name.zip" | cut -f1) KiB)"
[[ $test -eq 1 ]] || exit 0

wine=$(command -v wine64 || command -v wine || ls /usr/lib/wine/wine64 2>/dev/null || true)  # Debian 12: wine64 alone is /usr/lib/wine/wine64
[[ -n $wine ]] || { echo "windows: wine64 is missing (scripts/setup.sh --test)" >&2; exit 3; }
[[ -x $NATIVE ]] || cmake --build "$(dirname "$NATIVE")" --target rrflint >/dev/null
start=$SECONDS
export WINEPREFIX=$BUILD/wineprefix WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml="
# The test runs the exe from the unpacked zip, as a user would, outside the build folder (a binary below it links
# the source tree's pages, cli/docs_url.cc).
unpacked=$(mktemp -d)
trap 'rm -rf "$unpacked"' EXIT
(cd "$unpacked" && unzip -q "$BUILD/$name.zip")
exe=$unpacked/$name/rrflint.exe
out=$BUILD/wine-out
mkdir -p "$out"
fails=0
"$wine" "$exe" --version >"$out/version.txt" 2>&1 || true
tr -d '\r' <"$out/version.txt" | grep -qx "rrflint $version" || { echo "FAIL: --version: $(cat "$out/version.txt")"; fails=1; }
rc=0
"$wine" "$exe" check --color never examples/toolchanger >"$out/text.txt" 2>&1 || rc=$?
[[ $rc -eq 1 ]] || { echo "FAIL: rrflint.exe check examples/toolchanger exits $rc, not 1"; fails=1; }
grep -q "examples/toolchanger/sys/config.g:99:8: warning RRF304 g10-offset-on-unmapped-axis" "$out/text.txt" ||
  { echo "FAIL: the example's RRF304 is not in the text output"; fails=1; }
grep -q "file:///[A-Za-z]:/.*/docs/rules/g10-offset-on-unmapped-axis.md" "$out/text.txt" ||
  { echo "FAIL: the links do not point at the zip's docs/rules"; fails=1; }
rc=0
"$wine" "$exe" check --format json examples/toolchanger >"$out/windows.json" 2>"$out/json.err" || rc=$?
[[ $rc -eq 1 ]] || { echo "FAIL: --format json exits $rc, not 1: $(head -3 "$out/json.err")"; fails=1; }
"$NATIVE" check --format json examples/toolchanger >"$out/native.json" 2>/dev/null || true
python3 "$src/tests/windows_json_check.py" "$out/windows.json" "$out/native.json" || fails=1
echo "windows: wine tests $((SECONDS - start)) s"
[[ $fails -eq 0 ]] && echo "windows: rrflint.exe passes under wine"
exit $fails
