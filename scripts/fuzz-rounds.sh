#!/usr/bin/env bash
# Unattended fuzzing toward the goal of 10 million executions per target (tests/fuzz/RESULTS.md): runs
# scripts/fuzz.sh in rounds, each round on the target with the fewest executions recorded so far, until the time is
# up, a round finds something, or a stop file appears. Every round appends its row, so a machine stopped half-way
# loses one round at most.
#
#   scripts/fuzz-rounds.sh HOURS [TARGET…]     default targets: every one below 10 million executions
#
# FUZZ_JOBS=N runs N workers (default 1; one per core: FUZZ_JOBS=$(nproc)) on one build. Each has its own seeds,
# logs and artifacts (FUZZ_BUILD_DIR/fuzz-work/job-K for K > 1) and all share the scratch corpora, one folder per
# target. A lock per target (flock on $FUZZ_LOCKS/TARGET, default /tmp/rrflint-fuzz-locks) keeps two workers, or
# two instances, off the same target. The targets are built once, from the last commit (FUZZ_SNAPSHOT=1 of
# scripts/fuzz.sh: a copy of it beside the build folder, so that files edited while the build runs are not compiled
# in; its commit goes in every row). To stop every worker after its current round: touch
# "$FUZZ_BUILD_DIR/fuzz-work/STOP". When a round finds something, every worker stops after its current round and
# the exit status is 1; otherwise 0.
#
# Environment: FUZZ_JOBS, FUZZ_ROUND (seconds per round, default 1800), FUZZ_GOAL (default 10000000), and those of
# scripts/fuzz.sh; FUZZ_TIMEOUT defaults to 120 s here (a fuzzer starved by other jobs on the machine is slow, not
# hung).
set -euo pipefail
# The whole script is one block, which bash reads to its end before it runs any of it: a script edited while it runs
# (a round lasts half an hour) would otherwise be read on from the old offset in the new text.
{
cd "$(dirname "$0")/.."
hours=${1:-}
[[ "$hours" =~ ^[0-9]+([.][0-9]+)?$ ]] || { echo "usage: scripts/fuzz-rounds.sh HOURS [TARGET…]" >&2; exit 2; }
shift
jobs=${FUZZ_JOBS:-1}
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz-rounds: FUZZ_JOBS must be a positive number" >&2; exit 2; }
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
stop="$build/fuzz-work/STOP"
found=$(mktemp -d)  # holds the file "found" once a worker's round has found something: the others stop too
trap 'rm -rf "$found"' EXIT

# One worker: rounds until the time is up, the stop file appears or a round finds something (status 1). $1 names
# it in the log lines.
worker() {
  local me=$1 picked left secs status lock t
  while (($(date +%s) < end)); do
    [[ -e "$stop" ]] && { echo "fuzz-rounds$me: $stop found, stopping"; return 0; }
    [[ -e "$found/found" ]] && { echo "fuzz-rounds$me: another worker found something, stopping"; return 0; }
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
    [[ -n "$picked" ]] || { echo "fuzz-rounds$me: every target has reached $goal executions or is taken"; return 0; }
    left=$((end - $(date +%s)))
    secs=$((left < round ? left : round))
    ((secs >= 60)) || { exec {lock}>&-; break; }
    echo "fuzz-rounds$me: $(date -u +%H:%M) $picked for $secs s ($(total "$picked") executions so far)"
    status=0
    FUZZ_RESULTS=$results scripts/fuzz.sh "$secs" "$picked" || status=$?
    exec {lock}>&-
    if ((status != 0)); then
      touch "$found/found"
      echo "fuzz-rounds$me: $picked found something (its row says what): stopping" >&2
      return 1
    fi
  done
  echo "fuzz-rounds$me: time is up"
}

# Workers 2..N in the background, each with its own work folder and the first worker's corpora; worker 1 here.
export FUZZ_CORPUS="$build/fuzz-work/corpus"
pids=()
for ((k = 2; k <= jobs; ++k)); do
  FUZZ_WORK="$build/fuzz-work/job-$k" worker " [job $k]" &
  pids+=($!)
done
failed=0
worker "" || failed=1
for p in "${pids[@]}"; do wait "$p" || failed=1; done
exit $failed
}
