#!/usr/bin/env bash
# Prints every finding of every rule (--select ALL, JSON) on every fixture case and on every folder of
# ../shared/corpus (when present), plus the machine model of each corpus folder, in one stream. Two binaries
# that print the same stream report the same findings byte for byte: a refactoring that must not change
# behaviour compares them (scripts/findings_snapshot.sh OLD >a; scripts/findings_snapshot.sh NEW >b; cmp a b).
#
#   scripts/findings_snapshot.sh build/rrflint > findings.txt
set -uo pipefail
bin=$(realpath "${1:?usage: findings_snapshot.sh RRFLINT}")
cd "$(dirname "$0")/.."
for f in fixtures/*/*.g; do
  [[ $f == *.fixed.g ]] && continue
  opts=$(head -c 300 "$f" | tr "\r" "\n" | head -n1 | sed -n 's/.*rrflint-options:\(.*\)$/\1/p' | sed 's/--unsafe-fixes//')
  echo "### $f"
  # shellcheck disable=SC2086
  "$bin" check --select ALL --format json --color never $opts --stdin-filename sys/config.g - <"$f" 2>&1
  echo "rc=$?"
done
for d in fixtures/*/*/; do
  d=${d%/}
  opts=$(head -n1 "$d/sys/config.g" 2>/dev/null | sed -n 's/.*rrflint-options:\(.*\)$/\1/p' | sed 's/--unsafe-fixes//')
  echo "### $d"
  # shellcheck disable=SC2086
  "$bin" check --select ALL --format json --color never $opts "$d" 2>&1
  echo "rc=$?"
done
if [[ -d ../shared/corpus ]]; then
  for d in ../shared/corpus/*/; do
    d=${d%/}
    echo "### $d"
    "$bin" check --select ALL --format json --color never "$d" 2>&1
    echo "rc=$?"
    "$bin" model --format json "$d" 2>&1
    echo "rc=$?"
  done
fi
