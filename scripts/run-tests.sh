#!/bin/sh
# run-tests.sh: run test binaries and count what passed.
#
#   run-tests.sh one BUILD TEST      run one test binary; its output goes to
#                                    TEST.log, its result (passed or failed)
#                                    and wall time to TEST.result; prints one
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
    rm -f "$t.result"
    start=$(now)
    if $run "$t" >"$t.log" 2>&1; then
        result=passed
    else
        result=failed
    fi
    seconds=$(awk -v a="$start" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }')
    echo "$result $seconds" >"$t.result"
    if [ "$result" = passed ]; then
        printf '%-40s ok     %6s s\n' "$t" "$seconds"
    else
        # in one printf, so that a parallel test's line does not land inside
        printf '%-40s FAILED %6s s (log: %s)\n%s\n' "$t" "$seconds" "$t.log" "$(cat "$t.log")"
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
    for t in "$@"; do
        n=$((n + 1))
        seconds=$(cut -d' ' -f2 "$t.result" 2>/dev/null)
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
