#!/usr/bin/env bash
# Builds the whole project with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and
# runs the full test suite there (issue 8). Any sanitizer report fails the test that triggered it.
#
#   scripts/sanitize.sh [ctest arguments...]      e.g. scripts/sanitize.sh -R Fmpm
#
# Takes about 4-6 times the time of scripts/test.sh.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh >/dev/null
log=$(mktemp)
trap 'rm -f "$log"' EXIT
echo "sanitize: building build-asan/ (ASan + UBSan, RelWithDebInfo)"
if ! { cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMATPOINT_SANITIZE=ON \
         -DMATPOINT_BUILD_BENCHMARKS=OFF && cmake --build build-asan -j"$(nproc)"; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "sanitize: build failed (output above)" >&2
  exit 1
fi
# halt_on_error: the first report ends the test with a failure; leaks are reports too.
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir build-asan --output-on-failure -j2 "$@"
