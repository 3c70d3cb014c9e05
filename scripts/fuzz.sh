#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/fuzz_*.cc; clang 14, -fsanitize=fuzzer,address,undefined) in their own
# build folder and runs each for a given time, appending one row per run to tests/fuzz/RESULTS.md.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET…]     default: 60 seconds, every target
#   scripts/fuzz.sh --totals                           the executions recorded per target: "TARGET COUNT" lines
#
# TARGET: parse, lint, card, fix, render, lsp, session. Each run has a timeout per input (hang detection), a memory limit
# and leak detection on. Seeds come from tests/fuzz/make_seeds.py (fixtures/, and ../shared/corpus read-only when
# present); new inputs go to a scratch corpus under the build folder, kept from run to run; crash, hang, leak and
# out-of-memory inputs go to its artifacts/ folder. Exits non-zero when any run found something (the row names
# the input), when a target would not build, or when libFuzzer's output could not be read.
#
# Environment: FUZZ_BUILD_DIR (default build-fuzz), FUZZ_RESULTS (the file the rows go to; set it empty to record
# nothing, as the CI smoke does), FUZZ_SEEDS (keep that many seeds per target, spread over them: a short run would
# spend its time on the seeds alone), FUZZ_ENTROPIC (1: libFuzzer's entropic schedule, off by default, see below),
# FUZZ_TIMEOUT (seconds per input, default 10), FUZZ_RSS_MB (default 2048),
# FUZZ_NO_BUILD=1 (run the targets already built, as scripts/fuzz-rounds.sh does after building them once, so that
# edits made meanwhile are not built half-done; the rows name the commit each was built from, kept beside it as
# fuzz_TARGET.commit), FUZZ_BUILD_ONLY=1 (build the targets and stop), FUZZ_SNAPSHOT=1 (build from the committed tree,
# copied to FUZZ_BUILD_DIR-src, not from the working tree: scripts/fuzz-rounds.sh sets it), FUZZ_WORK (the folder of
# the seeds, logs and artifacts, default FUZZ_BUILD_DIR/fuzz-work) and FUZZ_CORPUS (the scratch corpora, one folder
# per target, default FUZZ_WORK/corpus): the workers of `FUZZ_JOBS=N scripts/fuzz-rounds.sh` each have their own
# FUZZ_WORK and share one FUZZ_CORPUS.
set -euo pipefail
# The whole script is one block, which bash reads to its end before it runs any of it: a script edited while it runs
# (a round lasts half an hour) would otherwise be read on from the old offset in the new text.
{
cd "$(dirname "$0")/.."
root=$(pwd)
results=${FUZZ_RESULTS-tests/fuzz/RESULTS.md}
# The executions per target over every recorded row, as "TARGET COUNT" lines sorted by target.
totals() {
  awk -F'|' '$3 ~ /[a-z]/ && $4 ~ /^ *[0-9]+ *$/ { gsub(/ /, "", $3); n[$3] += $4 } END { for (t in n) printf "%s %d\n", t, n[t] }' \
    "$results" | sort
}
if [[ "${1:-}" == --totals ]]; then
  [[ -n "$results" && -f "$results" ]] || { echo "fuzz: --totals needs FUZZ_RESULTS, an existing file" >&2; exit 2; }
  totals
  exit 0
fi
seconds=${1:-60}
shift || true
all=(parse lint card fix render lsp session)
targets=("$@")
[[ ${#targets[@]} -eq 0 ]] && targets=("${all[@]}")
for t in "${targets[@]}"; do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "fuzz: unknown target '$t' (known: ${all[*]})" >&2; exit 2; }
done
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -gt 0 ]] || { echo "fuzz: SECONDS_PER_TARGET must be a positive number" >&2; exit 2; }

build=${FUZZ_BUILD_DIR:-build-fuzz}
timeout=${FUZZ_TIMEOUT:-10}
rss=${FUZZ_RSS_MB:-2048}
cxx=$(command -v clang++-14 || command -v clang++ || true)
[[ -n "$cxx" ]] || { echo "fuzz: clang++-14 is needed (scripts/setup.sh --test installs it)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# The commit the targets are built from (`+`: with uncommitted changes, RESULTS.md aside).
commit=$(git rev-parse --short HEAD 2>/dev/null || echo "-")
git diff --quiet HEAD -- . ":(exclude)$results" 2>/dev/null || commit="$commit+"
src=.
if [[ "${FUZZ_SNAPSHOT:-}" == 1 && "${FUZZ_NO_BUILD:-}" != 1 ]]; then
  # Built from the committed tree, copied beside the build folder: files edited while the build runs are not
  # compiled in half-done, and the rows name exactly what was built. Only files whose content changed are copied
  # (and get a new time), so the next build recompiles only what the commits changed.
  src="$build-src"
  commit=$(git rev-parse --short HEAD)
  fresh=$(mktemp -d)
  git archive HEAD | tar -x -C "$fresh"
  mkdir -p "$src"
  (cd "$fresh" && find . -type f) | while IFS= read -r f; do
    cmp -s "$fresh/$f" "$src/$f" || { mkdir -p "$(dirname "$src/$f")" && cp "$fresh/$f" "$src/$f"; }
  done
  (cd "$src" && find . -type f) | while IFS= read -r f; do [[ -e "$fresh/$f" ]] || rm -f "$src/$f"; done
  rm -rf "$fresh"
  src=$(cd "$src" && pwd)
fi
# A build folder configured from another source folder is configured afresh (not when only running what is built).
if [[ "${FUZZ_NO_BUILD:-}" != 1 && -f "$build/CMakeCache.txt" ]] &&
  ! grep -qx "CMAKE_HOME_DIRECTORY:INTERNAL=$(cd "$src" && pwd)" "$build/CMakeCache.txt"; then
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"
fi
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
[[ -f "$build/CMakeCache.txt" ]] && generator=()
if [[ "${FUZZ_NO_BUILD:-}" == 1 ]]; then
  for t in "${targets[@]}"; do
    [[ -x "$build/fuzz_$t" ]] || { echo "fuzz: FUZZ_NO_BUILD=1 but $build/fuzz_$t is not built" >&2; exit 2; }
  done
else
  cmake -S "$src" -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DRRFLINT_FUZZ=ON -DBUILD_TESTING=OFF -DRRFLINT_WERROR=ON -DRRFLINT_PCH=ON "${launcher[@]}" >/dev/null
  cmake --build "$build" -j"$(nproc)" --target "${targets[@]/#/fuzz_}"
  for t in "${targets[@]}"; do echo "$commit" >"$build/fuzz_$t.commit"; done
fi
[[ "${FUZZ_BUILD_ONLY:-}" == 1 ]] && exit 0

work=${FUZZ_WORK:-$build/fuzz-work}
corpus=${FUZZ_CORPUS:-$work/corpus}
rm -rf "$work/seeds"
python3 tests/fuzz/make_seeds.py ${FUZZ_SEEDS:+--max "$FUZZ_SEEDS"} "$work/seeds"
mkdir -p "$work/artifacts" "$work/logs"

# libFuzzer's entropic schedule (on by default) updates a frequency for every feature an execution hits, and a lint
# hits tens of thousands (InputCorpus::UpdateFeatureFrequency: a third of the samples in perf). Off, the executions
# of equal time (one worker, session 22): lint from its seeds, 90 s: 21,605 against 17,927; render from its seeds,
# 75 s: 10,865 against 6,788; card from a 4,368-input corpus, 100 s: 9,811 against 9,443 (the corpus read in 40
# instead of 57 s, then no quicker). Coverage and features were higher with it off every time. Each round reads its
# whole corpus again, which is where it gains most. FUZZ_ENTROPIC=1 turns it back on.
entropic=${FUZZ_ENTROPIC:-0}
[[ "$entropic" == 0 || "$entropic" == 1 ]] || { echo "fuzz: FUZZ_ENTROPIC must be 0 or 1" >&2; exit 2; }
declare -A max_len=([parse]=8192 [lint]=4096 [card]=8192 [fix]=4096 [render]=4096 [lsp]=8192 [session]=8192)
if [[ -n "$results" && ! -f "$results" ]]; then
  echo "fuzz: $results is missing (it starts with the table header)" >&2
  exit 2
fi
failed=0
for t in "${targets[@]}"; do
  mkdir -p "$corpus/$t"
  log="$work/logs/$t.log"
  # The commit of the binary about to run, read now: a build during the run (FUZZ_NO_BUILD=1 runs what another
  # build left) would otherwise lend this row the next binary's commit.
  built_from=$(cat "$build/fuzz_$t.commit" 2>/dev/null || echo "$commit")
  start=$(date +%s)
  status=0
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/fuzz_$t" -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb="$rss" -detect_leaks=1 -entropic="$entropic" \
    -max_len="${max_len[$t]}" -dict="tests/fuzz/$([[ $t == lsp ]] && echo lsp || echo rrf).dict" -print_final_stats=1 \
    -artifact_prefix="$work/artifacts/$t-" "$corpus/$t" "$work/seeds/$t" >"$log" 2>&1 || status=$?
  elapsed=$(($(date +%s) - start))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(sed -n 's/.*[ \t]cov: \([0-9]*\).*/\1/p' "$log" | tail -1)
  # A slow-unit file is libFuzzer's note of an input that took over 10 s (-report_slow_units), not a failure: a
  # hang is a timeout (-timeout), a crash or sanitizer report ends the run. (A machine that stopped or starved the
  # fuzzer makes slow units of quick inputs.) They are counted in the row, not as findings.
  artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | grep -v '/[a-z]*-slow-unit-' | tail -1 || true)
  slow=$(grep -c 'Test unit written to .*-slow-unit-' "$log" || true)
  findings=0
  if [[ $status -ne 0 || -n "$artifact" ]]; then
    findings=${artifact:-"exit $status, see $log"}
    [[ -n "$artifact" ]] && findings="${artifact#"$root"/}"
    failed=1
    echo "fuzz: $t FOUND SOMETHING (exit $status): $findings" >&2
    # The report and the input itself, so that a finding on a machine whose files are gone (CI) can be replayed:
    # `base64 -d > crash && build-fuzz/fuzz_TARGET crash`.
    sed -n -E '/ERROR|ALARM|runtime error|out-of-memory/,+24p' "$log" | head -40 >&2 || true
    if [[ -n "$artifact" && -f "$artifact" ]]; then
      echo "fuzz: the input, $(wc -c <"$artifact") bytes, base64 (the first 12 KB):" >&2
      head -c 12288 "$artifact" | base64 -w 120 >&2
    fi
  elif [[ -z "$execs" ]]; then
    echo "fuzz: $t: no statistics in $log" >&2
    failed=1
    continue
  fi
  [[ "$findings" == 0 && "${slow:-0}" -gt 0 ]] && findings="0 (slow-unit notes: $slow, the slowest $(sed -n 's/^stat::slowest_unit_time_sec: *//p' "$log" | tail -1) s)"
  echo "fuzz: $t: ${execs:-?} executions in ${elapsed} s, cov ${cov:-?}, findings: $findings"
  if [[ -n "$results" ]]; then
    printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$(date -u +%Y-%m-%dT%H:%MZ)" "$t" "${execs:-?}" "$elapsed" \
      "${cov:-?}" "$findings" "$built_from" >>"$results"
  fi
done
if [[ -n "$results" ]]; then
  totals | while read -r t n; do echo "fuzz: total $t: $n executions"; done
fi
exit $failed
}
