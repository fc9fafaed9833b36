#!/usr/bin/env bash
# Set up, build, and denoise the bundled example sequence (8 Blender Cycles frames, 1 spp) with afn's
# default method, score it against the 2048-spp references, and write previews; results in ./out/demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
rm -rf out/demo && mkdir -p out/demo
T=build/cli/afntool
SEQ=examples/sequence
# AFN when the build embeds trained weights (weights/afn.afnw), else SVGF.
METHOD=svgf
if [[ $'\n'"$($T --methods)" == *$'\n'"afn ready "* ]]; then METHOD=afn; fi
$T --info $SEQ/frame.0000.exr
echo "== denoising frames 0-7 with '$METHOD' and comparing with the references"
$T --frames 0-7 $SEQ/frame.####.exr --denoise:method=$METHOD -o out/demo/denoised.####.exr \
   --compare $SEQ/reference.####.exr
echo "== the 1-spp input against the same references"
$T --frames 0-7 $SEQ/frame.####.exr --compare $SEQ/reference.####.exr
$T $SEQ/frame.0007.exr --preview out/demo/noisy.0007.png
$T out/demo/denoised.0007.exr --preview out/demo/denoised.0007.png
$T $SEQ/reference.0007.exr --preview out/demo/reference.0007.png
$T --contact-sheet out/demo/aovs.0000.png $SEQ/frame.0000.exr
echo "afn demo: outputs in out/demo"
ls -l out/demo
