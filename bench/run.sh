#!/usr/bin/env bash
# Runs rrflint's benchmarks in a Release build and writes the raw results to bench/out/.
#
#   P1  the whole corpus (../shared/corpus) in one `rrflint check` call, against `cat` of the same files
#   P2  one median corpus folder, against `cat` of its files
#   P3  a generated 100 MB file, against the npm package gcode-parser@2.2.0 and `wc -l` (the moonshot)
#   P4  peak RSS (/usr/bin/time -v) at 1, 10 and 100 MB: is memory linear in the input?
#   P5  in-process re-lint of a 300-line config (Google Benchmark, bench/bench_core.cc), target <= 1 ms
#   P6  the findings-heavy input (../shared/tools/gen-corpus-big.py) at 10, 30, 100 MB, against gcode-parser
#   P7  hostile shapes (bench/gen_hostile.py): a diamond of macro calls, thousands of tools, huge words, deep nesting;
#       and every fixture repeated to 1 MB (bench/repeat_fixtures.py)
#
# Usage: bench/run.sh [--quick]     (--quick: fewer runs, for checking the script itself)
# Needs: hyperfine, libbenchmark-dev, npm (scripts/setup.sh --bench installs them), python3.
# The results are summarised in bench/out/summary.md; bench/RESULTS.md records a reviewed run.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
src=$(cd "$here/.." && pwd)
out="$here/out"
build="$src/build-bench"
corpus="$src/../shared/corpus"
runs=10
big_runs=3
if [[ "${1:-}" == "--quick" ]]; then
  runs=2
  big_runs=1
fi

"$src/scripts/setup.sh" --bench
mkdir -p "$out"

echo "== build (Release) in $build"
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DRRFLINT_BENCH=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build "$build" -j2 --target rrflint rrflint_bench >/dev/null
rrflint="$build/rrflint"

echo "== inputs"
for size in 1M 10M 100M; do
  [[ -s "$out/gen-$size.g" ]] || python3 "$here/gen_gcode.py" --size "$size" --out "$out/gen-$size.g"
done
if [[ ! -d "$here/node_modules/gcode-parser" ]]; then
  npm install --prefix "$here" --no-save --no-package-lock --no-audit --no-fund gcode-parser@2.2.0 >/dev/null
fi

{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "machine: $(nproc) CPUs, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(free -g | awk '/Mem:/ {print $2}') GiB RAM"
  echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "rrflint: $("$rrflint" --version 2>/dev/null || echo unknown), commit $(git -C "$src" rev-parse --short HEAD 2>/dev/null || echo '?')"
  echo "compiler: $(c++ --version | head -1)"
} >"$out/machine.txt"
cat "$out/machine.txt"

check=("$rrflint" check --format json --exit-zero --color never)

if [[ -d "$corpus" ]]; then
  corpus=$(cd "$corpus" && pwd)
  mapfile -t folders < <(find "$corpus" -mindepth 1 -maxdepth 1 -type d | sort)
  # The median folder by total size.
  # The median folder by the total size of its files (bench_core.cc picks the same one).
  median=$(for d in "${folders[@]}"; do
    printf '%s\t%s\n' "$(find "$d" -type f -printf '%s\n' | awk '{s+=$1} END {print s+0}')" "$d"
  done | sort -n | awk -F'\t' '{a[NR]=$2} END {print a[int(NR/2)+1]}')
  echo "== P1: corpus (${#folders[@]} folders) in one call"
  hyperfine --warmup 2 --runs "$runs" --export-json "$out/p1.json" \
    -n "rrflint corpus" "${check[*]} $corpus/*/ >/dev/null" \
    -n "cat corpus" "find $corpus -mindepth 2 -type f -print0 | xargs -0 cat >/dev/null"
  echo "== P2: median folder $(basename "$median")"
  hyperfine --warmup 3 --runs $((runs * 3)) --export-json "$out/p2.json" \
    -n "rrflint folder" "${check[*]} '$median' >/dev/null" \
    -n "cat folder" "find '$median' -type f -print0 | xargs -0 cat >/dev/null"
else
  echo "== P1/P2 skipped: ../shared/corpus not found"
fi

echo "== P3: 100 MB file"
hyperfine --warmup 1 --runs "$big_runs" --export-json "$out/p3.json" \
  -n "rrflint 100M" "${check[*]} $out/gen-100M.g >/dev/null" \
  -n "gcode-parser 100M" "node $here/gcode_parser_bench.js $out/gen-100M.g >/dev/null" \
  -n "wc -l 100M" "wc -l $out/gen-100M.g >/dev/null"

echo "== P4: peak RSS"
: >"$out/p4.tsv"
for size in 1M 10M 100M; do
  /usr/bin/time -v "${check[@]}" "$out/gen-$size.g" >/dev/null 2>"$out/p4-$size.time"
  rss=$(awk -F': ' '/Maximum resident/ {print $2}' "$out/p4-$size.time")
  secs=$(awk -F': ' '/Elapsed/ {print $2}' "$out/p4-$size.time")
  printf '%s\t%s\t%s\t%s\n' "$size" "$(stat -c %s "$out/gen-$size.g")" "$rss" "$secs" >>"$out/p4.tsv"
done
/usr/bin/time -v node "$here/gcode_parser_bench.js" "$out/gen-100M.g" >/dev/null 2>"$out/p4-node-100M.time" || true
cat "$out/p4.tsv"

# P6: the findings-heavy input: the corpus's real config.g files concatenated (../shared/tools/gen-corpus-big.py),
# about 500 findings per MB, every one rendered as JSON. By its path the file is linted as a macro; the `as config.g`
# runs lint it as the boot file, where every node rule runs over it (that mode hid quadratic walks: RESULTS.md).
# Targets (issue 17): 10x input -> <= 11x time, peak RSS <= 3x input, >= 15x faster than gcode-parser at 100 MB.
gen_big="$src/../shared/tools/gen-corpus-big.py"
if [[ -f "$gen_big" ]]; then
  echo "== P6: findings-heavy input (gen-corpus-big) at 10, 30, 100 MB"
  for mb in 10 30 100; do
    [[ -s "$out/big-${mb}M.g" ]] || python3 "$gen_big" "$out/big-${mb}M.g" "$mb" >/dev/null
  done
  hyperfine --warmup 1 --runs "$big_runs" --export-json "$out/p6.json" \
    -n "rrflint big 10M" "${check[*]} $out/big-10M.g >/dev/null" \
    -n "rrflint big 30M" "${check[*]} $out/big-30M.g >/dev/null" \
    -n "rrflint big 100M" "${check[*]} $out/big-100M.g >/dev/null" \
    -n "rrflint big 10M as config.g" "${check[*]} --stdin-filename config.g - <$out/big-10M.g >/dev/null" \
    -n "rrflint big 100M as config.g" "${check[*]} --stdin-filename config.g - <$out/big-100M.g >/dev/null" \
    -n "gcode-parser big 100M" "node $here/gcode_parser_bench.js $out/big-100M.g >/dev/null"
  : >"$out/p6.tsv"
  for mb in 10 30 100; do
    /usr/bin/time -v "${check[@]}" "$out/big-${mb}M.g" >"$out/p6-${mb}M.json" 2>"$out/p6-${mb}M.time"
    rss=$(awk -F': ' '/Maximum resident/ {print $2}' "$out/p6-${mb}M.time")
    n=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["diagnostics"]))' "$out/p6-${mb}M.json")
    printf '%s\t%s\t%s\t%s\n' "${mb}M" "$(stat -c %s "$out/big-${mb}M.g")" "$rss" "$n" >>"$out/p6.tsv"
    rm -f "$out/p6-${mb}M.json"
  done
  cat "$out/p6.tsv"
  # Every output format at 30 MB, one run each: a renderer that builds a document tree grows with the findings
  # (SARIF did: 1 GB and 5.6 s at 100 MB until it was streamed). Marked when it needs over 3x the input in memory.
  echo "== P6: every format at 30 MB (wall s, peak RSS)"
  size=$(stat -c %s "$out/big-30M.g")
  : >"$out/p6-formats.tsv"
  for f in json json-lines sarif text concise github; do
    /usr/bin/time -f '%e %M' -o "$out/p6-format.time" "$rrflint" check --format "$f" --exit-zero --color never \
      -o /dev/null "$out/big-30M.g" 2>/dev/null
    read -r secs kb <"$out/p6-format.time"
    mark=$(awk -v kb="$kb" -v size="$size" 'BEGIN { print (kb * 1024 > 3 * size) ? "OVER 3x" : "ok" }')
    printf '%s\t%s\t%s\t%s\n' "$f" "$secs" "$kb" "$mark" | tee -a "$out/p6-formats.tsv"
  done
  rm -f "$out/p6-format.time"
else
  echo "== P6 skipped: $gen_big not found"
fi

# P7: hostile shapes (bench/gen_hostile.py): cards no real config looks like, each of which once cost seconds or
# gigabytes for a megabyte or less. Each should take about what a normal file of its size takes (tens of ms).
echo "== P7: hostile shapes"
rm -rf "$out/hostile"
python3 "$here/gen_hostile.py" "$out/hostile"
hostile=()
for shape in diamond tools suppression g10s ranges parens devices override; do
  hostile+=(-n "rrflint $shape" "${check[*]} $out/hostile/$shape >/dev/null 2>&1")
done
# longline's findings are RRF331's (an info, not in the default set): every rule runs on it.
hostile+=(-n "rrflint longline" "${check[*]} --select all $out/hostile/longline >/dev/null 2>&1")
hostile+=(-n "rrflint longline as SARIF" "${check[*]} --select all --format sarif $out/hostile/longline >/dev/null 2>&1")
hyperfine --warmup 1 --runs "$big_runs" -i --export-json "$out/p7.json" "${hostile[@]}"
# And every fixture repeated to 0.5 and 1 MB, then again with its device numbers varied per copy: a look-ahead
# that walks the nodes per command shows as a time that grows faster than the input (bench/repeat_fixtures.py marks
# it GROWS, and SLOW past 1 s per MB).
python3 "$here/repeat_fixtures.py" "$rrflint" 1000000 >"$out/p7-fixtures.md" ||
  echo "P7: some repeated fixtures are marked: see $out/p7-fixtures.md"
python3 "$here/repeat_fixtures.py" --vary "$rrflint" 1000000 >>"$out/p7-fixtures.md" ||
  echo "P7: some repeated fixtures (device numbers varied) are marked: see $out/p7-fixtures.md"

echo "== P5 and the core benchmarks (Google Benchmark)"
"$build/rrflint_bench" --benchmark_repetitions=$((runs > 2 ? 10 : 2)) --benchmark_report_aggregates_only=true \
  --benchmark_out="$out/bench_core.json" --benchmark_out_format=json

python3 - "$out" <<'PY'
import json, os, sys
out = sys.argv[1]
lines = ["# Benchmark summary (generated by bench/run.sh)", ""]
lines += ["```", open(os.path.join(out, "machine.txt")).read().strip(), "```", ""]

def hf(name, title):
    p = os.path.join(out, name)
    if not os.path.exists(p):
        return
    lines.append(f"## {title}")
    lines.append("| command | median (wall) | mean ± σ (wall) | min … max (wall) | CPU user+sys (mean) | runs |")
    lines.append("|---|---|---|---|---|---|")
    res = json.load(open(p))["results"]
    for r in res:
        sd = r.get("stddev") or 0.0
        lines.append(f"| {r['command']} | {r['median']*1000:.1f} ms | {r['mean']*1000:.1f} ± {sd*1000:.1f} ms "
                     f"| {r['min']*1000:.1f} … {r['max']*1000:.1f} ms | {(r['user'] + r['system'])*1000:.1f} ms "
                     f"| {len(r['times'])} |")
    base = res[0]["median"]
    base_cpu = res[0]["user"] + res[0]["system"]
    for r in res[1:]:
        cpu = r["user"] + r["system"]
        lines.append(f"\n{res[0]['command']} / {r['command']}: {base / r['median']:.2f}x wall, "
                     f"{base_cpu / cpu if cpu else float('inf'):.2f}x CPU")
    lines.append("")

hf("p1.json", "P1: whole corpus, one call")
hf("p2.json", "P2: median corpus folder")
hf("p3.json", "P3: 100 MB generated file")
p4 = os.path.join(out, "p4.tsv")
if os.path.exists(p4):
    lines += ["## P4: peak RSS", "| input | bytes | peak RSS | RSS / input | wall |", "|---|---|---|---|---|"]
    for row in open(p4):
        size, nbytes, rss, secs = row.rstrip("\n").split("\t")
        lines.append(f"| {size} | {nbytes} | {int(rss)/1024:.1f} MiB | {int(rss)*1024/int(nbytes):.1f} | {secs} |")
    lines.append("")
hf("p6.json", "P6: findings-heavy input (gen-corpus-big), every finding as JSON")
p6 = os.path.join(out, "p6.tsv")
if os.path.exists(p6):
    rows = [r.rstrip("\n").split("\t") for r in open(p6)]
    lines += ["| input | bytes | findings | peak RSS | RSS / input |", "|---|---|---|---|---|"]
    for size, nbytes, rss, n in rows:
        lines.append(f"| {size} | {nbytes} | {n} | {int(rss)/1024:.1f} MiB | {int(rss)*1024/int(nbytes):.2f} |")
    med = {r["command"]: r["median"] for r in json.load(open(os.path.join(out, "p6.json")))["results"]}
    b10, b100 = int(rows[0][1]), int(rows[2][1])
    t10, t100 = med["rrflint big 10M"], med["rrflint big 100M"]
    lines.append(f"\n{b100 / b10:.1f}x input -> {t100 / t10:.1f}x time (target: 10x -> <= 11x); "
                 f"gcode-parser / rrflint on 100 MB: {med['gcode-parser big 100M'] / t100:.1f}x (target >= 15x)")
    lines.append("")
hf("p7.json", "P7: hostile shapes (bench/gen_hostile.py)")
p7f = os.path.join(out, "p7-fixtures.md")
if os.path.exists(p7f):
    lines += ["## P7: every fixture repeated (bench/repeat_fixtures.py)", open(p7f).read().strip(), ""]
bc = os.path.join(out, "bench_core.json")
if os.path.exists(bc):
    lines += ["## Google Benchmark (bench/bench_core.cc)", "| benchmark | aggregate | real time | cpu time | extra |",
              "|---|---|---|---|---|"]
    for b in json.load(open(bc))["benchmarks"]:
        if b.get("aggregate_name") not in ("median", "stddev", "cv"):
            continue
        extra = ""
        if "bytes_per_second" in b and b.get("aggregate_name") == "median":
            extra = f"{b['bytes_per_second'] / 1e6:.1f} MB/s"
        unit = b.get("time_unit", "ns")
        if b.get("aggregate_name") == "cv":
            lines.append(f"| {b['run_name']} | cv | {b['real_time']*100:.1f} % | {b['cpu_time']*100:.1f} % | |")
        else:
            lines.append(f"| {b['run_name']} | {b['aggregate_name']} | {b['real_time']:.3f} {unit} | "
                         f"{b['cpu_time']:.3f} {unit} | {extra} |")
open(os.path.join(out, "summary.md"), "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
