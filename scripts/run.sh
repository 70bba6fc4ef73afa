#!/bin/sh
# run.sh: the main job of `make run`.
# Until the benchmark exists: the reference image of `crow` at 256x256 (box).
set -eu
mkdir -p results
build/aabench truth -p crow -s 256x256 -o results/crow-256-box.exr
build/aabench truth -p crow -s 256x256 -o results/crow-256-box.png
echo "reference images of crow: results/crow-256-box.exr (linear float), results/crow-256-box.png (sRGB)"
