#!/usr/bin/env bash
# Set up, build, and run afntool on the bundled example sequence; results go to ./out/demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out/demo
T=build/cli/afntool
$T --info examples/sequence/frame.0000.exr
$T --preview out/demo/frame0000-preview.png examples/sequence/frame.0000.exr
$T --contact-sheet out/demo/frame0000-aovs.png examples/sequence/frame.0000.exr
echo "afn demo: outputs in out/demo"
ls -l out/demo
