#!/bin/sh
# run.sh: the main job of `make run`: the default suite of `aabench run`
# (every method family at its main settings on crow 256x256 and 1024x1024).
set -eu
build/aabench run --suite default
