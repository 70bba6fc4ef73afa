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
failed=""
for t in "$@"; do
    if "$t" >"$t.log" 2>&1; then
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
