#!/usr/bin/env bash
# README command B: installs what is missing, builds with warnings as errors, runs every test (unit tests,
# rule fixtures, CLI tests, then the corpus smoke test when ../shared/corpus exists).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh --test
BUILD=${BUILD_DIR:-build-ci}
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRRFLINT_WERROR=ON -DBUILD_TESTING=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)"
cd "$BUILD"
# Everything but the corpus first, then the corpus smoke test (it skips, loudly, when the corpus is absent).
# --no-tests=error: a label that selects nothing fails rather than passing with "No tests were found".
ctest --output-on-failure --no-tests=error -LE corpus
ctest --output-on-failure --no-tests=error -L corpus
