#!/usr/bin/env bash
# Build the CUDA afn filter's GPU test and benchmark on this machine (a CUDA compiler is needed, a
# GPU is not) and put them, with the oneTBB runtime they link, into one folder that runs on a GPU
# machine without any build tools: bash scripts/gpu-check.sh --prebuilt DIR.
# Usage: scripts/make-gpu-bundle.sh [DIR (default gpu-bundle)] [BUILD_DIR (default build-gpu)]
# The binaries link statically everything but oneTBB, libstdc++, libgcc_s, libm and libc; the
# CUDA runtime is static and needs only the NVIDIA driver there.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-gpu-bundle}
build=${2:-build-gpu}

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DAFN_DEVICE_CUDA=ON >/dev/null
cmake --build "$build" -j"${AFN_JOBS:-2}" --target test_afn_cuda bench_afn_cuda

rm -rf "$out"
mkdir -p "$out"
cp "$build/tests/test_afn_cuda" "$build/bench/bench_afn_cuda" "$out/"
strip --strip-unneeded "$out/test_afn_cuda" "$out/bench_afn_cuda"

# oneTBB under its soname, and a check that nothing else outside the C/C++ runtime is needed.
allowed='^(linux-vdso|libtbb|libstdc\+\+|libm|libgcc_s|libc|ld-linux-x86-64)\.so'
for bin in "$out/test_afn_cuda" "$out/bench_afn_cuda"; do
  while read -r lib _ path _; do
    lib=$(basename "$lib")
    if ! [[ $lib =~ $allowed ]]; then
      echo "make-gpu-bundle: $bin needs $lib, which the GPU machine does not have" >&2
      exit 1
    fi
    if [[ $lib == libtbb.so* && ! -e "$out/$lib" ]]; then
      cp -L "$path" "$out/$lib"
    fi
  done < <(ldd "$bin" | sed -n 's/^[[:space:]]*\([^ ]*\)\( => \([^ ]*\)\)\{0,1\}.*/\1 x \3 y/p')
done
ls "$out"/libtbb.so.* >/dev/null

# Real renders for the parity test (CudaAfn.ParityOnTheBlenderSequence): the bundled sequence's
# first 4 frames as raw planes (OpenImageIO is read here, not on the GPU machine).
/usr/bin/python3 scripts/dump-gpu-frames.py examples "$out/frames" 4

{
  echo "afn GPU bundle"
  echo "commit: $(git rev-parse HEAD 2>/dev/null || echo unknown)$(git diff --quiet 2>/dev/null || echo ' (with uncommitted changes)')"
  echo "built: $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(uname -m), $(ldd --version | head -n1)"
  echo "nvcc: $("$(grep -m1 '^CMAKE_CUDA_COMPILER:' "$build/CMakeCache.txt" | cut -d= -f2)" --version | tail -n1)"
  echo "run: bash scripts/gpu-check.sh --prebuilt $out"
  (cd "$out" && sha256sum test_afn_cuda bench_afn_cuda libtbb.so.* frames/*)
} >"$out/MANIFEST"
du -sh "$out"
echo "make-gpu-bundle: wrote $out (run there: bash scripts/gpu-check.sh --prebuilt $out)"
