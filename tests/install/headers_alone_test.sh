#!/bin/bash
# Install.EveryInstalledHeaderCompilesAlone: every header cmake --install puts under include/facet
# compiles as the first and only include of a file, against the prefix alone (as a program linking Facet
# includes it). The build compiles the libraries in batches of files (unity build), where a header
# missing an include of its own compiles anyway when another file of its batch included it first; here it
# fails, naming the header and the compiler's message.
# Usage: headers_alone_test.sh BUILD_DIR COMPILER
set -euo pipefail
build=$1 compiler=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/facet-headers-alone.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >"$work/install.log"
include=$prefix/include/facet
[ -f "$include/pipeline/pipeline.h" ] || {
    echo "no pipeline/pipeline.h under $include: were the headers installed?"
    exit 1
}

# One compile per header, two at a time: -fsyntax-only parses and instantiates, which is where a
# missing declaration shows, without generating code.
export compiler include work
find "$include" -name '*.h' | sort >"$work/headers"
count=$(wc -l <"$work/headers")
xargs -P 2 -I {} bash -c '
    header=$1
    name=${header#"$include/"}
    log=$work/$(echo "$name" | tr / _).log
    echo "#include \"$name\"" >"$log.cpp"
    "$compiler" -std=c++20 -fsyntax-only -Wall -Wextra -Wno-psabi -I"$include" -I"$include/pipeline" "$log.cpp" \
        >"$log" 2>&1 || { echo "$name does not compile alone:"; head -n 20 "$log"; exit 1; }
' header-check {} <"$work/headers" || exit 1
echo "each of the $count installed headers compiles alone"
