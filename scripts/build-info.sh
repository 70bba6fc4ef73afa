#!/bin/sh
# build-info.sh: the C header that results files' context compiles in
# (harness/bench/context.c): the commit the program was built from and
# whether the tree was dirty, and the libraries' versions from pkg-config.
# The Makefile writes it into build/build-info.h, replacing it only when it
# changes.  A program run inside a git checkout also records the checkout's
# commit at run time, beside this one.
commit=$(git rev-parse HEAD 2>/dev/null || echo unknown)
if [ "$commit" = unknown ]; then
    dirty=-1
elif [ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ]; then
    dirty=1
else
    dirty=0
fi
version() { pkg-config --modversion "$1" 2>/dev/null || true; }
# FreeType's pkg-config version is its libtool version: read the header's
freetype() {
    for d in $(pkg-config --cflags-only-I freetype2 2>/dev/null | sed 's/-I//g'); do
        h=$d/freetype/freetype.h
        [ -f "$h" ] || continue
        sed -n 's/^#define FREETYPE_\(MAJOR\|MINOR\|PATCH\) *\([0-9]*\).*/\2/p' "$h" | paste -sd.
        return
    done
}
# stb has no version of its own: the Debian package's, else pkg-config's
stb() { dpkg-query -W -f '${Version}' libstb-dev 2>/dev/null || version stb; }
cat <<END
/* written by scripts/build-info.sh: do not edit */
#define AA_BUILD_COMMIT "$commit"
#define AA_BUILD_DIRTY $dirty
#define AA_VERSION_GSL "$(version gsl)"
#define AA_VERSION_OIIO "$(version OpenImageIO)"
#define AA_VERSION_FREETYPE "$(freetype)"
#define AA_VERSION_CAIRO "$(version cairo)"
#define AA_VERSION_STB "$(stb)"
END
