#!/usr/bin/env bash
# Builds the VS Code extension (editors/vscode/) into editors/vscode/rrflint-<version>.vsix and checks it:
# npm ci, ESLint, tsc, the extension's tests (node --test; the server smoke test when RRFLINT names the rrflint
# binary), vsce package, then what the .vsix holds. Needs node 18+ and npm (Debian 12: nodejs, npm;
# scripts/setup.sh --test installs them) and the npm registry for `npm ci`.
#   scripts/vscode.sh                  build and check; fails when node or npm is missing
#   scripts/vscode.sh --skip-missing   the same, but exit 77 (ctest: skipped) when node or npm is missing or the
#                                      registry cannot be reached, unless CI=true, where that is a failure
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
ext="$here/editors/vscode"

missing() {
  if [[ "${1:-}" == "--skip-missing" && "${CI:-}" != "true" ]]; then
    echo "vscode: SKIPPED: $2 (scripts/setup.sh --test installs node and npm; npm ci needs the npm registry)"
    exit 77
  fi
  echo "vscode: $2; ${3:-install Node 18 or later and npm (Debian: apt-get install nodejs npm, or scripts/setup.sh --test)}" >&2
  exit 1
}
for tool in node npm; do
  command -v "$tool" >/dev/null 2>&1 || missing "${1:-}" "$tool is not installed"
done
major=$(node -p 'process.versions.node.split(".")[0]')
[[ "$major" -ge 18 ]] || missing "${1:-}" "node $(node --version) is too old, the extension needs 18 or later"
echo "vscode: node $(node --version), npm $(npm --version)"

cd "$ext"
export npm_config_audit=false npm_config_fund=false npm_config_update_notifier=false
version=$(node -p 'require("./package.json").version')
vsix="rrflint-$version.vsix"
rm -f "$vsix"
step() {
  echo "vscode: $*"
  "$@"
}
# The registry first: a machine that cannot reach it (offline, or behind a TLS proxy whose certificate it does not
# trust) gets a clear message instead of npm's, and with --skip-missing a skip, except under CI=true.
if ! reason=$(npm ping 2>&1); then
  missing "${1:-}" "the npm registry is not reachable ($(grep -m1 -oE '(code|reason:?) [A-Za-z_: -]+' <<<"$reason" || echo "npm ping failed"))" \
    "npm ci needs it (check the network, a proxy and its CA certificate: npm config get cafile)"
fi
step npm ci
step npm run lint
step npm run compile
if [[ -n "${RRFLINT:-}" ]]; then
  export RRFLINT
else
  echo "vscode: RRFLINT is not set: the server smoke test is skipped"
fi
step npm test
step npx vsce package --skip-license --allow-missing-repository -o "$vsix"

# What the .vsix (a zip) must hold: the compiled extension, its runtime dependency, the language definition, a
# grammar that parses, and none of the sources, tests or build tools. Its version must be rrflint's (CMakeLists.txt).
cmake_version=$(sed -n 's/^project(rrflint VERSION \([0-9.]*\).*/\1/p' "$here/CMakeLists.txt")
python3 - "$vsix" "$cmake_version" <<'PY'
import json, sys, zipfile
vsix, cmake_version = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(vsix) as z:
    names = set(z.namelist())
    need = ["extension/package.json", "extension/out/extension.js", "extension/out/server.js", "extension/out/files.js",
            "extension/syntaxes/rrf-gcode.tmLanguage.json", "extension/language-configuration.json",
            "extension/README.md", "extension/node_modules/vscode-languageclient/package.json", "extension.vsixmanifest"]
    problems = [f"missing {n}" for n in need if n not in names]
    for prefix in ["extension/src/", "extension/out/test/", "extension/test/", "extension/node_modules/typescript/",
                   "extension/node_modules/@vscode/vsce/", "extension/node_modules/eslint/"]:
        if any(n.startswith(prefix) for n in names):
            problems.append(f"holds {prefix}")
    if not problems:
        manifest = json.loads(z.read("extension/package.json"))
        grammar = json.loads(z.read("extension/syntaxes/rrf-gcode.tmLanguage.json"))
        config = json.loads(z.read("extension/language-configuration.json"))
        if manifest["version"] != cmake_version:
            problems.append(f"version {manifest['version']} is not rrflint's {cmake_version}")
        if grammar.get("scopeName") != "source.rrf-gcode" or not grammar.get("patterns"):
            problems.append("the grammar has no scopeName source.rrf-gcode or no patterns")
        if config.get("comments", {}).get("lineComment") != ";":
            problems.append("the language configuration has no ; line comment")
        langs = manifest["contributes"]["languages"]
        if [l["id"] for l in langs] != ["rrf-gcode"] or langs[0]["extensions"] != [".g"]:
            problems.append("the manifest does not define rrf-gcode for .g files")
if problems:
    sys.exit("vscode: " + vsix + ": " + "; ".join(problems))
print(f"vscode: {vsix}: {len(names)} files, version {manifest['version']}, grammar and language configuration parse")
PY
echo "vscode: built editors/vscode/$vsix"
