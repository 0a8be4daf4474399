#!/usr/bin/env bash
# The sanitizer stage of CI (.ci/run): clang++ builds the library, the CLI, the tests and the
# libFuzzer harnesses with AddressSanitizer, UBSan (aborting on undefined behaviour) and coverage
# instrumentation (-DVOXREMESH_FUZZ=ON, cmake/Fuzzing.cmake); the whole test suite runs under
# them; then each harness fuzzes a scratch copy of its seeds for FUZZ_SECONDS (default 60).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
seconds="${FUZZ_SECONDS:-60}"
build=build-sanitize

CC=clang CXX=clang++ cmake -S . -B "$build" -DVOXREMESH_FUZZ=ON -DVOXREMESH_BUILD_TESTS=ON
cmake --build "$build" -j2
ctest --test-dir "$build" -j2 --output-on-failure

export LSAN_OPTIONS="suppressions=$root/tests/fuzz/lsan_suppressions.txt"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
for harness in "$build"/bin/fuzz_*; do
  name="$(basename "$harness")"
  seeds="$root/tests/fuzz/seeds/${name#fuzz_}"
  corpus="$scratch/${name#fuzz_}"
  mkdir -p "$corpus"
  cp -r "$seeds"/. "$corpus"/
  echo "ci_sanitizers: $name fuzzes for $seconds s"
  (cd "$scratch" && "$root/$harness" -max_total_time="$seconds" -rss_limit_mb=2048 "$corpus")
done
echo "ci_sanitizers: done"
