#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Fail unless the OFX binary's dynamic symbol table defines exactly OfxGetNumberOfPlugins and
# OfxGetPlugin. No C++ runtime symbol is unavoidable here: the version script (plugin/exports.map)
# makes every other symbol local, weak template instantiations and typeinfo included.
set -euo pipefail
binary="$1"
[[ -f "$binary" ]] || { echo "plugin_exports: $binary not found" >&2; exit 1; }
defined=$(nm -D --defined-only "$binary" | awk '{print $NF}' | sort)
expected=$'OfxGetNumberOfPlugins\nOfxGetPlugin'
if [[ "$defined" != "$expected" ]]; then
  echo "plugin_exports: $binary exports unexpected symbols:" >&2
  comm -23 <(echo "$defined") <(echo "$expected") >&2
  echo "missing:" >&2
  comm -13 <(echo "$defined") <(echo "$expected") >&2
  exit 1
fi
echo "plugin_exports: $binary exports only OfxGetNumberOfPlugins and OfxGetPlugin"
