#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The plugin bundle in the build tree and once installed (cmake --install, component afn_ofx, into
# a temporary prefix) must both pass check_bundle.py.
# Usage: check_bundle.sh CMAKE BUILD_DIR BUNDLE_DIR PYTHON
set -euo pipefail
cmake=$1 build=$2 bundle=$3 python=$4
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$cmake" --install "$build" --prefix "$tmp" --component afn_ofx >/dev/null
installed=$(find "$tmp" -type d -path '*/OFX/Plugins/afn.ofx.bundle')
if [[ -z "$installed" ]]; then
  echo "check_bundle ERROR: no <libdir>/OFX/Plugins/afn.ofx.bundle under the install prefix" >&2
  exit 1
fi
"$python" "$here/check_bundle.py" "$bundle" "$installed"
