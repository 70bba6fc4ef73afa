#!/bin/sh
# svg-corpus.sh: the svg pattern's reader (and its exact reference) over a
# directory of SVG files, counted: how many are taken, how many refused and
# why (the refusal's reason, its element, values and numbers left out), and
# how many failed otherwise (a crash, a time-out, an internal error: a bug).
#
#   sh scripts/svg-corpus.sh [options] DIR|FILE...
#
#   --aabench PATH  the command (default: $AABENCH, else build/aabench)
#   --size WxH      the view each file is drawn on (default 16x16)
#   --every K       every K-th file of each argument, in sorted order (default 1)
#   --jobs N        files read side by side (default 1)
#   --timeout S     seconds a file may take before it counts as hung (default 60)
#   --list FILE     also write one line a file: status, exit code, path, message
#   --from FILE     no files read: the table of a list --list wrote (no DIR)
#
# Each file is `aabench truth -p svg:file=F -s WxH --no-cache -q`: read, built
# into a scene and its box reference computed. Exit status 0 is taken, 2 is
# refused (by the reader, or by the reference: "pixel (i, j): ..."), anything
# else failed. Symbolic links are not followed (an icon theme links one file
# under many names). The script exits 1 when a file failed, else 0.
set -u

usage() {
    sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}

aabench=${AABENCH:-build/aabench}
size=16x16
every=1
jobs=1
timeout=60
list=
from=
while [ $# -gt 0 ]; do
    case $1 in
    --aabench) aabench=${2:?}; shift 2 ;;
    --size) size=${2:?}; shift 2 ;;
    --every) every=${2:?}; shift 2 ;;
    --jobs) jobs=${2:?}; shift 2 ;;
    --timeout) timeout=${2:?}; shift 2 ;;
    --list) list=${2:?}; shift 2 ;;
    --from) from=${2:?}; shift 2 ;;
    -h | --help) usage ;;
    --) shift; break ;;
    -*) echo "svg-corpus: unknown option $1" >&2; usage ;;
    *) break ;;
    esac
done
if [ -n "$from" ]; then
    [ $# -eq 0 ] || { echo "svg-corpus: --from takes no DIR or FILE" >&2; exit 2; }
    [ -r "$from" ] || { echo "svg-corpus: cannot read $from" >&2; exit 2; }
else
    [ $# -gt 0 ] || usage
fi
for n in "$every" "$jobs" "$timeout"; do
    case $n in '' | *[!0-9]* | 0) echo "svg-corpus: $n is not a positive whole number" >&2; exit 2 ;; esac
done
case $size in *[!0-9x]* | x* | *x | *x*x*) echo "svg-corpus: --size $size is not WxH" >&2; exit 2 ;; *x*) ;; *) echo "svg-corpus: --size $size is not WxH" >&2; exit 2 ;; esac
[ -n "$from" ] || [ -x "$aabench" ] || { echo "svg-corpus: $aabench is not an executable (build it: make)" >&2; exit 2; }
command -v timeout >/dev/null || { echo "svg-corpus: needs timeout (coreutils)" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/svg-corpus.XXXXXX") || exit 3
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM

if [ -n "$from" ]; then
    cp "$from" "$work/all" || exit 2
else
# The files, NUL-separated, every K-th of each argument.
for a in "$@"; do
    if [ -d "$a" ]; then
        find "$a" -type f \( -name '*.svg' -o -name '*.SVG' \) -print0 | sort -z |
            awk -v RS='\0' -v ORS='\0' -v k="$every" '(NR - 1) % k == 0'
    elif [ -f "$a" ]; then
        printf '%s\0' "$a"
    else
        echo "svg-corpus: $a is neither a file nor a directory" >&2
        exit 2
    fi
done >"$work/files" || exit 2

# One file: a line "STATUS<TAB>CODE<TAB>PATH<TAB>MESSAGE" on standard output,
# one write (shorter than a pipe's atomic size), the message the last line
# the command printed (warnings come before the error).
cat >"$work/one.sh" <<'EOF'
f=$1
case $f in
*[%,]*) spec=$(printf '%s' "$f" | sed 's/%/%25/g; s/,/%2C/g') ;;
*) spec=$f ;;
esac
msg=$(timeout -k 5 "$T" "$A" truth -p "svg:file=$spec" -s "$S" --no-cache -q -o "$W/out.$$.pfm" 2>&1 >/dev/null)
rc=$?
rm -f "$W/out.$$.pfm"
case $rc in
0) status=taken ;;
2) status=refused ;;
124 | 137) status=hung ;;
*) status=failed ;;
esac
nl='
'
msg=${msg##*"$nl"}
printf '%s\t%s\t%.1000s\t%.2000s\n' "$status" "$rc" "$f" "$msg"
EOF
xargs -0 -r -n 1 -P "$jobs" env W="$work" A="$aabench" S="$size" T="$timeout" \
    sh "$work/one.sh" <"$work/files" >"$work/lines"
sort -t "$(printf '\t')" -k3 "$work/lines" >"$work/all"
[ -n "$list" ] && cp "$work/all" "$list"
fi

# The table. A reason is the reader's message after its element (the
# element kept when the element is what is refused: "<switch>: this
# element is not supported"), or the reference's ("pixel (i, j): ..."),
# its quoted values and numbers replaced, so that alike refusals count
# together; its example names the file, the line and the element.
awk -F '\t' '
function reason(m) {
    if (match(m, /: line [0-9]+: /)) {
        m = substr(m, RSTART + RLENGTH)
        if (m !~ /^<[^>]*>: this element/) sub(/^<[^>]*>: /, "", m)
    } else if (match(m, /pixel \([0-9]+, [0-9]+\): /)) m = "reference: " substr(m, RSTART + RLENGTH)
    else sub(/^aabench truth: /, "", m)
    gsub(/"[^"]*"/, "\"...\"", m)
    gsub(/[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?/, "N", m)
    if (length(m) > 150) m = substr(m, 1, 147) "..."
    return m
}
{ n++; count[$1]++ }
function where(m) {
    return match(m, /: line [0-9]+: <[^>]*>/) ? substr(m, RSTART + 2, RLENGTH - 2) : ""
}
$1 == "refused" { r = reason($4); why[r]++; if (!(r in ex)) ex[r] = $3 (where($4) == "" ? "" : " (" where($4) ")") }
$1 == "hung" || $1 == "failed" { bad[++nb] = $1 " (exit " $2 "): " $3 ": " $4 }
END {
    printf "%d files: %d taken (%.1f%%), %d refused, %d failed, %d hung\n", n, count["taken"],
        n ? 100 * count["taken"] / n : 0, count["refused"], count["failed"], count["hung"]
    if (count["refused"]) {
        printf "\nrefused, by reason:\n"
        k = 0
        for (r in why) key[++k] = r
        for (i = 2; i <= k; i++) # most first, then by name
            for (j = i; j > 1 && (why[key[j]] > why[key[j - 1]] ||
                                  why[key[j]] == why[key[j - 1]] && key[j] < key[j - 1]); j--) {
                t = key[j]; key[j] = key[j - 1]; key[j - 1] = t
            }
        for (i = 1; i <= k; i++) printf "%7d  %s\n         e.g. %s\n", why[key[i]], key[i], ex[key[i]]
    }
    if (nb) {
        printf "\nfailed or hung:\n"
        for (i = 1; i <= nb; i++) print "  " bad[i]
    }
    exit nb > 0
}' "$work/all"
