#!/usr/bin/env bash
# What `cmake --install` and the .deb put on a machine, and that the installed binary works from there:
#   1. cmake --install into a scratch prefix: the binary, the man page, the bash completion, the rule pages; the
#      installed rrflint lints the bundled example (examples/toolchanger, exit 1) and its links point at the
#      installed pages; the man page renders with no groff warning and has its sections.
#   2. cpack -G DEB: the package's fields and its Depends (dpkg-shlibdeps: libfmt9, libstdc++6); dpkg -x into a
#      scratch root and the same checks; then dpkg --root installs and removes it in a scratch dpkg database.
# Part 2 needs dpkg-dev; without it the test skips (77), or fails under CI=true.
#   tests/install_test.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
BUILD=$(cd "$1" && pwd) SRC=$(cd "$2" && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
nrules=$("$BUILD/rrflint" rule --all --format json | grep -c '"code": "RRF')

# check_tree PREFIX: the files, the example, the links, the man page.
check_tree() {
  local p=$1 f
  for f in bin/rrflint share/man/man1/rrflint.1 share/bash-completion/completions/rrflint \
           share/doc/rrflint/firmware-behaviour.md share/doc/rrflint/rules/README.md; do
    [[ -f $p/$f ]] || fail "$p: no $f"
  done
  [[ -x $p/bin/rrflint ]] || { fail "$p/bin/rrflint is not executable"; return; }
  local pages
  pages=$(find "$p/share/doc/rrflint/rules" -name '*.md' ! -name README.md | wc -l)
  [[ $pages -eq $nrules ]] || fail "$p: $pages rule pages for $nrules rules"
  local out rc
  out=$("$p/bin/rrflint" check --color never "$SRC/examples/toolchanger" 2>&1); rc=$?
  [[ $rc -eq 1 ]] || fail "$p/bin/rrflint check examples/toolchanger exits $rc, not 1"
  grep -q "warning RRF304 g10-offset-on-unmapped-axis" <<<"$out" || fail "$p: the example's RRF304 is missing"
  grep -q "file://$p/share/doc/rrflint/rules/g10-offset-on-unmapped-axis.md" <<<"$out" ||
    fail "$p: the links do not point at the installed pages: $(grep -o 'file://[^ ]*' <<<"$out" | head -1)"
  out=$("$p/bin/rrflint" check --format json "$SRC/examples/toolchanger" 2>/dev/null)
  grep -q "\"url\": \"file://$p/share/doc/rrflint/rules/" <<<"$out" || fail "$p: the JSON urls are not the installed pages"
  "$p/bin/rrflint" --version | grep -qx "rrflint [0-9.]*" || fail "$p: --version"
  local man=$p/share/man/man1/rrflint.1 warnings page
  warnings=$(groff -man -Tutf8 -ww -z "$man" 2>&1)
  [[ -z $warnings ]] || fail "groff warns about the man page: $warnings"
  page=$(MANWIDTH=100 man -l "$man" 2>&1)
  for f in NAME SYNOPSIS DESCRIPTION COMMANDS OPTIONS RULES "EXIT STATUS" ENVIRONMENT FILES "SEE ALSO"; do
    grep -qx "$f" <<<"$page" || fail "the man page has no $f section"
  done
  grep -q "RRF304 g10-offset-on-unmapped-axis" <<<"$page" || fail "the man page does not list RRF304"
  grep -q -- "--output-file FILE" <<<"$page" || fail "the man page does not document --output-file"
}

echo "== cmake --install --prefix $scratch/prefix"
cmake --install "$BUILD" --prefix "$scratch/prefix" >/dev/null || fail "cmake --install"
check_tree "$scratch/prefix"

echo "== the .deb"
missing=()
for t in cpack dpkg-deb dpkg-shlibdeps dpkg; do command -v "$t" >/dev/null || missing+=("$t"); done
if [[ ${#missing[@]} -gt 0 ]]; then
  if [[ ${CI:-} == true ]]; then fail "no ${missing[*]} (scripts/setup.sh --test installs dpkg-dev)"; exit 1; fi
  echo "SKIP: the .deb part needs ${missing[*]} (dpkg-dev); failures so far: $failures" >&2
  exit $((failures > 0 ? 1 : 77))
fi
(cd "$BUILD" && cpack -G DEB -B "$scratch/pkg" >"$scratch/cpack.log" 2>&1) || { cat "$scratch/cpack.log" >&2; fail "cpack"; exit 1; }
deb=$(ls "$scratch"/pkg/rrflint_*.deb 2>/dev/null | head -1)
[[ -n $deb ]] || { fail "cpack made no rrflint_*.deb"; exit 1; }
echo "built $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"
for field in Package Version Architecture Maintainer Description; do
  [[ -n $(dpkg-deb -f "$deb" "$field") ]] || fail "the .deb has no $field"
done
[[ $(dpkg-deb -f "$deb" Package) == rrflint ]] || fail "Package is not rrflint"
[[ $(dpkg-deb -f "$deb" Version) == $("$BUILD/rrflint" --version | cut -d' ' -f2) ]] || fail "Version is not the binary's"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
names=" $(sed 's/([^)]*)//g; s/[,|]/ /g' <<<"$depends" | tr -s ' ') "
for lib in libc6 libfmt9 libstdc++6 libgcc-s1; do
  [[ $names == *" $lib "* ]] || fail "Depends does not list $lib"
done
for pkg in $names; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || fail "Depends names $pkg, not installed here"
done
dpkg-deb -c "$deb" | grep -q "/usr/local" && fail "the .deb installs under /usr/local"
mkdir -p "$scratch/root"
dpkg -x "$deb" "$scratch/root" || fail "dpkg -x"
check_tree "$scratch/root/usr"
file "$scratch/root/usr/bin/rrflint" 2>/dev/null | grep -q "not stripped" && fail "the packaged binary is not stripped"

# dpkg itself, into a scratch root with its own (empty) database: the dependencies are this machine's, so they
# are not checked there (--force-depends), but above against what is installed here.
db=$scratch/dpkgroot
mkdir -p "$db/var/lib/dpkg/info" "$db/var/lib/dpkg/updates" && touch "$db/var/lib/dpkg/status"
if dpkg --root="$db" --force-depends --force-not-root --log=/dev/null -i "$deb" >"$scratch/dpkg.log" 2>&1; then
  dpkg --root="$db" -s rrflint | grep -q "Status: install ok installed" || fail "dpkg --root: not installed"
  [[ -x $db/usr/bin/rrflint ]] || fail "dpkg --root: no usr/bin/rrflint"
  dpkg --root="$db" --force-not-root --log=/dev/null -r rrflint >/dev/null 2>&1 || fail "dpkg --root -r"
  [[ -e $db/usr/bin/rrflint ]] && fail "dpkg -r left usr/bin/rrflint"
elif [[ $(id -u) -eq 0 || ${CI:-} == true ]]; then
  # As root (and in CI) dpkg --root installs: a failure there is the package's.
  fail "dpkg --root -i: $(tail -1 "$scratch/dpkg.log")"
else
  echo "note: dpkg --root could not install here (not root): $(tail -1 "$scratch/dpkg.log")"
fi
[[ $failures -eq 0 ]] && echo "install: all checks passed"
exit $((failures > 0))
