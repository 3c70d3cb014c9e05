#!/usr/bin/env bash
# The bash completion the build generates (rrflint rule --generate-completion): sources it, sets COMP_WORDS
# and COMP_CWORD as bash does for a few command lines, calls the completion function and checks COMPREPLY.
#   tests/completion_test.sh COMPLETION_FILE RRFLINT SOURCE_DIR
set -uo pipefail
COMPLETION=$1 RRFLINT=$2 SRC=$3
[[ -f $COMPLETION ]] || { echo "FAIL: no completion file $COMPLETION" >&2; exit 1; }
# shellcheck disable=SC1090
source "$COMPLETION"
complete -p rrflint >/dev/null || { echo "FAIL: the script registers no completion for rrflint" >&2; exit 1; }
cd "$SRC" || exit 1
failures=0

# expect "WORDS…" "EXPECTED REPLIES" : the last word is the one being completed ('' for an empty word).
expect() {
  local line=$1 want=$2
  read -r -a COMP_WORDS <<<"$line"
  [[ $line == *" " ]] && COMP_WORDS+=("")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  _rrflint rrflint "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD-1]}"
  local got="${COMPREPLY[*]}"
  if [[ $got != "$want" ]]; then
    echo "FAIL: '$line' completes to '$got', expected '$want'" >&2
    failures=$((failures + 1))
  else
    echo "ok: '$line' -> '$got'"
  fi
}

expect "rrflint ch" "check"
expect "rrflint c" "check config"
expect "rrflint --v" "--version"
expect "rrflint check --for" "--format --force-exclude"
expect "rrflint check --format j" "json json-lines"
expect "rrflint check --format = sa" "sarif"          # --format=sa, split at '=' by bash
expect "rrflint check --fail-on " "error warning info"
expect "rrflint check --jobs " ""                       # a number: nothing to offer
expect "rrflint check --select RRF90" "RRF900 RRF901"
expect "rrflint check --ignore RRF1,g10-tool-b" "RRF1,g10-tool-before-definition"
expect "rrflint config --extend-select g10-imp" "g10-implicit-z"
expect "rrflint rule RRF50" "RRF501 RRF502 RRF503 RRF504 RRF505 RRF506 RRF507 RRF508"
expect "rrflint rule unused-s" "unused-suppression"
expect "rrflint model --format " "text json"
expect "rrflint server -" "-h --help"
expect "rrflint check --add-supp" "--add-suppressions"
expect "rrflint check examples/toolch" "examples/toolchanger"
expect "rrflint check -o examples/toolch" "examples/toolchanger"
expect "rrflint rule --generate-docs docs/ru" "docs/rules"

# Every rule of the binary, by code and by name, and nothing else.
want=$("$RRFLINT" rule --all --format json | grep -oE '"(code|name)": "[^"]*"' | sed 's/.*: "//; s/"$//' | sort)
COMP_WORDS=(rrflint rule "") COMP_CWORD=2 COMPREPLY=()
_rrflint
got=$(printf '%s\n' "${COMPREPLY[@]}" | grep -v '^ALL$' | sort)
if [[ -z $want || $got != "$want" ]]; then
  echo "FAIL: 'rrflint rule <TAB>' does not offer exactly the rules of 'rrflint rule --all'" >&2
  diff <(echo "$want") <(echo "$got") | head >&2
  failures=$((failures + 1))
fi
echo "$(($(wc -l <<<"$got"))) rule words"
exit $((failures > 0))
