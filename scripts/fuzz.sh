#!/usr/bin/env bash
# Run the libFuzzer targets of an AFN_BUILD_FUZZERS build (scripts/build-asan.sh) for a bounded
# time each, starting from their committed corpora (tests/fuzz/corpus/<target>, only read: new
# inputs go to <work>/<target>/corpus). Exits non-zero when a target finds a crash, a sanitizer
# report, a leak, a timeout or a violated property; the input is kept in <work>/<target>/artifacts
# and the target's output in <work>/<target>/log.txt.
# Usage: scripts/fuzz.sh [--seconds N] [--work DIR] [--build DIR] [TARGET ...]   (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=20
work=out/fuzz
build=build-asan
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$build"/tests/fuzz/fuzz_*; do
    [ -f "$f" ] && [ -x "$f" ] && targets+=("$(basename "$f")")
  done
fi
if [ ${#targets[@]} -eq 0 ]; then
  echo "fuzz: no fuzz targets in $build/tests/fuzz (build them with scripts/build-asan.sh)" >&2
  exit 1
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
status=0
for t in "${targets[@]}"; do
  dir=$work/$t
  rm -rf "$dir"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  start=$(date +%s)
  if "$build/tests/fuzz/$t" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2560 \
      -print_final_stats=1 -artifact_prefix="$dir/artifacts/" \
      "$dir/corpus" "tests/fuzz/corpus/$t" >"$dir/log.txt" 2>&1; then
    result=clean
  else
    result=FAILED
    status=1
  fi
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log.txt" | tail -1)
  seeds=$(find "tests/fuzz/corpus/$t" -type f | wc -l)
  printf 'fuzz: %-20s %-6s %10s executions in %4ss (%s committed inputs, %s new)\n' "$t" "$result" \
    "${execs:-?}" "$(( $(date +%s) - start ))" "$seeds" "$(find "$dir/corpus" -type f | wc -l)"
  if [ "$result" = FAILED ]; then
    grep -E "ERROR|property violated|runtime error|SUMMARY" "$dir/log.txt" | head -5 >&2 || true
    echo "fuzz: $t: input kept in $dir/artifacts, log in $dir/log.txt" >&2
  fi
done
exit $status
