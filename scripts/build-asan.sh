#!/usr/bin/env bash
# Configure and build afn with AddressSanitizer + UndefinedBehaviorSanitizer and the libFuzzer
# targets (tests/fuzz) into ./build-asan, with clang, at -O1 (compiles in about half the time of
# -O3 and keeps the sanitizers' reports exact). Extra arguments go to cmake's configure step
# (e.g. -DAFN_SANITIZERS=undefined for a faster fuzzing build in another folder, set with
# AFN_ASAN_BUILD_DIR). AFN_ASAN_TARGETS names the targets to build (default: all; scripts/test-asan.sh
# builds afn_sanitizer_suite, the unit and stress test programs and the fuzz targets).
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${AFN_ASAN_BUILD_DIR:-build-asan}
CC=clang CXX=clang++ cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DAFN_BUILD_FUZZERS=ON \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DCMAKE_C_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DAFN_BUILD_BENCHMARKS=OFF -DAFN_DEVICE_CUDA=OFF "$@" >/dev/null
cmake --build "$dir" -j"${AFN_JOBS:-2}" ${AFN_ASAN_TARGETS:+--target $AFN_ASAN_TARGETS}
