#!/usr/bin/env bash
# Unattended fuzzing toward the goal of 10 million executions per target (tests/fuzz/RESULTS.md): runs
# scripts/fuzz.sh in rounds, each round on the target with the fewest executions recorded so far, until the time is
# up, a round finds something, or a stop file appears. Every round appends its row, so a machine stopped half-way
# loses one round at most.
#
#   scripts/fuzz-rounds.sh HOURS [TARGET…]     default targets: every one below 10 million executions
#
# One instance per core: give each its own FUZZ_BUILD_DIR (e.g. build-fuzz, build-fuzz2). A lock per target
# (flock on $FUZZ_LOCKS/TARGET, default /tmp/rrflint-fuzz-locks) keeps two instances off the same target. The targets
# are built once, from the last commit (FUZZ_SNAPSHOT=1 of scripts/fuzz.sh: a copy of it beside the build folder, so
# that files edited while the build runs are not compiled in; its commit goes in every row). To stop after the
# current round: touch "$FUZZ_BUILD_DIR/fuzz-work/STOP".
#
# Environment: FUZZ_ROUND (seconds per round, default 1800), FUZZ_GOAL (default 10000000), and those of
# scripts/fuzz.sh; FUZZ_TIMEOUT defaults to 120 s here (a fuzzer starved by other jobs on the machine is slow, not
# hung).
set -euo pipefail
cd "$(dirname "$0")/.."
hours=${1:-}
[[ "$hours" =~ ^[0-9]+([.][0-9]+)?$ ]] || { echo "usage: scripts/fuzz-rounds.sh HOURS [TARGET…]" >&2; exit 2; }
shift
round=${FUZZ_ROUND:-1800}
goal=${FUZZ_GOAL:-10000000}
results=${FUZZ_RESULTS-tests/fuzz/RESULTS.md}
[[ -n "$results" && -f "$results" ]] || { echo "fuzz-rounds: the rows go to FUZZ_RESULTS, which must exist" >&2; exit 2; }
build=${FUZZ_BUILD_DIR:-build-fuzz}
locks=${FUZZ_LOCKS:-/tmp/rrflint-fuzz-locks}
mkdir -p "$locks"
export FUZZ_BUILD_DIR=$build FUZZ_TIMEOUT=${FUZZ_TIMEOUT:-120}
candidates=("$@")
[[ ${#candidates[@]} -eq 0 ]] && candidates=(parse lint card fix render lsp session)

# The executions recorded for target $1.
total() {
  FUZZ_RESULTS=$results scripts/fuzz.sh --totals | awk -v t="$1" '$1 == t { n = $2 } END { print n + 0 }'
}

# Build once, then run what was built (each row names the commit its target was built from).
FUZZ_SNAPSHOT=${FUZZ_SNAPSHOT:-1} FUZZ_BUILD_ONLY=1 scripts/fuzz.sh 1 "${candidates[@]}" || { echo "fuzz-rounds: the targets did not build" >&2; exit 2; }
export FUZZ_NO_BUILD=1

end=$(($(date +%s) + $(awk -v h="$hours" 'BEGIN { printf "%d", h * 3600 }')))
while (($(date +%s) < end)); do
  [[ -e "$build/fuzz-work/STOP" ]] && { echo "fuzz-rounds: $build/fuzz-work/STOP found, stopping"; exit 0; }
  # The candidates below the goal, fewest executions first; the first whose lock is free runs.
  picked=""
  for t in $(for c in "${candidates[@]}"; do echo "$(total "$c") $c"; done | sort -n | awk -v g="$goal" '$1 < g { print $2 }'); do
    exec {lock}>"$locks/$t"
    if flock -n "$lock"; then
      picked=$t
      break
    fi
    exec {lock}>&-
  done
  [[ -n "$picked" ]] || { echo "fuzz-rounds: every target has reached $goal executions or is taken"; exit 0; }
  left=$((end - $(date +%s)))
  secs=$((left < round ? left : round))
  ((secs >= 60)) || break
  echo "fuzz-rounds: $(date -u +%H:%M) $picked for $secs s ($(total "$picked") executions so far)"
  status=0
  FUZZ_RESULTS=$results scripts/fuzz.sh "$secs" "$picked" || status=$?
  exec {lock}>&-
  ((status == 0)) || { echo "fuzz-rounds: $picked found something (its row says what): stopping" >&2; exit 1; }
done
echo "fuzz-rounds: time is up"
