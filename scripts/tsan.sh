#!/usr/bin/env bash
# The unit tests and a threaded lint of a large file under ThreadSanitizer (clang 14): the thread pool
# (lint/base/parallel.cc), the parse in parts, the file rules beside the forward pass, the JSON report in pieces.
# Not part of .ci/run (a third sanitized build would take CI past its 40 minutes): run it after changing anything
# that threads touch.
#
#   scripts/tsan.sh          (TSAN_BUILD_DIR: the build folder, default build-tsan)
#
# Passes only with zero reports: halt_on_error makes the first report fail the run.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh --test
build=${TSAN_BUILD_DIR:-build-tsan}
cxx=$(command -v clang++-14 || command -v clang++ || true)
[[ -n "$cxx" ]] || { echo "tsan: clang++-14 is needed (scripts/setup.sh --test installs it)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRRFLINT_WERROR=OFF -DBUILD_TESTING=ON \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" "${launcher[@]}" >/dev/null
cmake --build "$build" -j"$(nproc)" --target rrflint_tests rrflint
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
"$build/rrflint_tests" -r compact
# A file of 8 MB (past the size at which a file is parsed in parts and its rules run beside the model), linted as a
# macro and as a config.g on four threads, the report as JSON.
big=$(mktemp -d)
trap 'rm -rf "$big"' EXIT
python3 bench/gen_gcode.py --size 8M --out "$big/big.g" >/dev/null
"$build/rrflint" check -j4 --format json --exit-zero "$big/big.g" >/dev/null
"$build/rrflint" check -j4 --format json --exit-zero --stdin-filename config.g - <"$big/big.g" >/dev/null
echo "tsan: no reports"
