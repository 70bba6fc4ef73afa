#!/bin/sh
# readme-figures.sh: the README's montage and error-against-time plot.
# Runs the default suite into build/readme-run and copies the two figures
# into results/readme/ (committed).  Run from the repository's top level
# after `make`.
set -eu
build/aabench run --suite default --out build/readme-run -q
mkdir -p results/readme
cp build/readme-run/montage.png results/readme/montage.png
cp build/readme-run/plots/error_vs_time.png results/readme/error_vs_time.png
cp build/readme-run/plots/convergence.png results/readme/convergence.png
cp build/readme-run/results.csv results/readme/results.csv
echo "results/readme/: montage.png, error_vs_time.png, convergence.png, results.csv"
