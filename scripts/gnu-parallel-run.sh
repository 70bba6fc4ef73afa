#!/bin/sh
# gnu-parallel-run.sh: an aabench run cut into shards that GNU parallel runs,
# on this machine or on machines that share the folder, then merged.
#
#   sh scripts/gnu-parallel-run.sh [--jobs N] [--shards N] [--sshloginfile FILE]
#       [--aabench PATH] RUN-OPTIONS... --out DIR
#
# RUN-OPTIONS are `aabench run`'s own (--suite quick, -p, -m, --reps, ...).
# Each shard K of N runs `aabench run RUN-OPTIONS --shard K/N --out
# DIR/shards/K`; then `aabench merge DIR/shards/* --out DIR` writes the whole
# run's results into DIR, as `aabench run RUN-OPTIONS --out DIR` would.  The
# references are computed first, once (`aabench truth --warm`), into the
# cache the shards share.
#
#   --jobs N            shards run at once on each machine (default: cores)
#   --shards N          parts to cut the run into (default: --jobs, or with
#                       --sshloginfile the machines times their jobs)
#   --sshloginfile FILE GNU parallel's list of machines (user@host, or
#                       N/host for N jobs there); each must see this folder
#                       (DIR, the cache, the program) at the same path
#   --aabench PATH      the program (default: $AABENCH, else build/aabench
#                       beside this script)
#
# A shard that stops (killed, a machine lost) is named; `aabench run --resume
# DIR/shards/K` finishes it and the merge can be run again.  Exit status:
# the merge's (0, or 1 when some cases failed), 2 bad usage, 3 a shard did
# not finish.
set -eu

root=$(cd "$(dirname "$0")/.." && pwd)
jobs=""
shards=""
sshlogin=""
out=""
suite=default
merge=""
aabench=${AABENCH:-$root/build/aabench}
n=$#
while [ "$n" -gt 0 ]; do
    a=$1
    shift
    n=$((n - 1))
    case $a in
    --jobs | --shards | --sshloginfile | --aabench | --out | --suite | --cache)
        [ "$n" -gt 0 ] || { echo "gnu-parallel-run.sh: $a needs a value" >&2; exit 2; }
        v=$1
        shift
        n=$((n - 1))
        case $a in
        --jobs) jobs=$v ;;
        --shards) shards=$v ;;
        --sshloginfile) sshlogin=$v ;;
        --aabench) aabench=$v ;;
        --out) out=$v ;;
        --suite) suite=$v; set -- "$@" --suite "$v" ;;
        --cache) merge="$merge --cache $v"; set -- "$@" --cache "$v" ;;
        esac
        ;;
    --shard | --shard=* | --resume | --resume=*)
        echo "gnu-parallel-run.sh: $a is given by the driver" >&2
        exit 2
        ;;
    -h | --help)
        sed -n '2,27p' "$0" | sed 's/^# \{0,1\}//'
        exit 0
        ;;
    *) set -- "$@" "$a" ;;
    esac
done
[ -n "$out" ] || { echo "gnu-parallel-run.sh: --out DIR is required" >&2; exit 2; }
command -v parallel >/dev/null 2>&1 ||
    { echo "gnu-parallel-run.sh: GNU parallel is missing (apt-get install parallel)" >&2; exit 2; }
[ -x "$aabench" ] || { echo "gnu-parallel-run.sh: no program $aabench (make build/aabench)" >&2; exit 2; }
case $aabench in /*) ;; *) aabench=$(pwd)/$aabench ;; esac
[ -n "$jobs" ] || jobs=$(nproc 2>/dev/null || echo 2)
if [ -z "$shards" ]; then
    shards=$jobs
    if [ -n "$sshlogin" ]; then
        machines=$(grep -c '^[^#[:space:]]' "$sshlogin" || true)
        shards=$((jobs * (machines > 0 ? machines : 1)))
    fi
fi
case $jobs$shards in *[!0-9]*) echo "gnu-parallel-run.sh: --jobs and --shards take counts" >&2; exit 2 ;; esac

mkdir -p "$out/shards"
# the references once, into the shared cache, before any shard starts
if ! printf '%s\n' "$@" | grep -qx -- '--no-cache'; then
    "$aabench" truth --warm "$suite" "$@" --out "$out" -q
fi
remote=""
[ -n "$sshlogin" ] && remote="--sshloginfile $sshlogin --workdir ."
# shellcheck disable=SC2086 # $remote is words
parallel --will-cite -q --jobs "$jobs" $remote --joblog "$out/shards/joblog" --halt never \
    "$aabench" run "$@" -q --shard "{}/$shards" --out "$out/shards/{}" \
    ::: $(seq 1 "$shards") || true
# `run` exits 1 when some cases failed: a result; anything else stopped it
bad=$(awk -F'\t' 'NR > 1 && $7 != 0 && $7 != 1 { print $9 }' "$out/shards/joblog" |
    sed 's/.*--shard \([0-9]*\/[0-9]*\).*/\1/')
if [ -n "$bad" ]; then
    echo "gnu-parallel-run.sh: shard(s) $(echo $bad) did not finish (see $out/shards/joblog);" \
        "aabench run --resume $out/shards/K finishes one, then run this again" >&2
    exit 3
fi
dirs=$(seq 1 "$shards" | sed "s|^|$out/shards/|")
# shellcheck disable=SC2086 # one folder a word
exec "$aabench" merge $dirs --out "$out" $merge $(printf '%s\n' "$@" | grep -qx -- '-q' && echo -q)
