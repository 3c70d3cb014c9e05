#!/usr/bin/env bash
# Corpus smoke test: lint every folder of ../shared/corpus with the default rules.
#
# Fails when rrflint crashes, takes longer than 30 s on a folder, exits with a code other than 0 or 1, prints
# output that is not valid JSON, or reports a syntax-error (RRF100) finding that is not in the checked-in
# allowlist tests/corpus_rrf100_allowlist.tsv (`<folder>\t<file>:<line>\t<reason>`). Prints a summary: folders,
# findings per rule. Exits 77 (ctest: skipped) when the corpus is absent, as in a user's clone.
#
#   RRFLINT=build/rrflint tests/corpus_smoke.sh
set -uo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/.." && pwd)
corpus="$source_dir/../shared/corpus"
allowlist="$here/corpus_rrf100_allowlist.tsv"

if [[ ! -d "$corpus" ]]; then
  echo "corpus_smoke: SKIPPED: ../shared/corpus not found"
  exit 77
fi
corpus=$(cd "$corpus" && pwd)
rrflint="${RRFLINT:-}"
if [[ -z "$rrflint" || ! -x "$rrflint" ]]; then
  echo "corpus_smoke: set RRFLINT to the rrflint binary (got '${rrflint}')" >&2
  exit 2
fi
python=$(command -v python3 || true)
if [[ -z "$python" ]]; then
  echo "corpus_smoke: python3 is needed to read the JSON output" >&2
  exit 2
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

failures=0
folders=0
for dir in "$corpus"/*/; do
  name=$(basename "$dir")
  folders=$((folders + 1))
  timeout 30 "$rrflint" check --format json --color never "$dir" >"$work/$name.json" 2>"$work/$name.err"
  rc=$?
  echo "$rc" >"$work/$name.rc"
  case $rc in
    0 | 1) ;;
    124)
      echo "FAIL $name: timed out after 30 s"
      failures=$((failures + 1))
      ;;
    *)
      if ((rc > 128)); then
        echo "FAIL $name: crashed (signal $((rc - 128)))"
      else
        echo "FAIL $name: exit code $rc"
      fi
      sed 's/^/    /' "$work/$name.err" | head -20
      failures=$((failures + 1))
      ;;
  esac
done

"$python" - "$work" "$corpus" "$allowlist" "$folders" "$failures" <<'PY'
import collections, json, os, sys

work, corpus, allowlist_path, folders, failures = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])

allowed = {}
if os.path.exists(allowlist_path):
    for n, raw in enumerate(open(allowlist_path, encoding="utf-8"), 1):
        line = raw.rstrip("\n")
        if not line or line.startswith("#"):
            continue
        parts = line.split("\t")
        if len(parts) != 3 or not parts[2].strip():
            print(f"FAIL {os.path.basename(allowlist_path)}:{n}: expected <folder>\\t<file>:<line>\\t<reason>")
            failures += 1
            continue
        allowed[(parts[0], parts[1])] = parts[2]

per_rule = collections.Counter()
per_severity = collections.Counter()
seen_rrf100 = set()
unlisted = []
for name in sorted(os.listdir(corpus)):
    if not os.path.isdir(os.path.join(corpus, name)):
        continue
    rc = open(os.path.join(work, name + ".rc")).read().strip()
    if rc not in ("0", "1"):
        continue
    try:
        report = json.load(open(os.path.join(work, name + ".json"), encoding="utf-8"))
    except (ValueError, UnicodeDecodeError) as e:
        print(f"FAIL {name}: the JSON output does not parse: {e}")
        failures += 1
        continue
    diags = report.get("diagnostics", [])
    if rc == "0" and any(d.get("severity") == "error" for d in diags):
        print(f"FAIL {name}: exit code 0 with error findings")
        failures += 1
    for d in diags:
        code = d.get("code", "?")
        per_rule[code + " " + d.get("name", "?")] += 1
        per_severity[d.get("severity", "?")] += 1
        if code != "RRF100":
            continue
        path = os.path.relpath(d.get("file", "?"), os.path.join(corpus, name))
        key = (name, f"{path}:{d.get('line')}")
        seen_rrf100.add(key)
        if key not in allowed:
            unlisted.append((key, d.get("message", "")))

for (folder, where), message in unlisted:
    print(f"FAIL {folder}/{where}: RRF100 not in the allowlist: {message}")
failures += len(unlisted)
stale = sorted(set(allowed) - seen_rrf100)
for folder, where in stale:
    print(f"note: allowlist entry no longer reported: {folder}\t{where}")

print(f"corpus_smoke: {folders} folders, {sum(per_rule.values())} findings "
      f"({', '.join(f'{n} {s}' for s, n in sorted(per_severity.items()))})")
for rule, n in sorted(per_rule.items()):
    print(f"  {n:6d}  {rule}")
print(f"corpus_smoke: RRF100 {len(seen_rrf100)} lines, {len(allowed)} allowlisted, {len(unlisted)} not listed, "
      f"{len(stale)} stale")
if failures:
    print(f"corpus_smoke: FAILED ({failures} problems)")
    sys.exit(1)
print("corpus_smoke: OK")
PY
