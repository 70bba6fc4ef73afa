#!/bin/sh
# check-slurm.sh: the Slurm driver (scripts/slurm-run.sh) tested for real on
# a single-node Slurm started here, as root: munged, slurmctld and slurmd
# on this machine with a minimal slurm.conf in a temporary folder (ports
# $SLURM_CHECK_PORT and the next, default 16817), so nothing of a Slurm
# already installed is used or touched.
#
#   sh scripts/check-slurm.sh [BUILD]        (make check-slurm)
#
# It runs a small suite whole, then through slurm-run.sh as 2 shards (a
# references job, a job array, a dependent merge job), waits, and checks
# the merge against the whole run: the same errors and notes in every row,
# the same montage.png.  Slurm and munge are installed (Debian slurm-wlm,
# munge) when missing; if they cannot be installed or started, it says
# SKIP and why, and exits 0.  Every daemon it started is stopped at the end,
# whatever happens; the run stops after $SLURM_CHECK_TIMEOUT seconds (300).
set -u

root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-build}
aabench=$root/$build/aabench
port=${SLURM_CHECK_PORT:-16817}
limit=${SLURM_CHECK_TIMEOUT:-300}
skip() {
    echo "check-slurm: SKIP: $*"
    exit 0
}
fail() {
    echo "check-slurm: FAILED: $*" >&2
    for f in "$D"/*.log; do
        [ -f "$f" ] && { echo "--- $f" >&2; tail -20 "$f" >&2; }
    done
    exit 1
}
[ -x "$aabench" ] && [ -x "$root/$build/tests/test_shard" ] ||
    { echo "check-slurm: make $build/aabench $build/tests/test_shard first" >&2; exit 2; }
if ! command -v slurmctld >/dev/null 2>&1 || ! command -v slurmd >/dev/null 2>&1 ||
    ! command -v munged >/dev/null 2>&1; then
    [ "$(id -u)" = 0 ] || skip "slurm-wlm and munge are missing, and installing them needs root"
    echo "check-slurm: installing slurm-wlm and munge"
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurm-wlm munge \
        >/dev/null 2>&1 || skip "slurm-wlm and munge cannot be installed (apt-get install failed)"
fi

D=$(mktemp -d /tmp/aabench-slurm-XXXXXX)
stop() {
    for d in slurmd slurmctld munged; do
        if [ -f "$D/$d.pid" ]; then
            pid=$(cat "$D/$d.pid")
            kill "$pid" 2>/dev/null
            for _ in 1 2 3 4 5 6 7 8 9 10; do
                kill -0 "$pid" 2>/dev/null || break
                sleep 0.5
            done
            kill -9 "$pid" 2>/dev/null
        fi
    done
    rm -rf "$D"
}
trap stop EXIT
trap 'exit 130' INT TERM

# munge: a key of our own, a socket in the folder
if command -v mungekey >/dev/null 2>&1; then
    mungekey --create --keyfile="$D/munge.key" >/dev/null 2>&1
else
    dd if=/dev/urandom of="$D/munge.key" bs=1024 count=1 2>/dev/null
fi
chmod 400 "$D/munge.key"
munged --key-file="$D/munge.key" --socket="$D/munge.sock" --pid-file="$D/munged.pid" \
    --log-file="$D/munged.log" --seed-file="$D/munged.seed" --force >/dev/null 2>&1 ||
    skip "munged cannot be started here ($(tail -1 "$D/munged.log" 2>/dev/null))"

host=$(hostname -s)
mkdir -p "$D/state" "$D/spool"
cat >"$D/slurm.conf" <<CONF
ClusterName=aabench-check
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$D/munge.sock
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/slurmctld.log
SlurmdLogFile=$D/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=check Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$D/slurm.conf"
slurmctld -c -i -f "$SLURM_CONF" >/dev/null 2>&1 || skip "slurmctld cannot be started here"
slurmd -f "$SLURM_CONF" >/dev/null 2>&1 || skip "slurmd cannot be started here"
up=""
for _ in $(seq 1 60); do
    state=$(sinfo -h -o %T 2>/dev/null | head -1)
    case $state in idle* | mixed* | alloc*) up=1; break ;; esac
    sleep 1
done
[ -n "$up" ] || skip "the node did not come up (state: ${state:-none}; $(tail -1 "$D/slurmctld.log"))"
echo "check-slurm: single-node Slurm up ($(sinfo -V), node $host, $(nproc) CPUs)"

opts="-p crow -s 64x64 -s 96x96 -f box -f tent:r=1 -m point -m supersample -m jitter:spp=4 \
-m area --reps 1 --no-plots --threads 1"
# shellcheck disable=SC2086 # $opts is words
"$aabench" run $opts -q --cache "$D/cache" --out "$D/whole" >"$D/whole.log" 2>&1 ||
    fail "the whole run failed"
start=$(date +%s)
# shellcheck disable=SC2086
timeout "$limit" sh "$root/scripts/slurm-run.sh" --shards 2 --wait --aabench "$aabench" \
    $opts --cache "$D/cache" --out "$D/sharded" >"$D/driver.log" 2>&1
code=$?
end=$(date +%s)
echo "check-slurm: slurm-run.sh exited $code after $((end - start)) s:"
sed 's/^/  /' "$D/driver.log"
for f in "$D"/sharded/slurm/warm-*.log "$D"/sharded/slurm/shard-*.log; do
    echo "  --- $(basename "$f")"
    sed 's/^/    /' "$f"
done
[ "$code" = 0 ] || fail "slurm-run.sh exited $code"
# every row's errors and notes, the images and the montage against the
# whole run's, read back by the library (tests/test_shard.c)
AABENCH=$aabench AABENCH_COMPARE_RUNS="$D/whole $D/sharded" "$root/$build/tests/test_shard" \
    >"$D/compare.log" 2>&1 || fail "the merged results differ from the whole run's"
rows=$(($(wc -l <"$D/whole/results.csv") - 1))
for k in 1 2; do
    [ "$(($(wc -l <"$D/sharded/shards/$k/results.csv") - 1))" -gt 0 ] ||
        fail "shard $k measured nothing"
done
echo "check-slurm: ok: $rows cases through 2 Slurm shards, merged equal to the whole run"
