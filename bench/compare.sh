#!/usr/bin/env bash
# Old against new, side by side in one run: P1-P4 with hyperfine (3 warm-up and 10 measured runs each, medians
# compared) and P5 with the in-process benchmark's own repetitions. For a change that must keep the speed (a
# refactoring): P1-P4 within 10 %, P5 within 20 %.
#
#   bench/compare.sh OLD_COMMIT [NEW_COMMIT]     (NEW defaults to the work tree as it is)
# Builds each in Release under bench/out/compare-*/, writes bench/out/compare.md. Needs hyperfine and
# libbenchmark-dev (scripts/setup.sh --bench). Run it on a quiet machine: other load skews the medians.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
src=$(cd "$here/.." && pwd)
out="$here/out"
old=${1:?usage: bench/compare.sh OLD_COMMIT [NEW_COMMIT]}
new=${2:-}
mkdir -p "$out"
corpus="$src/../shared/corpus"

build_at() {  # build_at NAME COMMIT|"" -> prints the build folder
  local name=$1 commit=$2 tree="$src"
  if [[ -n "$commit" ]]; then
    tree="$out/compare-$name-src"
    rm -rf "$tree" && mkdir -p "$tree"
    git -C "$src" archive "$commit" | tar -x -C "$tree"
  fi
  local b="$out/compare-$name-build"
  cmake -S "$tree" -B "$b" -DCMAKE_BUILD_TYPE=Release -DRRFLINT_BENCH=ON -DBUILD_TESTING=OFF >/dev/null
  cmake --build "$b" -j"$(nproc)" --target rrflint rrflint_bench >/dev/null
  echo "$b"
}
ob=$(build_at old "$old")
nb=$(build_at new "$new")
for size in 1M 10M 100M; do
  [[ -s "$out/gen-$size.g" ]] || python3 "$here/gen_gcode.py" --size "$size" --out "$out/gen-$size.g"
done
args="check --format json --exit-zero --color never"
hf() { hyperfine --warmup 3 --runs 10 --export-json "$out/compare-$1.json" -n "old $1" "$ob/rrflint $2 >/dev/null" \
         -n "new $1" "$nb/rrflint $2 >/dev/null"; }
if [[ -d "$corpus" ]]; then
  corpus=$(cd "$corpus" && pwd)
  hf P1 "$args $corpus/*/"
  median=$(for d in "$corpus"/*/; do printf '%s\t%s\n' "$(find "$d" -type f -printf '%s\n' | awk '{s+=$1} END {print s+0}')" "$d"; done |
           sort -n | awk -F'\t' '{a[NR]=$2} END {print a[int(NR/2)+1]}')
  hf P2 "$args '$median'"
fi
hf P3 "$args $out/gen-100M.g"
: >"$out/compare-P4.tsv"
for which in old new; do
  b=$ob; [[ $which == new ]] && b=$nb
  for i in 1 2 3; do
    /usr/bin/time -f '%M' "$b/rrflint" $args "$out/gen-100M.g" 2>&1 >/dev/null | tail -1 | sed "s/^/$which\t/" >>"$out/compare-P4.tsv"
  done
done
for which in old new; do
  b=$ob; [[ $which == new ]] && b=$nb
  (cd "$src" && "$b/rrflint_bench" --benchmark_filter=BM_Relint300 --benchmark_repetitions=20 \
     --benchmark_report_aggregates_only=true --benchmark_out="$out/compare-P5-$which.json" --benchmark_out_format=json >/dev/null)
done
python3 - "$out" <<'PY'
import json, os, statistics, sys
out = sys.argv[1]
rows = ["| | old (median) | new (median) | new / old | limit |", "|---|---|---|---|---|"]
ok = True
for p in ["P1", "P2", "P3"]:
    f = os.path.join(out, f"compare-{p}.json")
    if not os.path.exists(f):
        continue
    r = json.load(open(f))["results"]
    o, n = r[0]["median"], r[1]["median"]
    ok &= n / o <= 1.10
    rows.append(f"| {p} | {o*1000:.1f} ms | {n*1000:.1f} ms | {n/o:.3f} | 1.10 |")
rss = {"old": [], "new": []}
for line in open(os.path.join(out, "compare-P4.tsv")):
    w, kb = line.split()
    rss[w].append(int(kb))
o, n = statistics.median(rss["old"]), statistics.median(rss["new"])
ok &= n / o <= 1.10
rows.append(f"| P4 peak RSS, 100 MB | {o/1024:.1f} MiB | {n/1024:.1f} MiB | {n/o:.3f} | 1.10 |")
def p5(w):
    for b in json.load(open(os.path.join(out, f"compare-P5-{w}.json")))["benchmarks"]:
        if b.get("aggregate_name") == "median":
            return b["real_time"]
o, n = p5("old"), p5("new")
ok &= n / o <= 1.20
rows.append(f"| P5 re-lint 300 lines | {o:.1f} us | {n:.1f} us | {n/o:.3f} | 1.20 |")
text = "\n".join(rows) + f"\n\n{'within the limits' if ok else 'OVER A LIMIT'}\n"
open(os.path.join(out, "compare.md"), "w").write(text)
print(text)
PY
