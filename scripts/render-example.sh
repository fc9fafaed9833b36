#!/usr/bin/env bash
# Re-render the bundled example sequence and the small test EXR with Blender Cycles (CPU).
# Usage: scripts/render-example.sh [--ref-spp N] [--only sequence|testdata]
# Writes examples/sequence/frame.NNNN.exr (8 frames, 320x180, 1 spp, all passes),
# examples/sequence/reference.NNNN.exr (Combined only, float, N spp; default 2048) and
# tests/data/blender_64x36.exr, then checks them (passes present, Vector not zero, Depth bg 1e10).
set -euo pipefail
cd "$(dirname "$0")/.."
REF_SPP=2048
ONLY=""
while [ $# -gt 0 ]; do
  case "$1" in
    --ref-spp) REF_SPP="$2"; shift 2 ;;
    --only) ONLY="$2"; shift 2 ;;
    *) echo "render-example.sh ERROR: unknown argument $1" >&2; exit 2 ;;
  esac
done
command -v blender >/dev/null || bash scripts/setup.sh --blender
SCRIPT=examples/blender/render_example.py
CHECK="/usr/bin/python3 examples/blender/check_exr.py --expect-motion"
run_blender() {
  blender -b --factory-startup --python-exit-code 1 --python "$SCRIPT" -- "$@" \
    | grep --line-buffered '^afn:\|Error\|ERROR'
}

if [ -z "$ONLY" ] || [ "$ONLY" = testdata ]; then
  tmp=$(mktemp -d)
  run_blender --out "$tmp" --frames 3 --only-frames 1 --width 64 --height 36 --spp 4 \
    --kinds noisy --noisy-name blender_64x36 --seed 3
  $CHECK "$tmp/blender_64x36.0001.exr"
  mv "$tmp/blender_64x36.0001.exr" tests/data/blender_64x36.exr
  rm -rf "$tmp"
fi

if [ -z "$ONLY" ] || [ "$ONLY" = sequence ]; then
  out=examples/sequence
  mkdir -p "$out"
  rm -f "$out"/frame.*.exr "$out"/reference.*.exr "$out"/render-times.json
  start=$(date +%s)
  run_blender --out "$out" --frames 8 --width 320 --height 180 --spp 1 --ref-spp "$REF_SPP" --seed 1
  echo "render-example: sequence rendered in $(( $(date +%s) - start )) s"
  $CHECK "$out"/frame.*.exr
  $CHECK --reference "$out"/reference.*.exr
  du -sh "$out"
fi
