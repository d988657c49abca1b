#!/usr/bin/env bash
# Installs what is missing, builds Release and runs the whole test suite (extra arguments go to ctest).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
status=0
ctest --test-dir build --output-on-failure -j2 "$@" || status=$?
exit "$status"
