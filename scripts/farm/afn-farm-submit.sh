#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Submit afn-slurm.sbatch as a job array with one task per chunk of the shot (docs/farm.md).
# Usage: afn-farm-submit.sh --frames A-B [--chunk N] [--preroll N] [--method M] [--afntool PATH]
#          [--args "AFNTOOL ARGS"] INPUT.####.exr OUTPUT.####.exr [-- SBATCH ARGS...]
# Prints the job id (sbatch --parsable).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
usage() { sed -n '3,6p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }

frames="" chunk=20 preroll=8 method=afn tool=${AFNTOOL:-afntool} args="" files=()
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --chunk) chunk=$2; shift 2 ;;
    --preroll) preroll=$2; shift 2 ;;
    --method) method=$2; shift 2 ;;
    --afntool) tool=$2; shift 2 ;;
    --args) args=$2; shift 2 ;;
    --) shift; break ;;
    -h|--help) usage ;;
    *) files+=("$1"); shift ;;
  esac
done
[ ${#files[@]} -eq 2 ] || usage
if ! [[ $frames =~ ^(-?[0-9]+)-(-?[0-9]+)$ ]]; then
  echo "afn-farm-submit: --frames expects A-B, got '$frames'" >&2
  exit 2
fi
first=${BASH_REMATCH[1]} last=${BASH_REMATCH[2]}
if ! [[ $chunk =~ ^[0-9]+$ && $preroll =~ ^[0-9]+$ ]] || [ "$chunk" -lt 1 ] || [ "$last" -lt "$first" ]; then
  echo "afn-farm-submit: need A <= B, --chunk >= 1 and --preroll >= 0" >&2
  exit 2
fi
tasks=$(( (last - first + chunk) / chunk ))

export AFN_INPUT=${files[0]} AFN_OUTPUT=${files[1]} AFN_FIRST=$first AFN_LAST=$last
export AFN_CHUNK=$chunk AFN_PREROLL=$preroll AFN_METHOD=$method AFNTOOL=$tool AFN_ARGS=$args
exec sbatch --parsable --array="0-$((tasks - 1))" --export=ALL "$@" "$here/afn-slurm.sbatch"
