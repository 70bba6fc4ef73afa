#!/bin/sh
# check-gallery.sh DIR: the gallery DIR/index.html (aabench figures, or a run
# folder's report) seen by a browser.  Takes a headless Chromium screenshot of the page and checks it
# is not blank, then dumps the page's DOM and checks every <img> names a
# file present in DIR.  Installs nothing: without chromium it says how to
# get it and exits 2.  Exit 0 if the page passes, 1 if not.
set -u
if [ $# -ne 1 ] || [ ! -f "$1/index.html" ]; then
    echo "usage: check-gallery.sh DIR (a folder holding index.html, from aabench figures or run)" >&2
    exit 2
fi
if ! command -v chromium >/dev/null 2>&1; then
    echo "check-gallery: chromium is not installed; install it with" >&2
    echo "    sudo apt-get install chromium" >&2
    exit 2
fi
dir=$(cd "$1" && pwd)
tmp=$(mktemp -d /tmp/check-gallery-XXXXXX)
trap 'rm -rf "$tmp"' EXIT
url="file://$dir/index.html"
flags="--headless --no-sandbox --disable-gpu --hide-scrollbars"
status=0

# 1. screenshot, not blank
chromium $flags --screenshot="$tmp/shot.png" --window-size=1200,4000 "$url" \
    >"$tmp/shot.log" 2>&1
if [ ! -s "$tmp/shot.png" ]; then
    echo "check-gallery: no screenshot was taken:" >&2
    tail -5 "$tmp/shot.log" >&2
    exit 1
fi
size=$(wc -c <"$tmp/shot.png")
if command -v python3 >/dev/null 2>&1; then
    # decode the PNG (8-bit RGB or RGBA, non-interlaced, as Chromium writes
    # it) and count the pixels that differ from the most common colour
    python3 - "$tmp/shot.png" <<'PY' || status=1
import struct, sys, zlib
from collections import Counter
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, w = 8, b"", 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, ctype, _, _, lace = struct.unpack(">IIBBBBB", body)
        assert depth == 8 and ctype in (2, 6) and lace == 0, "unexpected PNG kind"
        bpp = 3 if ctype == 2 else 4
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
raw = zlib.decompress(idat)
stride = w * bpp
prev = bytearray(stride)
colours = Counter()
for j in range(h):
    f = raw[j * (stride + 1)]
    line = bytearray(raw[j * (stride + 1) + 1:(j + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b = prev[i]
        c = prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    prev = line
    if j % 4 == 0:
        for i in range(0, stride, 4 * bpp):
            colours[bytes(line[i:i + 3])] += 1
total = sum(colours.values())
common = colours.most_common(1)[0][1]
other = 1 - common / total
print("screenshot: %dx%d, %d colours, %.1f%% of pixels differ from the most common" %
      (w, h, len(colours), 100 * other))
if len(colours) < 16 or other < 0.02:
    print("check-gallery: the screenshot is blank", file=sys.stderr)
    sys.exit(1)
PY
else
    echo "screenshot: $size bytes (python3 missing: only its size is checked)"
    if [ "$size" -lt 20000 ]; then
        echo "check-gallery: the screenshot is blank ($size bytes)" >&2
        status=1
    fi
fi

# 2. every <img> of the rendered page names a file in DIR
chromium $flags --dump-dom "$url" >"$tmp/dom.html" 2>"$tmp/dom.log"
grep -o '<img [^>]*src="[^"]*"' "$tmp/dom.html" | sed 's/.*src="\([^"]*\)"/\1/' >"$tmp/srcs"
n=$(wc -l <"$tmp/srcs")
if [ "$n" -eq 0 ]; then
    echo "check-gallery: the page shows no image" >&2
    status=1
fi
missing=0
while read -r src; do
    case "$src" in
    *://* | /*) echo "check-gallery: $src is not a relative link" >&2; missing=$((missing + 1)) ;;
    *) [ -s "$dir/$src" ] || { echo "check-gallery: $src is missing" >&2; missing=$((missing + 1)); } ;;
    esac
done <"$tmp/srcs"
[ "$missing" -eq 0 ] || status=1
echo "images: $n in the page, $missing missing"
if grep -qi '<script' "$tmp/dom.html"; then
    echo "check-gallery: the page has a script" >&2
    status=1
fi
[ "$status" -eq 0 ] && echo "check-gallery: $dir/index.html ok"
exit $status
