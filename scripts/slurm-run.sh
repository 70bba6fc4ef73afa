#!/bin/sh
# slurm-run.sh: an aabench run cut into shards on a Slurm cluster: a job
# that computes the references once, a job array of one task per shard
# after it, and a merge job after the array, all through
# scripts/slurm-shards.sbatch.
#
#   sh scripts/slurm-run.sh [--shards N] [--aabench PATH] [--sbatch "OPTIONS"]
#       [--wait] RUN-OPTIONS... --cache SHARED/CACHE --out SHARED/DIR
#
# RUN-OPTIONS are `aabench run`'s own (--suite quick, -p, -m, --reps, ...).
# DIR, the cache and the program must be on a file system every node sees.
#
#   --shards N        tasks of the array (default 4)
#   --aabench PATH    the program (default: $AABENCH, else build/aabench)
#   --sbatch OPTIONS  more sbatch options for every job (--partition=...,
#                     --time=..., --cpus-per-task=...)
#   --wait            wait for the merge; its exit status is this script's
#
# The jobs' logs go to DIR/slurm/.  Exit status: 0 submitted (with --wait:
# the merge's status: 0, or 1 when some cases failed), 2 bad usage, 3 the
# merge did not finish.
set -eu

root=$(cd "$(dirname "$0")/.." && pwd)
shards=4
out=""
suite=default
cache=""
sbopts=""
wait=""
aabench=${AABENCH:-$root/build/aabench}
n=$#
while [ "$n" -gt 0 ]; do
    a=$1
    shift
    n=$((n - 1))
    case $a in
    --shards | --aabench | --out | --suite | --sbatch | --cache)
        [ "$n" -gt 0 ] || { echo "slurm-run.sh: $a needs a value" >&2; exit 2; }
        v=$1
        shift
        n=$((n - 1))
        case $a in
        --shards) shards=$v ;;
        --aabench) aabench=$v ;;
        --out) out=$v ;;
        --sbatch) sbopts=$v ;;
        --suite) suite=$v; set -- "$@" --suite "$v" ;;
        --cache) cache=$v; set -- "$@" --cache "$v" ;;
        esac
        ;;
    --wait) wait=1 ;;
    --shard | --shard=* | --resume | --resume=*)
        echo "slurm-run.sh: $a is given by the driver" >&2
        exit 2
        ;;
    -h | --help)
        sed -n "2,21p" "$0" | sed "s/^# \{0,1\}//"
        exit 0
        ;;
    *) set -- "$@" "$a" ;;
    esac
done
[ -n "$out" ] || { echo "slurm-run.sh: --out DIR is required" >&2; exit 2; }
case $shards in '' | *[!0-9]* | 0) echo "slurm-run.sh: --shards takes a count" >&2; exit 2 ;; esac
command -v sbatch >/dev/null 2>&1 || { echo "slurm-run.sh: sbatch is missing" >&2; exit 2; }
[ -x "$aabench" ] || { echo "slurm-run.sh: no program $aabench" >&2; exit 2; }
case $aabench in /*) ;; *) aabench=$(pwd)/$aabench ;; esac
mkdir -p "$out/slurm"
out=$(cd "$out" && pwd)
rm -f "$out/merge.exit"
script=$root/scripts/slurm-shards.sbatch
export AABENCH="$aabench" AABENCH_SUITE="$suite" AABENCH_SHARDS="$shards"
# shellcheck disable=SC2086 # $sbopts is words
warm=$(sbatch --parsable $sbopts --job-name=aabench-warm --output="$out/slurm/warm-%j.log" \
    "$script" warm "$out" "$@")
# shellcheck disable=SC2086
# a failed references job cancels the rest (--kill-on-invalid-dep)
array=$(sbatch --parsable $sbopts --job-name=aabench-shard --dependency="afterok:$warm" \
    --kill-on-invalid-dep=yes \
    --array="1-$shards" --output="$out/slurm/shard-%A_%a.log" "$script" shard "$out" "$@")
merge_cache=""
[ -n "$cache" ] && merge_cache="--cache $cache"
# shellcheck disable=SC2086
merge=$(sbatch --parsable $sbopts --job-name=aabench-merge --dependency="afterany:$array" \
    --kill-on-invalid-dep=yes \
    --output="$out/slurm/merge-%j.log" "$script" merge "$out" $merge_cache)
echo "slurm-run.sh: references job $warm, shards job array $array (1-$shards), merge job $merge"
echo "slurm-run.sh: logs in $out/slurm/, results in $out/results.csv after job $merge"
[ -n "$wait" ] || exit 0
while [ -n "$(squeue -h -j "$warm,$array,$merge" 2>/dev/null)" ]; do
    sleep 2
done
if [ ! -f "$out/merge.exit" ]; then
    echo "slurm-run.sh: the merge job $merge did not finish (see $out/slurm/)" >&2
    exit 3
fi
cat "$out"/slurm/merge-*.log
exit "$(cat "$out/merge.exit")"
