#!/bin/sh
# install-deps.sh: install the Debian packages aabench needs that are missing.
#
# Each need is checked the cheapest way (pkg-config module, command, header);
# only what is missing is installed, so a second run is a no-op.  Installing
# needs root (or sudo); otherwise the command to run is printed.
set -eu

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
need pc:cmocka libcmocka-dev
need pc:freetype2 libfreetype-dev
need pc:stb libstb-dev
need pc:cairo libcairo2-dev
need cmd:gnuplot gnuplot-nox
need file:/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf fonts-dejavu-core

[ -z "$missing" ] && exit 0

echo "install-deps: installing${missing}" >&2
if [ "$(id -u)" -eq 0 ]; then
    SUDO=""
elif command -v sudo >/dev/null 2>&1; then
    SUDO="sudo"
else
    echo "install-deps: not root; run as root: apt-get install -y${missing}" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
echo "install-deps: done" >&2
