#!/usr/bin/env bash
# Set up, build with ASan + UBSan (scripts/build-asan.sh) and run the whole ctest suite there, the
# replay of every fuzz target's committed corpus included. Any sanitizer report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --sanitizers
bash scripts/build-asan.sh
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
(cd build-asan && ctest --output-on-failure -j"${AFN_JOBS:-2}")
