#!/bin/sh
# run-tests.sh: run test binaries and count what passed.
#
#   run-tests.sh one BUILD TEST      run one test binary; its output goes to
#                                    TEST.log, its result (passed or failed),
#                                    wall time and user and system CPU time
#                                    (seconds) to TEST.result; prints one
#                                    line (and the log if it failed); exits 0
#                                    either way
#   run-tests.sh summary TEST...     the failed tests, then "N passed, N
#                                    failed" as the last line; exits 1 if
#                                    any failed or did not run
#   run-tests.sh BUILD TEST...       both, one test after the other
#   run-tests.sh order TEST...       the tests, the longest in their last
#                                    run (TEST.result) first; those not run
#                                    yet before all, in the order given
#
# The Makefile runs `one` for each test as its own target, so that make -j
# runs them in parallel, in the order `order` gives, then `summary`.  The tests find the command under
# test through $AABENCH and the example plug-in through $AABENCH_PLUGIN.
# AABENCH_VALGRIND=1 (make valgrind): each test under memcheck; errors and
# definite or indirect leaks fail it.
# AABENCH_TEST_TIMEOUT=S: a test still running after S seconds is stopped
# (TERM, then KILL 10 s later) and fails, its log ending "timed out after S
# s"; default 900 (the slowest took 89 s in CI, under the sanitizers, the
# two builds' tests side by side on 2 cores), none under valgrind; 0: no
# limit.  A test that hangs fails rather than holding up the whole run.
set -u

now() { date +%s.%N; }

one() {
    build=$1
    t=$2
    AABENCH="$(pwd)/$build/aabench"
    AABENCH_PLUGIN="$(pwd)/$build/tests/plugin_example.so"
    # OpenMP threads that wait sleep rather than spin: the tests run side by
    # side on every core, and a spinning thread takes a core from another
    # test (a small run's command spent most of its time so); what the
    # tests check does not depend on how threads wait
    OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
    export AABENCH AABENCH_PLUGIN OMP_WAIT_POLICY
    run=""
    if [ -n "${AABENCH_VALGRIND:-}" ]; then
        run="valgrind --tool=memcheck --error-exitcode=1 --leak-check=full \
--errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect \
--suppressions=$(pwd)/tests/valgrind.supp --quiet"
    fi
    if [ -n "${AABENCH_VALGRIND:-}" ]; then
        limit=${AABENCH_TEST_TIMEOUT:-0}
    else
        limit=${AABENCH_TEST_TIMEOUT:-900}
    fi
    case $limit in
    '' | *[!0-9]*)
        echo "run-tests.sh: AABENCH_TEST_TIMEOUT must be a whole number of seconds, not '$limit'" >&2
        exit 2
        ;;
    esac
    rm -f "$t.result"
    start=$(now)
    # the test in a subshell whose `times` (its children's user and system
    # CPU: the test and every process it waited for) follows its status;
    # CPU time is what a busy machine inflates least.  Under a limit,
    # timeout runs the test in a process group of its own, which a
    # terminal's Ctrl-C does not reach: timeout runs in the background and
    # the INT, TERM or HUP the subshell gets is passed on to it (it passes
    # it on to the test's group), then the subshell waits for it again
    if [ "$limit" -gt 0 ]; then
        out=$( {
            timeout -k 10 "$limit" $run "$t" >"$t.log" 2>&1 &
            pid=$!
            trap 'kill -s INT $pid 2>/dev/null' INT
            trap 'kill -s TERM $pid 2>/dev/null' TERM HUP
            # wait returns early (above 128) where a trapped signal came;
            # the last wait, once the process is gone, gives its status
            while wait $pid 2>>"$t.log"; st=$?; kill -0 $pid 2>/dev/null; do :; done
            echo "$st"
            times
        } )
    else
        out=$( { $run "$t" >"$t.log" 2>&1; echo "$?"; times; } )
    fi
    status=${out%%[!0-9]*}
    result=failed
    [ "$status" = 0 ] && result=passed
    seconds=$(awk -v a="$start" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }')
    # timeout's status: 124 after TERM, 137 (128 + 9) where KILL was needed;
    # the same from a test of its own only if it ran less than the limit
    if [ "$limit" -gt 0 ] && { [ "$status" = 124 ] || [ "$status" = 137 ]; } &&
        awk -v s="$seconds" -v l="$limit" 'BEGIN { exit !(s >= l) }'; then
        echo "timed out after $limit s" >>"$t.log"
    fi
    # times' last line: the children's user and system time, as 1m2.5s
    cpu=$(echo "$out" | awk 'END {
        for (i = 1; i <= 2; i++) { split($i, p, "m"); sub("s", "", p[2]); s[i] = p[1] * 60 + p[2] }
        printf "%.1f %.1f", s[1], s[2] }')
    # result, wall seconds, user and system CPU seconds
    echo "$result $seconds $cpu" >"$t.result"
    cpus=$(echo "$cpu" | awk '{ printf "%.1f", $1 + $2 }')
    if [ "$result" = passed ]; then
        printf '%-40s ok     %6s s  %6s s CPU\n' "$t" "$seconds" "$cpus"
    else
        # in one printf, so that a parallel test's line does not land inside
        printf '%-40s FAILED %6s s  %6s s CPU (log: %s)\n%s\n' "$t" "$seconds" "$cpus" "$t.log" "$(cat "$t.log")"
    fi
}

summary() {
    passed=0
    failed=0
    names=""
    for t in "$@"; do
        if [ "$(cut -d' ' -f1 "$t.result" 2>/dev/null)" = passed ]; then
            passed=$((passed + 1))
        else
            failed=$((failed + 1))
            names="$names $t"
        fi
    done
    if [ "$failed" -gt 0 ]; then
        echo "failed:$names"
    fi
    echo "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
}

order() {
    n=0
    # read, a built-in, not a process a test: make runs this when it reads
    # the Makefile, once a pass, in each make of `make test`
    for t in "$@"; do
        n=$((n + 1))
        seconds=""
        if [ -f "$t.result" ]; then
            read -r _ seconds _ <"$t.result" || :
        fi
        echo "${seconds:-1e9} $n $t"
    done | sort -k1,1gr -k2,2n | cut -d' ' -f3
}

case "${1:-}" in
order)
    shift
    order "$@"
    ;;
one)
    shift
    one "$@"
    ;;
summary)
    shift
    summary "$@"
    ;;
*)
    build=$1
    shift
    for t in "$@"; do
        one "$build" "$t"
    done
    summary "$@"
    ;;
esac
