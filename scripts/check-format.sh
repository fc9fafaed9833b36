#!/usr/bin/env bash
# Fail when a tracked C/C++ file differs from what clang-format makes of it with the repository's
# .clang-format (clang-format 14, Debian's). Fix with: git ls-files '*.cpp' '*.h' '*.hpp' '*.c' '*.cu' '*.cuh' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check-format: clang-format is not installed"; exit 1; }
bad=()
while IFS= read -r f; do
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(git ls-files '*.cpp' '*.h' '*.hpp' '*.c' '*.cu' '*.cuh')
if [ ${#bad[@]} -gt 0 ]; then
  echo "check-format: ${#bad[@]} file(s) not formatted with .clang-format:"; printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "check-format: all C/C++ files formatted"
