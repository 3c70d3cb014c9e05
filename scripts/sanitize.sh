#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (with leak detection): builds
# everything with -fsanitize=address,undefined -fno-sanitize-recover=all in its own build folder, then runs every
# ctest test (unit tests, fixtures, the CLI and language-server tests, which run this build's sanitized rrflint)
# and the corpus tests. Passes only with zero sanitizer reports: any report aborts the process that made it (so
# its test fails), and the reports are also written under the build folder and printed at the end.
#
#   scripts/sanitize.sh          (SANITIZE_BUILD_DIR: the build folder, default build-asan)
#
# SANITIZE_FUZZ=1 (clang only) also builds the libFuzzer targets in this folder, for `FUZZ_BUILD_DIR=build-asan
# FUZZ_NO_BUILD=1 scripts/fuzz.sh` (.ci/run's fuzz smoke): the core is then compiled once with the coverage
# instrumentation libFuzzer needs as well as the sanitizers (RRFLINT_FUZZ), instead of again in a fuzz build of its
# own. The suite runs on that core: the instrumentation calls no-op hooks outside a fuzz target.
#
# Left out, as they test nothing under the sanitizers and scripts/test.sh runs them: `scaffold`, which builds a
# scratch copy of the sources of its own (not sanitized); `windows`, which cross-builds and runs rrflint.exe under
# wine; `vscode`, the TypeScript extension's build and tests (npm).
# Warnings are not errors here: they change with the compiler and the sanitizers' instrumentation (false
# positives), and the warnings gate is the ordinary GCC build of scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh --test
build=${SANITIZE_BUILD_DIR:-build-asan}
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# clang-14 (setup.sh --test installs it for the fuzz targets) at -O1 with line tables, assertions on: it builds
# this suite in about a third of the time GCC takes at -O2 -g with the same sanitizers, which keeps CI within its
# 40 minutes, and -O1 is what the sanitizers' authors advise. SANITIZE_CXX picks another compiler.
cxx=${SANITIZE_CXX:-$(command -v clang++-14 || command -v clang++ || echo g++)}
cxx=$(command -v "$cxx")
# A build folder configured with another compiler is configured afresh.
if [[ -f "$build/CMakeCache.txt" ]] && ! grep -qx "CMAKE_CXX_COMPILER:[A-Z]*=$cxx" "$build/CMakeCache.txt"; then
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
fi
clang=0
[[ $("$cxx" --version) == *clang* ]] && clang=1
debug=-gline-tables-only
((clang)) || debug=-g1
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
fuzz=OFF
if [[ "${SANITIZE_FUZZ:-}" == 1 ]]; then
  ((clang)) || { echo "sanitize: SANITIZE_FUZZ=1 needs clang (libFuzzer)" >&2; exit 2; }
  fuzz=ON
fi
start=$(date +%s)
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 $debug" -DRRFLINT_WERROR=OFF -DBUILD_TESTING=ON -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DRRFLINT_PCH=ON -DRRFLINT_FUZZ=$fuzz "${launcher[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)"
built=$(date +%s)

reports=$(cd "$build" && pwd)/sanitizer-reports
rm -rf "$reports"
mkdir -p "$reports"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:log_path=$reports/asan"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:abort_on_error=1:log_path=$reports/ubsan"
export LSAN_OPTIONS="log_path=$reports/lsan"
status=0
(cd "$build" && ctest --output-on-failure --no-tests=error -LE 'corpus|scaffold|windows|vscode') || status=1
(cd "$build" && ctest --output-on-failure --no-tests=error -L corpus) || status=1
end=$(date +%s)
if compgen -G "$reports/*" >/dev/null; then
  echo "sanitize: sanitizer reports:" >&2
  cat "$reports"/* >&2
  status=1
fi
echo "sanitize: build $((built - start)) s, tests $((end - built)) s, $( ((status == 0)) && echo passed || echo FAILED)"
exit $status
