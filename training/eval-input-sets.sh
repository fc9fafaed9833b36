#!/bin/bash
# SPDX-License-Identifier: Apache-2.0
# afn per input combination on the held-out sequences of a generated dataset
# (docs/afn-evaluation.md): each combination is made from the full files by unbinding the other
# passes (afntool --aov ROLE=none), denoised by the model afn chooses for it, and compared with
# the sequence's clean reference (afntool --compare; PSNR/SSIM on T(x), docs/metrics.md).
#   bash eval-input-sets.sh DATA AFNTOOL [SPP] [--weights-color F] [--weights-albedo-normal F]
#                           [--weights-all F]
# Without --weights-* the built-in models run. Prints a markdown table (mean over frames, then
# over sequences) and writes the per-run JSON in $OUT (default: a temporary folder; runs whose
# JSON is there already are not repeated; CONFIGS="noisy all" runs only those combinations).
set -euo pipefail
data=$1 afntool=$2 spp=${3:-1}
shift $(( $# < 3 ? $# : 3 ))
wcolor="" wan="" wall=""
while [ $# -gt 0 ]; do
  case $1 in
    --weights-color) wcolor=$2; shift 2 ;;
    --weights-albedo-normal) wan=$2; shift 2 ;;
    --weights-all) wall=$2; shift 2 ;;
    *) echo "eval-input-sets.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
none() { for r in "$@"; do printf -- "--aov %s=none " "$r"; done; }
declare -A args=(
  [noisy]=""
  [color]="$(none albedo normal depth motion position) --denoise:method=afn"
  [albedo+normal]="$(none depth motion position) --denoise:method=afn"
  [albedo+normal+depth]="$(none motion position) --denoise:method=afn"
  [all]="--denoise:method=afn"
)
[ -n "$wcolor" ] && args[color]+=" --weights $wcolor"
[ -n "$wan" ] && args[albedo+normal]+=" --weights $wan" && args[albedo+normal+depth]+=" --weights $wan"
[ -n "$wall" ] && args[all]+=" --weights $wall"
order="noisy color albedo+normal albedo+normal+depth all"
seqs=""
for d in "$data"/eval/*/; do
  s=$(basename "$d")
  ls "$d"reference.*.exr > /dev/null 2>&1 && [ -d "$d/spp$spp" ] && seqs+="$s "
done
for s in $seqs; do
  n=$(ls "$data/eval/$s"/reference.*.exr | wc -l)
  for c in ${CONFIGS:-$order}; do
    [ -s "$out/$s.$c.json" ] && continue # a rerun with the same $OUT resumes
    # shellcheck disable=SC2086
    "$afntool" -q --frames 0-$((n - 1)) "$data/eval/$s/spp$spp/frame.####.exr" ${args[$c]} \
      --compare "$data/eval/$s/reference.####.exr" --json > "$out/$s.$c.json"
  done
done
[ -n "${CONFIGS:-}" ] && exit 0
/usr/bin/python3 - "$out" "$order" $seqs <<'PY'
import json, sys
out, order, seqs = sys.argv[1], sys.argv[2].split(), sys.argv[3:]
m = {(s, c): json.load(open(f"{out}/{s}.{c}.json"))["mean"] for s in seqs for c in order}
print("| Inputs | " + " | ".join(f"PSNR `{s}`" for s in seqs) + " | PSNR (avg) | SSIM (avg) |")
print("|---" * (len(seqs) + 3) + "|")
for c in order:
    p = [m[s, c]["psnr"] for s in seqs]
    q = [m[s, c]["ssim"] for s in seqs]
    print(f"| {c} | " + " | ".join(f"{v:.2f}" for v in p)
          + f" | {sum(p) / len(p):.2f} | {sum(q) / len(q):.4f} |")
PY
