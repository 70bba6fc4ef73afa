#!/bin/sh
# bench.sh BUILD: the speed measurements of `make bench`.
# Each figure is a median timed by precision: renders after a warm-up until
# the 95% CI of the median is within TARGET_CI percent (default 2) or BUDGET
# seconds (default 1) have passed, at least 5; REPS=N times exactly instead.
# make bench TARGET_CI=1 BUDGET=3 passes them through.  Timings marked * are
# noisy (harness/bench/README.md, "A quiet measurement").
set -eu
build=$1
timing="--target-ci ${TARGET_CI:-2} --budget ${BUDGET:-1}"
if [ -n "${REPS:-}" ]; then
    timing="$timing -r $REPS"
fi
echo "== ground truth (reference image), crow; medians by precision ($timing) =="
# shellcheck disable=SC2086
"$build/bench_truth" -p crow -s 1024x1024,4096x4096 -f "box;tent:r=0.5;tent:r=1;gauss" -t 1,2 $timing
echo
echo "== pathological scenes: thousands of edges in a pixel (reference and area) =="
"$build/bench_patho" -t 1,2
echo
echo "== methods and peers, crow 1024x1024 box; memory at 4096x4096 =="
# shellcheck disable=SC2086
"$build/bench_methods" -p crow -s 1024x1024 -f box $timing -m 4096x4096
echo
echo "== curves: area against point on parabolas, cubic and elliptical arcs 1024x1024 box =="
# shellcheck disable=SC2086
"$build/bench_curves" -s 1024x1024 --target-ci ${TARGET_CI:-2} --budget ${BUDGET:-1} ${REPS:+--reps "$REPS"}
echo
echo "== analytic under its filters against area under the box, crow 1024x1024, one thread =="
# shellcheck disable=SC2086
"$build/bench_analytic" -p crow -s 1024x1024 $timing
echo
echo "== strokes: 1,000 stroked cubic segments 1024x1024, one thread: stroker, box reference, point, area =="
"$build/bench_bezstroke" -s 1024x1024 ${REPS:+-r "$REPS"}
