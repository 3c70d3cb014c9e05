#!/usr/bin/env bash
# Runs one real-editor test of `rrflint server` (tests/clients/): neovim 0.7+ headless, or Emacs 28+ in batch mode
# with eglot. Each works on a scratch copy of tests/clients/card, with rrflint first on PATH (the documented
# snippets start `rrflint server` from PATH) and a scratch HOME, so no user configuration takes part.
#
#   tests/clients/run_client.sh nvim|eglot path/to/rrflint
#
# Exit 0 when the test passes, 1 when it fails. When the editor (or eglot) is missing: exit 77 (ctest SKIP) -- but
# with CI=true in the environment, exit 1: CI must not pass over a test that did not run.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
client=${1:-}
rrflint=${2:-}
if [[ -z "$client" || -z "$rrflint" || ! -x "$rrflint" ]]; then
  echo "usage: run_client.sh nvim|eglot path/to/rrflint" >&2
  exit 2
fi

missing() {
  if [[ "${CI:-}" == "true" ]]; then
    echo "run_client: FAIL: $1 (CI=true: scripts/setup.sh --test installs it)" >&2
    exit 1
  fi
  echo "run_client: SKIPPED: $1 (scripts/setup.sh --test installs it)"
  exit 77
}

scratch=$(mktemp -d "${TMPDIR:-/tmp}/rrflint-client.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
cp -R "$here/card" "$scratch/card"
mkdir -p "$scratch/home"
export HOME="$scratch/home" XDG_CONFIG_HOME="$scratch/home/.config" XDG_DATA_HOME="$scratch/home/.local/share"
export XDG_STATE_HOME="$scratch/home/.local/state" XDG_CACHE_HOME="$scratch/home/.cache"
export RRFLINT_CARD="$scratch/card" RRFLINT_EDITORS_MD="$here/../../docs/editors.md"
PATH="$(cd "$(dirname "$rrflint")" && pwd):$PATH"
export PATH
cd "$scratch" || exit 1

start=$(date +%s.%N)
case "$client" in
  nvim)
    command -v nvim >/dev/null 2>&1 || missing "nvim not found"
    # -u: the test is the init file, so the documented snippet runs where an init.lua would, before the file
    # types load. No shada, no swap files, no plugins; timeout: the outer guard, should neovim hang.
    timeout -k 5 90 nvim --headless -u "$here/nvim_lsp_test.lua" -i NONE -n --noplugin
    rc=$?
    ;;
  eglot)
    command -v emacs >/dev/null 2>&1 || missing "emacs not found"
    # stdin from /dev/null: a prompt fails at once rather than waiting.
    timeout -k 5 90 emacs -Q --batch -l "$here/eglot_test.el" </dev/null
    rc=$?
    [[ $rc -eq 77 ]] && missing "eglot not found (Debian: elpa-eglot for Emacs 28)"
    ;;
  *)
    echo "run_client: unknown client '$client' (nvim or eglot)" >&2
    exit 2
    ;;
esac
if [[ $rc -eq 124 || $rc -eq 137 ]]; then
  echo "run_client: FAIL: $client did not finish within 90 s" >&2
  rc=1
fi
awk -v c="$client" -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "run_client: %s took %.1f s\n", c, b - a }'
exit $rc
