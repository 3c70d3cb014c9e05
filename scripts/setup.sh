#!/usr/bin/env bash
# Installs rrflint's build and test dependencies from Debian packages.
# Idempotent: does nothing when everything is present. Works as root or through sudo.
#   scripts/setup.sh          build dependencies
#   scripts/setup.sh --test   build + test dependencies (with node and npm for the VS Code extension)
set -euo pipefail

pkgs=(cmake make g++ pkg-config libfmt-dev nlohmann-json3-dev catch2 libcli11-dev libtomlplusplus-dev)
if [[ "${1:-}" == "--test" ]]; then
  pkgs+=(python3 python3-jsonschema git pre-commit clang-format-14)
  # tests/clients/: the language server in real editors (neovim 0.7 headless, Emacs 28 with eglot in batch mode)
  pkgs+=(neovim emacs-nox elpa-eglot)
  # The VS Code extension's build (scripts/vscode.sh, ctest -L vscode); a node from elsewhere brings its own npm.
  command -v npm >/dev/null 2>&1 || pkgs+=(nodejs npm)
  pkgs+=(dpkg-dev file groff-base man-db)  # tests/install_test.sh: cpack's .deb (dpkg-shlibdeps, file), the man page
  pkgs+=(g++-mingw-w64-x86-64-posix wine64 zip unzip)  # scripts/windows.sh: the Windows build, zipped, run under wine
  pkgs+=(clang-14 libclang-rt-14-dev)  # scripts/fuzz.sh: the libFuzzer targets (clang 14, libFuzzer, ASan, UBSan)
fi
if [[ "${1:-}" == "--bench" ]]; then
  pkgs+=(libbenchmark-dev hyperfine)
  command -v npm >/dev/null 2>&1 || pkgs+=(npm)
fi

missing=()
for p in "${pkgs[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

if [[ $(id -u) -eq 0 ]]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "setup: need root or sudo to install: ${missing[*]}" >&2
  exit 2
fi
echo "setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
