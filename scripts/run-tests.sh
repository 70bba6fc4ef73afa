#!/bin/sh
# run-tests.sh BUILD TEST...: run each test binary, report, fail if any fails.
# The tests find the command under test through $AABENCH and the example
# plug-in through $AABENCH_PLUGIN.
set -u
build=$1
shift
AABENCH="$(pwd)/$build/aabench"
AABENCH_PLUGIN="$(pwd)/$build/tests/plugin_example.so"
export AABENCH AABENCH_PLUGIN
# AABENCH_VALGRIND=1 (make valgrind): each test under memcheck; errors and
# definite or indirect leaks fail it.
run=""
if [ -n "${AABENCH_VALGRIND:-}" ]; then
    run="valgrind --tool=memcheck --error-exitcode=1 --leak-check=full \
--errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect \
--suppressions=$(pwd)/tests/valgrind.supp --quiet"
fi
failed=""
for t in "$@"; do
    if $run "$t" >"$t.log" 2>&1; then
        printf '%-40s ok\n' "$t"
    else
        printf '%-40s FAILED (log: %s)\n' "$t" "$t.log"
        cat "$t.log"
        failed="$failed $t"
    fi
done
if [ -n "$failed" ]; then
    echo "failed:$failed"
    exit 1
fi
