#!/bin/bash
# Install.DebianPackageListsItsDependencies: cpack -G DEB makes facet_<version>_<arch>.deb whose Depends
# are the Debian packages of the libraries the program and its modules link (dpkg-shlibdeps), so that
# apt-get install ./facet_*.deb brings them. Skipped without dpkg-dev (dpkg-shlibdeps) or file, which
# CPack runs to find the package's programs and libraries.
# Usage: debian_package_test.sh BUILD_DIR VERSION
set -euo pipefail
build=$1 version=$2
if ! command -v dpkg-shlibdeps >/dev/null || ! command -v dpkg-deb >/dev/null || ! command -v file >/dev/null; then
    echo "skipped: no dpkg-shlibdeps or file (apt-get install dpkg-dev file)"
    exit 77
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/facet-deb.XXXXXX")
trap 'rm -rf "$work"' EXIT

cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work" >"$work/cpack.log" 2>&1 || {
    cat "$work/cpack.log"
    exit 1
}
deb=$work/facet_${version}_$(dpkg --print-architecture).deb
[ -f "$deb" ] || {
    echo "no $(basename "$deb"); cpack made: $(ls "$work")"
    exit 1
}
dpkg-deb -I "$deb"

fail() {
    echo "$*"
    exit 1
}
[ "$(dpkg-deb -f "$deb" Package)" = facet ] || fail "Package: $(dpkg-deb -f "$deb" Package)"
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "Version: $(dpkg-deb -f "$deb" Version)"
[ "$(dpkg-deb -f "$deb" Section)" = graphics ] || fail "Section: $(dpkg-deb -f "$deb" Section)"
depends=$(dpkg-deb -f "$deb" Depends)
# facet's own libraries (Embree, libpng) and its modules' (OpenImageIO, OpenCV).
for package in libopenimageio libembree libpng16 libopencv-core libc6; do
    [[ "$depends" == *"$package"* ]] || fail "Depends lacks $package: $depends"
done
# Compiling a shader of one's own (--shader toon.cpp) needs a compiler and GLM's headers.
recommends=$(dpkg-deb -f "$deb" Recommends)
[[ "$recommends" == *libglm-dev* ]] || fail "Recommends lacks libglm-dev: $recommends"
[[ "$recommends" == *g++* || "$recommends" == *clang* ]] || fail "Recommends names no compiler: $recommends"
# The program, its modules (in lib/facet or lib/<multiarch>/facet, as GNUInstallDirs gave), the models,
# the man page and what programs of one's own need.
files=$(dpkg-deb -c "$deb" | awk '{ print $NF }')
for path in ./usr/bin/facet './usr/lib/([^/]+/)?facet/libfacet_openimageio\.so' \
    './usr/lib/([^/]+/)?facet/libfacet_opencv\.so' ./usr/share/facet/models/spot/spot_triangulated.obj \
    ./usr/share/man/man1/facet.1 ./usr/include/facet/pipeline/pipeline.h \
    ./usr/include/facet/shaders/user_shader.h ./usr/include/facet/facet_shader_abi.h \
    './usr/lib/([^/]+/)?cmake/Facet/FacetConfig\.cmake' './usr/lib/([^/]+/)?pkgconfig/facet\.pc'; do
    grep -qxE "$path" <<<"$files" || fail "the package has no $path"
done
echo "$(basename "$deb"): Depends: $depends"
