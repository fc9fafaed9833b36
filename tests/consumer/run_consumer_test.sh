#!/usr/bin/env bash
# Install afn from the build tree into a temporary prefix, then build and run a find_package consumer.
set -euo pipefail
build_dir=$1; source_dir=$2; shift 2
# Further arguments go to the consumer's configure step (the compiler, sanitizer link flags).
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cmake --install "$build_dir" --prefix "$tmp/prefix" >/dev/null
test -x "$tmp/prefix/bin/afntool"
test -f "$tmp/prefix/include/afn/afn.h"
test -f "$tmp/prefix/share/afn/ocio/config.ocio"
cmake -S "$source_dir/tests/consumer" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" "$@" >/dev/null
cmake --build "$tmp/build" >/dev/null
LD_LIBRARY_PATH="$tmp/prefix/lib:${LD_LIBRARY_PATH:-}" "$tmp/build/consumer"
# The installed afntool runs without LD_LIBRARY_PATH (install RPATH) and finds a colour config with
# nothing set (the lookup of the config installed beside the library is tested in test_color_config).
OCIO= "$tmp/prefix/bin/afntool" --version
OCIO= "$tmp/prefix/bin/afntool" "$source_dir/tests/data/blender_64x36.exr" --preview "$tmp/preview.png"
test -s "$tmp/preview.png"
