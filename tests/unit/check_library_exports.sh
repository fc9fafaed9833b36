#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Fail when a shared library exports a function of one of its own namespaces that its public
# header does not declare: every exported afn:: function must be declared in the header (marked
# with the library's export macro). Usage: check_library_exports.sh LIBRARY HEADER NAMESPACE
set -euo pipefail
lib="$1" header="$2" ns="$3"
[[ -f "$lib" ]] || { echo "library_exports: $lib not found" >&2; exit 1; }
bad=0
while IFS= read -r sym; do
  # afn::io::readFrame(...) -> readFrame; afn::color::ColorManager::views(...) -> ColorManager;
  # f[abi:cxx11](...) (a function returning std::string) -> f
  name=${sym#"$ns::"}; name=${name%%(*}; name=${name%%::*}; name=${name%%\[abi:*}
  if ! grep -qE "\b${name}\b" "$header"; then echo "library_exports: $lib exports $sym" >&2; bad=1; fi
done < <(nm -DC --defined-only "$lib" | awk '$2 == "T" || $2 == "W"' | cut -d' ' -f3- | grep "^$ns::" || true)
[[ $bad -eq 0 ]] || exit 1
n=$(nm -DC --defined-only "$lib" | awk '$2 == "T"' | grep -c "^.* $ns::" || true)
echo "library_exports: $lib exports $n functions, all declared in $(basename "$header")"
