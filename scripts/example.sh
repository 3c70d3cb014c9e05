#!/usr/bin/env bash
# README command A: installs what is missing, builds rrflint, and lints the bundled example config.
# Exits like rrflint: 1 here, because the example has mistakes in it on purpose.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF >/dev/null
cmake --build build -j"$(nproc)" --target rrflint
exec ./build/rrflint check examples/toolchanger "$@"
