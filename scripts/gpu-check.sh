#!/usr/bin/env bash
# The GPU check of the CUDA afn filter, for a machine with an NVIDIA GPU of compute capability 9.0
# or newer: first the parity tests (the CUDA filter against the CPU filter in the same process, on
# synthetic sequences and on the bundled Blender renders; limit 200 s), then the benchmark (limit 150 s); a crash in the benchmark cannot lose the parity
# results, which are written first. Not yet run on a GPU: docs/gpu.md has the command to run. Logs go to $OUT when it is set, else to out/gpu-check:
#   gpu.txt      nvidia-smi's view of the GPU and driver
#   parity.log   every parity line (per case and frame: PSNR, mean, 99.9% and max |dT|, TA match)
#   parity.xml   GoogleTest's report
#   bench.log    the benchmark's output; bench.csv its table
#   summary.txt  what is printed last: the verdict of each part and the timing table
# Usage: scripts/gpu-check.sh [--prebuilt DIR]
#   --prebuilt DIR  run the binaries of scripts/make-gpu-bundle.sh in DIR (nothing is built)
#   otherwise       build them first into build-gpu (needs the build dependencies and CUDA)
# Exit status: 0 both parts passed; 77 no usable GPU (both parts skipped; the summary says "no GPU,
# skipped"); 1 anything else (a failure, a timeout, or one part skipped and not the other).
set -uo pipefail
cd "$(dirname "$0")/.."
bin=""
while [ $# -gt 0 ]; do
  case "$1" in
    --prebuilt) bin=${2:?--prebuilt needs a folder}; shift 2 ;;
    *) echo "usage: scripts/gpu-check.sh [--prebuilt DIR]" >&2; exit 2 ;;
  esac
done
out=${OUT:-out/gpu-check}
mkdir -p "$out"

if [ -z "$bin" ]; then
  bash scripts/make-gpu-bundle.sh build-gpu/bundle build-gpu || exit 1
  bin=build-gpu/bundle
fi
bin=$(cd "$bin" && pwd)
export LD_LIBRARY_PATH="$bin${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# The bundle's real renders for the parity test (scripts/dump-gpu-frames.py).
if [ -d "$bin/frames" ]; then
  export AFN_GPU_FRAMES="$bin/frames"
fi

{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  [ -f "$bin/MANIFEST" ] && sed -n 's/^commit: /bundle commit: /p' "$bin/MANIFEST"
  if command -v nvidia-smi >/dev/null; then
    nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv
  else
    echo "nvidia-smi: not found"
  fi
} >"$out/gpu.txt" 2>&1
cat "$out/gpu.txt"

echo "== parity: CUDA filter against the CPU filter =="
timeout -k 10 200 "$bin/test_afn_cuda" --gtest_output="xml:$out/parity.xml" 2>&1 | tee "$out/parity.log"
parity=${PIPESTATUS[0]}

echo "== benchmark =="
timeout -k 10 150 "$bin/bench_afn_cuda" --csv "$out/bench.csv" 2>&1 | tee "$out/bench.log"
bench=${PIPESTATUS[0]}

verdict() {
  case "$1" in
    0) echo "passed" ;;
    77) echo "skipped (no usable GPU)" ;;
    124 | 137) echo "TIMED OUT (exit $1)" ;;
    *) echo "FAILED (exit $1)" ;;
  esac
}
# Skipped parity tests (no usable GPU) fail the check: it exists to run them.
if [ "$parity" -eq 0 ] && grep -q '^\[  SKIPPED \]' "$out/parity.log"; then
  parity=77
fi
{
  echo
  echo "== gpu-check summary =="
  cat "$out/gpu.txt"
  echo "parity: $(verdict "$parity"); $(grep -m1 -E '^\[  PASSED  \]' "$out/parity.log" || echo 'no test passed')"
  grep -E '^\[  (FAILED|SKIPPED) \] [A-Za-z_.]+$' "$out/parity.log" | sort -u | head -n 20
  grep -m1 'skipped (' "$out/parity.log" || true
  # The worst frame of each parity case (lowest PSNR), one line each.
  awk -F': ' '/^\[ parity \]/ {
      split($1, a, " frame "); name = a[1]; sub(/^\[ parity \] /, "", name);
      match($2, /PSNR\(T\) [-0-9.einf]+/); v = substr($2, RSTART + 8, RLENGTH - 8);
      p = (v ~ /inf/) ? 1e9 : v + 0;
      if (!(name in worst) || p < worst[name]) { worst[name] = p; line[name] = $2 }
      if (!(name in order)) { order[name] = ++n; names[n] = name } }
    END { for (i = 1; i <= n; ++i) printf "  %-60s %s\n", names[i], line[names[i]] }' \
    "$out/parity.log" | cut -c1-220
  echo "benchmark: $(verdict "$bench")"
  sed -n '/^size /,$p' "$out/bench.log"
} | tee "$out/summary.txt"

if [ "$parity" -eq 77 ] && [ "$bench" -eq 77 ]; then
  echo "gpu-check: no GPU, skipped (nothing was measured)" | tee -a "$out/summary.txt"
  exit 77
fi
[ "$parity" -eq 0 ] && [ "$bench" -eq 0 ]
