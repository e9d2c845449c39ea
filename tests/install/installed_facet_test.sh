#!/bin/bash
# Install.InstalledFacetRendersFromThePrefix: facet installed with cmake --install and the prefix then
# moved, so that neither the build tree nor the prefix it was installed to can be what it uses: it renders
# the bundled cow and a scene file from <prefix>/share/facet/models to PNG, and to EXR through its
# OpenImageIO module, found in <prefix>/lib/facet relative to the program; without that module it says
# so (it never falls back on the build's copy). --version prints the project's version, and the man page
# is installed.
# Usage: installed_facet_test.sh BUILD_DIR VERSION
set -euo pipefail
build=$1 version=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/facet-installed.XXXXXX")
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/installed" >"$work/install.log"
mv "$work/installed" "$work/moved"
prefix=$work/moved
facet=$prefix/bin/facet
models=$prefix/share/facet/models

fail() {
    echo "$*"
    exit 1
}

"$facet" render "$models/spot/spot_triangulated.obj" -o "$work/cow.png" --width 160 --height 120
[ "$(head -c 8 "$work/cow.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "cow.png is not a PNG file"
"$facet" render "$models/spot/spot_triangulated.obj" -o "$work/cow.exr" --width 160 --height 120
[ "$(head -c 4 "$work/cow.exr" | od -An -tx1 | tr -d ' \n')" = 762f3101 ] || fail "cow.exr is not an OpenEXR file"
# A scene file names its models relative to itself.
"$facet" render "$models/example-scene.json" -o "$work/scene.png" --width 160 --height 120

# The module comes from the prefix: without it, EXR fails and the message names where it was looked for.
module=$(find "$prefix" -name libfacet_openimageio.so)
[ -n "$module" ] || fail "no libfacet_openimageio.so in the prefix"
rm "$module"
if "$facet" render "$models/spot/spot_triangulated.obj" -o "$work/again.exr" --width 16 --height 12 \
    2>"$work/error.txt"; then
    fail "facet wrote an EXR without the module in its prefix (loaded from elsewhere, e.g. the build tree)"
fi
grep -qF "needs OpenImageIO, and libfacet_openimageio.so was not found (looked for $prefix/bin/libfacet_openimageio.so and $module;" \
    "$work/error.txt" || fail "unexpected message: $(cat "$work/error.txt")"

[ "$("$facet" --version | head -n 1)" = "facet $version" ] || fail "facet --version: $("$facet" --version)"
[ -s "$prefix/share/man/man1/facet.1" ] || fail "no man page at share/man/man1/facet.1"
echo "installed facet $version rendered PNG, EXR and a scene from a moved prefix"
