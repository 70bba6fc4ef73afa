#!/bin/sh
# check-install.sh: `make install` into a staging folder, then the
# installed command run from a folder outside the source tree, with no
# AABENCH_* variable set:
#
#   check-install.sh BUILD       (make check-install; BUILD built first)
#
# It checks that the command finds the SVG scenes it installed (the svg
# pattern's default file, PREFIX/share/aabench/svg/shapes.svg, named by
# `list patterns -v` and rendered by a run), that it keeps its reference
# cache in $XDG_CACHE_HOME/aabench (and in ~/.cache/aabench without it),
# and that it writes nothing into the folder it runs in but its --out.
# Prints "check-install: passed", or each failure; exit 1 if any.
set -u

[ $# -eq 1 ] || { echo "usage: check-install.sh BUILD" >&2; exit 2; }
build=$1
[ -x "$build/aabench" ] || { echo "check-install: no $build/aabench (build first)" >&2; exit 2; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/aabench-install.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT
trap 'exit 2' HUP INT TERM
stage=$tmp/stage
failed=0
fail() {
    echo "check-install: $*" >&2
    failed=1
}

if ! ${MAKE:-make} --no-print-directory install BUILD="$build" DESTDIR="$stage" >"$tmp/install.log" 2>&1; then
    cat "$tmp/install.log" >&2
    echo "check-install: make install failed" >&2
    exit 1
fi
bin=$(find "$stage" -path '*/bin/aabench' -type f | head -n 1)
[ -n "$bin" ] || { echo "check-install: no bin/aabench under $stage" >&2; exit 1; }
prefix=${bin%/bin/aabench}
svg=$prefix/share/aabench/svg

# The run's folder: outside the source tree (a folder of its own under
# TMPDIR) and empty; HOME and XDG_CACHE_HOME of the check's own.
mkdir -p "$tmp/run" "$tmp/home" || exit 2
# run NAME CMD...: the installed command in $tmp/run, output in $tmp/NAME.log
run() {
    name=$1
    shift
    (cd "$tmp/run" && env -i PATH=/usr/bin:/bin HOME="$tmp/home" ${XDG:+XDG_CACHE_HOME="$XDG"} \
        "$bin" "$@") >"$tmp/$name.log" 2>&1
}

# 1. the svg pattern's default file is the installed shapes.svg
XDG=$tmp/xdg
if ! run list list patterns -v; then
    fail "aabench list patterns -v failed:"; cat "$tmp/list.log" >&2
elif ! grep -qF "file=$svg/shapes.svg " "$tmp/list.log"; then
    fail "the svg pattern's default file is not $svg/shapes.svg:"
    grep -F 'file=' "$tmp/list.log" >&2
fi
for f in mono shapes rules curves logo arcs strokes; do
    [ -f "$svg/$f.svg" ] || fail "$svg/$f.svg was not installed"
done

# 2. a run of the default svg scene and a shipped one by name: references
#    computed into $XDG_CACHE_HOME/aabench, nothing else in the run's folder
if ! run svg run -p svg -p "svg:file=$svg/logo.svg" -m point -s 32x32 -f box --reps 1 \
        --no-images --no-plots -q --out out; then
    fail "aabench run on the installed SVG scenes failed:"; cat "$tmp/svg.log" >&2
fi
n=$(find "$tmp/xdg/aabench" -type f -name 'ref-*' 2>/dev/null | wc -l)
[ "$n" -eq 2 ] || fail "expected 2 references in \$XDG_CACHE_HOME/aabench, found $n"
left=$(cd "$tmp/run" && find . -mindepth 1 -maxdepth 1 ! -name out)
[ -z "$left" ] || fail "the run wrote into its folder besides --out: $left"

# 3. without XDG_CACHE_HOME: ~/.cache/aabench
XDG=
if ! run home run -p svg -m point -s 16x16 -f box --reps 1 --no-images --no-plots -q --out out2; then
    fail "aabench run without XDG_CACHE_HOME failed:"; cat "$tmp/home.log" >&2
fi
n=$(find "$tmp/home/.cache/aabench" -type f -name 'ref-*' 2>/dev/null | wc -l)
[ "$n" -eq 1 ] || fail "expected 1 reference in ~/.cache/aabench, found $n"

[ "$failed" -eq 0 ] && echo "check-install: passed (installed under $prefix, run from $tmp/run)"
exit "$failed"
