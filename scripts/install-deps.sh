#!/bin/sh
# install-deps.sh: install the Debian packages aabench needs that are missing,
# and, with --locale, generate the locale its tests use.
#
#   sh scripts/install-deps.sh [--locale] [--with-renderers]
#
# --locale (or AABENCH_INSTALL_LOCALE=1) also generates de_DE.UTF-8, which
# only the tests need (`make test` passes it; `make run` does not).
#
# Each need is checked the cheapest way (pkg-config module, command, header);
# only what is missing is installed, so a second run is a no-op.  Installing
# needs root (or sudo); otherwise the command to run is printed.
#
# --with-renderers (or AABENCH_INSTALL_RENDERERS=1) also installs the SVG
# renderers the external method runs (scripts/renderers/README.md): librsvg's
# rsvg-convert (librsvg2-bin), Chromium (chromium), and resvg's Node.js
# binding, the npm package @resvg/resvg-js, into build/renderers/node.  They
# are optional: `make test` and `make run` never install them.
set -eu

renderers=${AABENCH_INSTALL_RENDERERS:-}
locale=${AABENCH_INSTALL_LOCALE:-}
for arg in "$@"; do
    case $arg in
    --with-renderers) renderers=1 ;;
    --locale) locale=1 ;;
    *) echo "usage: sh scripts/install-deps.sh [--locale] [--with-renderers]" >&2; exit 2 ;;
    esac
done
[ "$renderers" = 0 ] && renderers=""
[ "$locale" = 0 ] && locale=""
root=$(cd "$(dirname "$0")/.." && pwd)
# the resvg binding's version and folder (scripts/renderers/resvg looks there)
RESVG_JS=@resvg/resvg-js@2.6.2
RESVG_DIR=$root/build/renderers/node

missing=""
need() { # need CHECK PACKAGE
    case "$1" in
    pc:*) pkg-config --exists "${1#pc:}" 2>/dev/null && return 0 ;;
    cmd:*) command -v "${1#cmd:}" >/dev/null 2>&1 && return 0 ;;
    hdr:*) [ -f "/usr/include/${1#hdr:}" ] && return 0 ;;
    file:*) [ -f "${1#file:}" ] && return 0 ;;
    esac
    missing="$missing $2"
}

need cmd:gcc gcc
need cmd:g++ g++
need hdr:stdio.h libc6-dev
need cmd:pkg-config pkg-config
need pc:gsl libgsl-dev
need pc:OpenImageIO libopenimageio-dev
need pc:libpng libpng-dev
need pc:cmocka libcmocka-dev
need pc:freetype2 libfreetype-dev
need pc:stb libstb-dev
need pc:cairo libcairo2-dev
need pc:libagg libagg-dev
need pc:libcjson libcjson-dev
need cmd:parallel parallel
need pc:libxml-2.0 libxml2-dev
need pc:harfbuzz libharfbuzz-dev
need cmd:gnuplot gnuplot-nox
need file:/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf fonts-dejavu-core
# a CFF (cubic) font for the text pattern's tests
need file:/usr/share/fonts/opentype/cantarell/Cantarell-Regular.otf fonts-cantarell
if [ -n "$renderers" ]; then
    need cmd:rsvg-convert librsvg2-bin
    need cmd:chromium chromium
    need cmd:node nodejs
    need cmd:npm npm
fi

# The tests run the number formatting under a locale whose decimal point is
# a comma (LOCALE); Debian generates it from /etc/locale.gen with locale-gen
# (package locales).
LOCALE=de_DE.UTF-8
have_locale() {
    locale -a 2>/dev/null | grep -qix 'de_DE\.utf-\{0,1\}8'
}
need_locale=""
if [ -n "$locale" ] && ! have_locale; then
    need_locale=1
    need file:/usr/sbin/locale-gen locales
fi

need_resvg=""
if [ -n "$renderers" ] && [ ! -f "$RESVG_DIR/node_modules/@resvg/resvg-js/package.json" ]; then
    need_resvg=1
fi

[ -z "$missing" ] && [ -z "$need_locale" ] && [ -z "$need_resvg" ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
    SUDO=""
elif command -v sudo >/dev/null 2>&1; then
    SUDO="sudo"
else
    SUDO=""
    echo "install-deps: not root; run as root:" >&2
    [ -n "$missing" ] && echo "    apt-get install -y${missing}" >&2
    [ -n "$need_locale" ] &&
        echo "    sed -i 's/^# *$LOCALE UTF-8/$LOCALE UTF-8/' /etc/locale.gen && locale-gen" >&2
    if [ -z "$missing" ] && [ -z "$need_locale" ]; then
        : # the resvg binding goes under build/: no root needed
    else
        exit 1
    fi
fi
if [ -n "$missing" ]; then
    echo "install-deps: installing${missing}" >&2
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    # shellcheck disable=SC2086
    $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
if [ -n "$need_locale" ]; then
    echo "install-deps: generating the locale $LOCALE" >&2
    if grep -q "^# *$LOCALE UTF-8" /etc/locale.gen 2>/dev/null; then
        $SUDO sed -i "s/^# *$LOCALE UTF-8/$LOCALE UTF-8/" /etc/locale.gen
    elif ! grep -q "^$LOCALE UTF-8" /etc/locale.gen 2>/dev/null; then
        echo "$LOCALE UTF-8" | $SUDO tee -a /etc/locale.gen >/dev/null
    fi
    $SUDO /usr/sbin/locale-gen >/dev/null
    if ! have_locale; then
        echo "install-deps: locale $LOCALE is still missing after locale-gen" >&2
        exit 1
    fi
fi
if [ -n "$need_resvg" ]; then
    echo "install-deps: installing $RESVG_JS into $RESVG_DIR (npm)" >&2
    mkdir -p "$RESVG_DIR"
    npm install --prefix "$RESVG_DIR" --no-audit --no-fund --silent "$RESVG_JS" >&2
fi
echo "install-deps: done" >&2
