#!/usr/bin/env bash
# The pre-commit hook end to end: Debian's pre-commit runs this repository's .pre-commit-hooks.yaml (through
# `pre-commit try-repo` on a scratch clone that holds it) on a scratch printer-config repository, with the
# built rrflint first on PATH. It must fail on a bad config, pass on a good one, and honour the config file's
# `exclude` although pre-commit names the files explicitly (the hook's --force-exclude).
# Nothing is fetched: the hook repository is a local folder and the hook's language is `system`.
# Exit 77 (ctest: skipped) when pre-commit or git is missing. Needs RRFLINT = the rrflint binary.
set -euo pipefail

: "${RRFLINT:?set RRFLINT to the rrflint binary}"
src=$(cd "$(dirname "$0")/.." && pwd)
for tool in git pre-commit; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "precommit_test: SKIPPED: $tool is not installed (scripts/setup.sh --test installs it)"
    exit 77
  fi
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# A private HOME and cache: no user configuration, nothing written outside the scratch folder.
export HOME="$work/home" PRE_COMMIT_HOME="$work/cache" GIT_CONFIG_NOSYSTEM=1
export GIT_AUTHOR_NAME=t GIT_AUTHOR_EMAIL=t@example.com GIT_COMMITTER_NAME=t GIT_COMMITTER_EMAIL=t@example.com
unset GITHUB_ACTIONS FORCE_COLOR
mkdir -p "$HOME" "$work/bin"
ln -s "$(cd "$(dirname "$RRFLINT")" && pwd)/$(basename "$RRFLINT")" "$work/bin/rrflint"
export PATH="$work/bin:$PATH"

# The hook repository: a scratch clone holding this repository's hook definitions.
hooks="$work/hooks"
mkdir -p "$hooks"
cp "$src/.pre-commit-hooks.yaml" "$hooks/"
git -C "$hooks" init -q
git -C "$hooks" add .pre-commit-hooks.yaml
git -C "$hooks" commit -q -m hooks

repo="$work/printer"
mkdir -p "$repo/sys" "$repo/macros"
git -C "$repo" init -q
printf 'M584 X0 Y1 Z2\nM98 P"/macros/park"\n' > "$repo/sys/config.g"
printf 'G1 X0 Y200 F6000\n' > "$repo/macros/park"
printf 'just notes, not G-code\n' > "$repo/README.txt"

failures=0
run() {  # run <expected exit: 0|nonzero> <label>
  local want=$1 label=$2 rc=0
  git -C "$repo" add -A
  (cd "$repo" && pre-commit try-repo "$hooks" rrflint --all-files) > "$work/out.txt" 2>&1 || rc=$?
  if { [[ $want == 0 ]] && [[ $rc -ne 0 ]]; } || { [[ $want != 0 ]] && [[ $rc -eq 0 ]]; }; then
    echo "precommit_test: FAILED: $label (exit $rc)"
    cat "$work/out.txt"
    failures=$((failures + 1))
  else
    echo "precommit_test: ok: $label"
  fi
}

run 0 "a good config passes"

printf 'M584 X0 Y1 Z2\nM9999\nM98 P"/macros/park"\n' > "$repo/sys/config.g"
run 1 "a bad config fails"
if ! grep -q "RRF101" "$work/out.txt"; then
  echo "precommit_test: FAILED: the hook output does not name the finding"
  cat "$work/out.txt"
  failures=$((failures + 1))
fi

printf 'G1 X0 ; fine\nM9999\n' > "$repo/macros/park"
printf 'M584 X0 Y1 Z2\nM98 P"/macros/park"\n' > "$repo/sys/config.g"
run 1 "an extensionless macro under macros/ is linted"

mkdir -p "$repo/old/sys"
printf 'G1 X0\n' > "$repo/macros/park"
printf 'M9999\n' > "$repo/old/sys/config.g"
run 1 "a second card with a finding fails"
printf 'exclude = ["old"]\n' > "$repo/.rrflint.toml"
run 0 "the config file's exclude is honoured for files pre-commit names"

if [[ $failures -ne 0 ]]; then
  echo "precommit_test: $failures check(s) failed"
  exit 1
fi
echo "precommit_test: all checks passed"
