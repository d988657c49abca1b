#!/usr/bin/env bash
# Fuzzes the input reader and validator with libFuzzer for a bounded time (issue 8, "input safety").
#
#   scripts/fuzz.sh [SECONDS]      default 600
#
# Installs clang and its fuzzer/sanitizer runtimes if missing, builds fuzz/fuzz_input with
# AddressSanitizer + UndefinedBehaviorSanitizer into build-fuzz/, seeds the corpus with every
# example input and every malformed input of tests/inputs/bad/, and gives libFuzzer a dictionary
# of the validator's keys and choices (the string literals of src/matpoint/io/input.cpp and io/input/).
# Exit 0 and "no finding" when nothing crashed, hung or tripped a sanitizer; otherwise libFuzzer's
# report and the reproducer file under out/fuzz/. Executions per second are printed at the end.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds=${1:-600}

bash scripts/install_packages.sh clang libclang-rt-14-dev libomp-14-dev cmake libeigen3-dev nlohmann-json3-dev \
  libcli11-dev

log=$(mktemp)
trap 'rm -f "$log"' EXIT
echo "fuzz: building build-fuzz/fuzz_input (clang, libFuzzer, ASan, UBSan)"
if ! { CXX=clang++ CC=clang cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMATPOINT_FUZZ=ON \
         -DMATPOINT_BUILD_TESTS=OFF -DMATPOINT_BUILD_BENCHMARKS=OFF &&
       cmake --build build-fuzz -j"$(nproc)" --target fuzz_input; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "fuzz: build failed (output above)" >&2
  exit 1
fi

work=out/fuzz
mkdir -p "$work/corpus" "$work/findings"
cp examples/*/input.json "$work/corpus/" 2>/dev/null || true
for f in examples/*/input.json tests/inputs/bad/*.json; do
  cp "$f" "$work/corpus/$(echo "$f" | tr '/' '_')"
done
# Dictionary: every quoted identifier-like literal of the validator (keys and choices).
grep -oh '"[a-z_][a-z0-9_+-]*"' src/matpoint/io/input.cpp src/matpoint/io/input/* | sort -u >"$work/input.dict"

echo "fuzz: running for $seconds s on $(ls "$work/corpus" | wc -l) seed inputs"
status=0
ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1 \
  build-fuzz/fuzz_input "$work/corpus" -dict="$work/input.dict" -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=4096 -max_len=16384 -print_final_stats=1 -artifact_prefix="$work/findings/" \
  >"$work/fuzz.log" 2>&1 || status=$?
grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)" "$work/fuzz.log" || true
if ((status != 0)); then
  grep -E "ERROR|SUMMARY|Test unit written" "$work/fuzz.log" | head -20 >&2
  echo "fuzz: FINDING (exit $status); log in $work/fuzz.log, reproducer in $work/findings/" >&2
  exit 1
fi
echo "fuzz: no finding in $seconds s (log in $work/fuzz.log)"
