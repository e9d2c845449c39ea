#!/bin/bash
# Install.OutOfTreeProjectDrawsWithFindPackage: Facet installed into a fresh prefix with cmake --install,
# then used from outside the repository as a user would: a CMake project (consumer/) that finds it with
# find_package(Facet) and a one-file program compiled with pkg-config's flags, both drawing the README's
# shader example, cut out of README.md between the markers tests/CMakeLists.txt uses for readme_example.h.
# Usage: find_package_test.sh BUILD_DIR SOURCE_DIR VERSION
set -euo pipefail
build=$1 source=$2 version=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/facet-find-package.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >"$work/install.log"

# The example: the lines between "<!-- readme-example:begin -->" + "```cpp" and "```" +
# "<!-- readme-example:end -->".
mkdir "$work/example"
awk '
    state == 0 && $0 == "<!-- readme-example:begin -->" { state = 1; next }
    state == 1 { if ($0 != "```cpp") exit 1; state = 2; next }
    state == 2 && $0 == "```" { state = 3; next }
    state == 2 { print; next }
    state == 3 { if ($0 != "<!-- readme-example:end -->") exit 1; found = 1; exit }
    END { if (!found) exit 1 }
' "$source/README.md" >"$work/example/body" || {
    echo "README.md has no readme-example block"
    exit 1
}
{ echo "#pragma once"; cat "$work/example/body"; } >"$work/example/readme_example.h"

# find_package(Facet <version>) from the prefix alone.
cmake -S "$source/tests/install/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
    -DFACET_EXPECTED_VERSION="$version" -DFACET_EXAMPLE_DIR="$work/example" >"$work/configure.log" || {
    cat "$work/configure.log"
    exit 1
}
cmake --build "$work/consumer" >"$work/build.log" 2>&1 || {
    cat "$work/build.log"
    exit 1
}
"$work/consumer/consumer" "$prefix/share/facet/models/spot/spot_triangulated.obj" "$work/triangle.png"
[ "$(head -c 8 "$work/triangle.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || {
    echo "the consumer's triangle.png is not a PNG file"
    exit 1
}

# pkg-config: the pipeline's flags and libraries from facet.pc in the prefix.
PKG_CONFIG_PATH=$(dirname "$(find "$prefix" -name facet.pc)")
export PKG_CONFIG_PATH
[ "$(pkg-config --modversion facet)" = "$version" ] || {
    echo "facet.pc's version is $(pkg-config --modversion facet), not $version"
    exit 1
}
# shellcheck disable=SC2046  # pkg-config's flags are words
"${CXX:-c++}" -std=c++20 -I"$work/example" "$source/tests/install/consumer/main.cpp" \
    $(pkg-config --cflags --libs facet) -o "$work/pkg-config-consumer"
"$work/pkg-config-consumer"
echo "find_package(Facet $version) and pkg-config facet: both programs drew the triangle"
