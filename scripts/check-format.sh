#!/usr/bin/env bash
# Fail when a tracked C/C++ file differs from what clang-format makes of it with the repository's
# .clang-format (clang-format 14, Debian's). Fix with: git ls-files '*.cpp' '*.h' '*.hpp' '*.c' '*.cu' '*.cuh' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check-format: clang-format is not installed"; exit 1; }
# Files in batches, two clang-format processes at a time; each unformatted file is named in an
# "error: code should be clang-formatted" line.
status=0
out=$(git ls-files -z '*.cpp' '*.h' '*.hpp' '*.c' '*.cu' '*.cuh' \
  | xargs -0 -P"${AFN_JOBS:-2}" -n 40 clang-format --dry-run -Werror 2>&1 >/dev/null) || status=$?
mapfile -t bad < <(printf '%s\n' "$out" \
  | sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)
if [ ${#bad[@]} -gt 0 ]; then
  echo "check-format: ${#bad[@]} file(s) not formatted with .clang-format:"; printf '  %s\n' "${bad[@]}"
  exit 1
fi
if [ "$status" -ne 0 ]; then
  echo "check-format: clang-format failed:"; printf '%s\n' "$out" | head -20
  exit 1
fi
echo "check-format: all C/C++ files formatted"
