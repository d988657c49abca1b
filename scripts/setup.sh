#!/usr/bin/env bash
# Installs the Debian packages matpoint needs (only those missing), then builds Release into build/.
# Safe to run again: it installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

packages=(build-essential cmake libeigen3-dev nlohmann-json3-dev libcli11-dev libfmt-dev libhdf5-dev
          libgtest-dev libgmock-dev libbenchmark-dev
          python3 python3-matplotlib python3-numpy python3-meshio)

# Command output goes to a log: quiet when all is well, shown in full when something fails.
log=$(mktemp)
trap 'rm -f "$log"' EXIT

missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo=(sudo)
    else
      echo "setup: need root (or sudo) to install: ${missing[*]}" >&2
      exit 1
    fi
  fi
  apt=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -q -y)
  if ! { "${apt[@]}" update && "${apt[@]}" install --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
    cat "$log" >&2
    echo "setup: package installation failed (output above)" >&2
    exit 1
  fi
fi

echo "setup: building Release into build/"
if ! { cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j"$(nproc)"; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "setup: build failed (output above)" >&2
  exit 1
fi
echo "setup: build/matpoint is ready"
