#!/bin/sh
# check-cycles.sh: cycles between the source files at link level.
#
#   check-cycles.sh BUILD        the objects under BUILD/obj (every *.o)
#   check-cycles.sh --self-test  compiles two tiny objects that use each
#                                other's functions, and two that do not,
#                                and checks that the first pair is reported
#                                and the second is not
#
# A file uses another when its object has an undefined symbol (nm type U)
# that the other's object defines (T, D, B, R, G, S or C).  The files and
# these uses make a graph; each strongly connected component of more than
# one file is a cycle: no file of it can be linked without the others.  The
# script prints each cycle, its files and, for each use inside it, the
# symbols that make it; then the number of cycles.  Exit 0 when there is
# none, 1 when there is one or more, 2 for bad usage or no objects.
set -u

usage() {
    echo "usage: check-cycles.sh BUILD | --self-test" >&2
    exit 2
}

# cycles OBJECT...: the report on the objects given; exit status as above
cycles() {
    # nm -P -A: "FILE: NAME TYPE [VALUE SIZE]" a line
    table=$(nm -P -A "$@") || { echo "check-cycles: nm failed" >&2; return 2; }
    printf '%s\n' "$table" | awk '
    {
        file = $1; sub(/:$/, "", file)
        name = $2; type = $3
        if (!(file in id)) { id[file] = ++nfile; fname[nfile] = file }
        if (type == "U") {
            uses[file, name] = 1
            used[++nused] = file SUBSEP name
        } else if (type ~ /^[TDBRGSC]$/) {
            if ((name in definer) && definer[name] != file)
                definer[name] = definer[name] SUBSEP file
            else
                definer[name] = file
        }
    }
    # the edges a -> b (a uses b) and their symbols, in the order read
    END {
        for (k = 1; k <= nused; k++) {
            split(used[k], p, SUBSEP)
            a = p[1]; name = p[2]
            if (!(name in definer)) continue
            nd = split(definer[name], defs, SUBSEP)
            for (j = 1; j <= nd; j++) {
                b = defs[j]
                if (b == a) continue
                ia = id[a]; ib = id[b]
                if (!((ia, ib) in syms)) {
                    nout[ia]++; out[ia, nout[ia]] = ib
                    syms[ia, ib] = name
                } else if (index(" " syms[ia, ib] " ", " " name " ") == 0) {
                    syms[ia, ib] = syms[ia, ib] " " name
                }
            }
        }
        for (v = 1; v <= nfile; v++)
            if (!(v in index_of)) strong(v)
        ncycles = 0
        for (c = 1; c <= ncomp; c++) {
            if (csize[c] < 2) continue
            ncycles++
            printf "cycle %d: %d files\n", ncycles, csize[c]
            for (i = 1; i <= csize[c]; i++)
                printf "  %s\n", fname[cmember[c, i]]
            for (i = 1; i <= csize[c]; i++) {
                v = cmember[c, i]
                for (j = 1; j <= nout[v]; j++) {
                    w = out[v, j]
                    if (comp[w] == c)
                        printf "  %s -> %s: %s\n", fname[v], fname[w], syms[v, w]
                }
            }
        }
        printf "%d cycle%s\n", ncycles, ncycles == 1 ? "" : "s"
        exit (ncycles > 0 ? 1 : 0)
    }
    # Tarjan: the strongly connected components, each in comp[] and
    # cmember[]; the files of one component in the order they were read
    function strong(v,    j, w, n, i, t) {
        index_of[v] = low[v] = ++counter
        stack[++top] = v; onstack[v] = 1
        for (j = 1; j <= nout[v]; j++) {
            w = out[v, j]
            if (!(w in index_of)) {
                strong(w)
                if (low[w] < low[v]) low[v] = low[w]
            } else if (onstack[w] && index_of[w] < low[v]) {
                low[v] = index_of[w]
            }
        }
        if (low[v] != index_of[v]) return
        ncomp++; n = 0
        do {
            w = stack[top--]; onstack[w] = 0
            comp[w] = ncomp; member[++n] = w
        } while (w != v)
        # sort the members by the order read (insertion sort: few)
        for (i = 2; i <= n; i++) {
            t = member[i]
            for (j = i - 1; j >= 1 && member[j] > t; j--) member[j + 1] = member[j]
            member[j + 1] = t
        }
        for (i = 1; i <= n; i++) cmember[ncomp, i] = member[i]
        csize[ncomp] = n
    }'
}

# self_test: the check run on objects with and without a cycle
self_test() {
    cc=${CC:-cc}
    dir=$(mktemp -d "${TMPDIR:-/tmp}/check-cycles.XXXXXX") || exit 2
    trap 'rm -rf "$dir"' EXIT
    trap 'exit 2' HUP INT TERM
    # ping.c and pong.c call each other: a cycle of two
    printf 'int pong(int);\nint ping(int n) { return n > 0 ? pong(n - 1) : 0; }\n' >"$dir/ping.c"
    printf 'int ping(int);\nint pong(int n) { return n > 0 ? ping(n - 1) : 1; }\n' >"$dir/pong.c"
    # top.c uses leaf.c, which uses nothing: no cycle
    printf 'int leaf(int);\nint top(int n) { return leaf(n) + 1; }\n' >"$dir/top.c"
    printf 'int leaf_data = 3;\nint leaf(int n) { return n * leaf_data; }\n' >"$dir/leaf.c"
    for f in ping pong top leaf; do
        "$cc" -c "$dir/$f.c" -o "$dir/$f.o" || { echo "check-cycles: self-test: $cc failed" >&2; exit 2; }
    done
    failed=0
    out=$(cycles "$dir/ping.o" "$dir/pong.o" "$dir/top.o" "$dir/leaf.o"); status=$?
    expected="cycle 1: 2 files
  $dir/ping.o
  $dir/pong.o
  $dir/ping.o -> $dir/pong.o: pong
  $dir/pong.o -> $dir/ping.o: ping
1 cycle"
    if [ "$status" -ne 1 ] || [ "$out" != "$expected" ]; then
        echo "check-cycles: self-test: the cycle ping.o <-> pong.o was not reported as expected" >&2
        echo "exit status $status (expected 1), output:" >&2
        printf '%s\n' "$out" >&2
        failed=1
    fi
    out=$(cycles "$dir/top.o" "$dir/leaf.o"); status=$?
    if [ "$status" -ne 0 ] || [ "$out" != "0 cycles" ]; then
        echo "check-cycles: self-test: top.o -> leaf.o reported as a cycle" >&2
        echo "exit status $status (expected 0), output:" >&2
        printf '%s\n' "$out" >&2
        failed=1
    fi
    [ "$failed" -eq 0 ] && echo "check-cycles: self-test passed"
    exit "$failed"
}

[ $# -eq 1 ] || usage
case $1 in
--self-test) self_test ;;
-*) usage ;;
esac
build=$1
[ -d "$build/obj" ] || { echo "check-cycles: no folder $build/obj (build first)" >&2; exit 2; }
# the objects in a fixed order, so that the report is the same each time
objects=$(find "$build/obj" -name '*.o' | LC_ALL=C sort)
[ -n "$objects" ] || { echo "check-cycles: no objects under $build/obj" >&2; exit 2; }
# shellcheck disable=SC2086 # the build's paths have no blanks
cycles $objects
