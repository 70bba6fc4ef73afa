#!/bin/sh
# bench.sh BUILD: the speed measurements of `make bench`.
set -eu
build=$1
echo "== ground truth (reference image), crow; medians of repeated renders =="
"$build/bench_truth" -p crow -s 1024x1024,4096x4096 -f "box;tent:r=0.5;tent:r=1;gauss" -t 1,2
echo
echo "== pathological scenes: thousands of edges in a pixel (reference and area) =="
"$build/bench_patho" -t 1,2
echo
echo "== methods and peers, crow 1024x1024 box; memory at 4096x4096 =="
"$build/bench_methods" -p crow -s 1024x1024 -f box -r 15 -m 4096x4096
