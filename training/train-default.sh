#!/usr/bin/env bash
# The default AFN training protocol on a dataset made by training/render-dataset (docs/dataset.md),
# sized for a 2-core CPU (a few hours in all); the same commands run on a GPU with --device cuda.
#
#   cd training && bash train-default.sh [DATA] [RESULTS]
#       (defaults $AFN_DATA/afn-default, or ../data/afn-default without AFN_DATA; results)
#
# 1. eval-full:  the evaluation model (variant "full"); never sees the held-out scenes
#                (AFN_HOLDOUT, default moving_light,glass); AFN_EVAL_MINUTES of training.
# 2. ablation:   the four variants of the paper's Table 11 (1spp, ta, fusion, full), each started
#                from eval-full's weights (the tensors it shares) and trained AFN_ABLATION_EPOCHS
#                more epochs on the same scenes at lr 3e-4 (a learning-rate decay step): an equal
#                budget per variant. ablation-full is the evaluation model of the tables.
# 3. ship:       the model to ship, started from ablation/full and trained AFN_SHIP_MINUTES on every
#                scene (the held-out ones included) at lr 3e-4, exported to RESULTS/ship/afn.afnw.
# 4. the tables: RESULTS/afn-evaluation.md (+ .json) from the held-out scenes (ablation/full is the
#                AFN column).
# Nothing in the source tree is written: the shipped weights/afn.afnw and docs/afn-evaluation.*
# change only when you copy the results over them (the script prints the commands at the end).
# AFN_DRY_RUN=1 prints every command instead of running it.
# A finished step is skipped when rerun (RESULTS/NAME/DONE); an interrupted one resumes from its
# checkpoint. Logs: RESULTS/NAME.log (and RESULTS/NAME/log.csv per epoch).
set -euo pipefail
cd "$(dirname "$0")"
DATA=${1:-${AFN_DATA:-../data}/afn-default}
OUT=${2:-results}
HOLDOUT=${AFN_HOLDOUT:-moving_light,glass}
PY=/usr/bin/python3
THREADS=${AFN_THREADS:-0}
common=(--data "$DATA" --threads "$THREADS")
DRY=${AFN_DRY_RUN:-}
# run CMD...: run it, or print it under AFN_DRY_RUN
run() {
  if [ -n "$DRY" ]; then printf '%q ' "$@"; echo; else "$@"; fi
}
run mkdir -p "$OUT"
# step NAME ARGS...: train into $OUT/NAME unless it finished before ($OUT/NAME/DONE)
step() {
  local name=$1; shift
  if [ -f "$OUT/$name/DONE" ]; then echo "   $name: done before"; return; fi
  if [ -n "$DRY" ]; then run $PY -m afn.train "${common[@]}" --out "$OUT/$name" "$@"; return; fi
  $PY -m afn.train "${common[@]}" --out "$OUT/$name" "$@" 2>&1 | tee -a "$OUT/$name.log"
  touch "$OUT/$name/DONE"
}

echo "== 1. eval-full (held out: $HOLDOUT)"
step eval-full --holdout "$HOLDOUT" --minutes "${AFN_EVAL_MINUTES:-40}"

echo "== 2. ablation"
E=${AFN_ABLATION_EPOCHS:-6}
for v in full fusion 1spp ta; do
  step "ablation-$v" --holdout "$HOLDOUT" --variant "$v" --init "$OUT/eval-full/model.afnw" \
      --epochs "$E" --lr 3e-4
done

echo "== 3. ship (all scenes)"
step ship --init "$OUT/ablation-full/model.afnw" --minutes "${AFN_SHIP_MINUTES:-8}" --lr 3e-4
run $PY -m afn.export "$OUT/ship" -o "$OUT/ship/afn.afnw"

echo "== 4. tables"
AFNTOOL=${AFNTOOL:-../build/cli/afntool}
run $PY -m afn.evaluate --data "$DATA" --scenes "$HOLDOUT" --afntool "$AFNTOOL" \
    --weights "$OUT/ablation-full/model.afnw" \
    --ablation "full=$OUT/ablation-full/model.afnw,fusion=$OUT/ablation-fusion/model.afnw,1spp=$OUT/ablation-1spp/model.afnw,ta=$OUT/ablation-ta/model.afnw" \
    --out "$OUT/afn-evaluation.md" --json "$OUT/afn-evaluation.json"

echo "== done. To ship these weights and tables (then rebuild: the weights are embedded):"
echo "   cp $OUT/ship/afn.afnw ../weights/afn.afnw"
echo "   cp $OUT/afn-evaluation.md $OUT/afn-evaluation.json ../docs/"
