#!/usr/bin/env bash
# The rule scaffold end to end (ctest 'scaffold'): copies the sources (git ls-files, untracked files included) into
# a scratch folder, runs scripts/new_rule.py there for a made-up file rule, node rule and end rule, regenerates the
# docs as the guide tells authors to (docs/adding-a-rule.md), builds the copy and checks that `rrflint rule CODE`
# prints each new rule and that the fixture and docs tests pass, the new skeleton fixtures included.
#
#   scaffold_test.sh SOURCE_DIR [CXX_COMPILER]
#
# The copy is built unoptimised and without debug information (a Debug build at -O0, assertions on): it checks
# that the scaffolded rules compile without warnings and pass their tests, not how fast they run, and it builds in
# less than half the time of an -O2 -g build (the warnings gate for the real code is scripts/test.sh's build).
# Skips (77) when python3 or cmake is missing. The scratch folder sits beside the source tree (under ccache's
# base_dir, /work here) under a name fixed per source tree, so a rerun's compiles hit ccache (its -O0 flags differ
# from the main build's, whose objects it cannot reuse). It is removed on exit. RRFLINT_SCAFFOLD_KEEP=1 keeps it.
set -euo pipefail
src=$(cd "$1" && pwd)
cxx=${2:-}
command -v python3 >/dev/null || { echo "SKIP: python3 not found"; exit 77; }
command -v cmake >/dev/null || { echo "SKIP: cmake not found"; exit 77; }

parent=$(dirname "$src")
[ -w "$parent" ] || parent=${TMPDIR:-/tmp}
scratch="$parent/tmp-scaffold-$(basename "$src")"
cleanup() { [ "${RRFLINT_SCAFFOLD_KEEP:-0}" = 1 ] || rm -rf "$scratch"; }
trap cleanup EXIT
rm -rf "$scratch"
mkdir -p "$scratch"

# The sources: what git knows (tracked and untracked, not ignored), else everything but build*/ and .git.
if git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git -C "$src" ls-files -z --cached --others --exclude-standard |
    tar -C "$src" --null -T - --ignore-failed-read -cf - 2>/dev/null | tar -C "$scratch" -xf -
else
  tar -C "$src" --exclude='./build*' --exclude=./.git -cf - . | tar -C "$scratch" -xf -
fi

# Three free codes, from the top of the range down.
codes=()
for n in $(seq 999 -1 900); do
  grep -rqs "\"RRF$n\"" "$scratch/rules" "$scratch/lint" || codes+=("RRF$n")
  [ "${#codes[@]}" -lt 3 ] || break
done
names=(scaffold-made-up-file scaffold-made-up-node scaffold-made-up-end)
python3 "$scratch/scripts/new_rule.py" --root "$scratch" "${codes[0]}" "${names[0]}"
python3 "$scratch/scripts/new_rule.py" --root "$scratch" "${codes[1]}" "${names[1]}" --kind node --on "G10 M563" \
  --severity error
python3 "$scratch/scripts/new_rule.py" --root "$scratch" "${codes[2]}" "${names[2]}" --kind end --on T --severity info
# It refuses a code or a name that is taken, and a name that is not kebab-case.
for bad in "${codes[0]} scaffold-other" "RRF998x scaffold-other" "${codes[2]%?}0 ${names[1]}" "RRF100 Not_Kebab"; do
  rc=0
  # shellcheck disable=SC2086
  python3 "$scratch/scripts/new_rule.py" --root "$scratch" $bad 2>/dev/null || rc=$?
  [ "$rc" = 2 ] || { echo "FAIL: new_rule.py $bad exited $rc, not 2"; exit 1; }
done

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
compiler=()
[ -n "$cxx" ] && compiler=(-DCMAKE_CXX_COMPILER="$cxx")
cmake -S "$scratch" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DRRFLINT_WERROR=ON \
  -DBUILD_TESTING=ON -DRRFLINT_PCH=ON "${launcher[@]}" "${compiler[@]}" >/dev/null
cmake --build "$scratch/build" -j2 --target rrflint rrflint_tests
cmake --build "$scratch/build" --target rrflint_docs >/dev/null
# The guide's next step: the snapshot of the new rules' findings (fixtures/<name>/snapshot.txt).
RRFLINT_UPDATE_SNAPSHOTS=1 "$scratch/build/rrflint_tests" "[snapshots]" >/dev/null
for i in 0 1 2; do
  [ -s "$scratch/fixtures/${names[$i]}/snapshot.txt" ] || { echo "FAIL: no snapshot for ${names[$i]}"; exit 1; }
done

for i in 0 1 2; do
  out=$("$scratch/build/rrflint" rule "${codes[$i]}")
  first=$(printf '%s\n' "$out" | head -1)
  [ "$first" = "# ${names[$i]} (${codes[$i]})" ] || { echo "FAIL: rrflint rule ${codes[$i]} printed: $first"; exit 1; }
  [ -f "$scratch/docs/rules/${names[$i]}.md" ] || { echo "FAIL: no docs/rules/${names[$i]}.md"; exit 1; }
done
# The fixture tests (the new skeletons among them: two positive and two negative cases each) and the docs test.
"$scratch/build/rrflint_tests" -w NoTests "[fixtures],[docs]"
echo "scaffold: ${codes[*]} scaffolded, built, registered, fixtures and docs pass"
