#!/usr/bin/env bash
# Set up, build with ASan + UBSan (scripts/build-asan.sh) and run the unit and stress suites and
# the replay of every fuzz target's committed corpus there (ctest labels unit, stress and fuzz).
# Any sanitizer report fails the run.
# Left to the normal build's run (scripts/test.sh): the soak cases (label soak, the 10,000-frame
# EveryMethod/LongRuns.* suites: the same per-frame code paths the determinism and adversarial
# suites run here, repeated), the end-to-end afntool and plugin suites (labels integration and
# plugin: the afntool and plugin code they drive runs here through the stress suites' afntool and
# plugin determinism and corrupt-file cases and the fuzz targets) and the CMake package consumer.
# AFN_ASAN_ALL=1 builds everything and runs the whole suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --sanitizers
labels=(-L '^(unit|stress|fuzz)$')
if [ -n "${AFN_ASAN_ALL:-}" ]; then
  labels=()
  bash scripts/build-asan.sh
else
  AFN_ASAN_TARGETS=afn_sanitizer_suite bash scripts/build-asan.sh
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
(cd build-asan && ctest --output-on-failure -j"${AFN_JOBS:-2}" "${labels[@]}")
