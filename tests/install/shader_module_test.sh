#!/bin/bash
# Install.ShaderModulesFromThePrefix: shaders of one's own with an installed Facet, its prefix moved so
# that neither the build tree nor the prefix it was installed to can be what it uses:
#  1. an out-of-tree CMake project (shader_consumer/) builds toon.so with facet_add_shader() of the
#     installed package, and the installed facet draws with it (--shader toon.so): not blank, and not
#     the built-in shader's image;
#  2. a module built against other headers (another key) is refused, with a message naming both keys;
#  3. the installed facet compiles toon.cpp itself against the installed headers (--shader toon.cpp),
#     into the same image as the module's;
#  4. without the installed headers it says where it looked (so 3 took them from the prefix).
# Usage: shader_module_test.sh BUILD_DIR SOURCE_DIR CXX_COMPILER
set -euo pipefail
build=$1 source=$2 compiler=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/facet-shader-module.XXXXXX")
trap 'rm -rf "$work"' EXIT

fail() {
    echo "$*"
    exit 1
}

cmake --install "$build" --prefix "$work/installed" >"$work/install.log"
mv "$work/installed" "$work/moved"
prefix=$work/moved
facet=$prefix/bin/facet
model=$prefix/share/facet/models/spot/spot_triangulated.obj
export FACET_SHADER_CACHE=$work/cache
size=(--width 96 --height 72)

# 1. facet_add_shader() from the moved prefix alone. (Breaks if the package lacks facet_add_shader,
# the installed headers miss one a shader includes, or the module's name or flags are wrong.)
mkdir "$work/shader"
cp "$source/tests/cli/shaders/toon.cpp" "$work/shader/toon.cpp"
cmake -S "$source/tests/install/shader_consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_CXX_COMPILER="$compiler" -DFACET_TEST_SHADER="$work/shader/toon.cpp" >"$work/configure.log" 2>&1 || {
    cat "$work/configure.log"
    exit 1
}
cmake --build "$work/consumer" -j2 >"$work/build.log" 2>&1 || {
    cat "$work/build.log"
    exit 1
}
[ -f "$work/consumer/toon.so" ] || fail "facet_add_shader(toon ...) made no toon.so: $(ls "$work/consumer")"

"$facet" render "$model" "${size[@]}" -o "$work/builtin.ppm"
"$facet" render "$model" "${size[@]}" --shader "$work/consumer/toon.so" -o "$work/module.ppm" 2>"$work/module.err" || {
    cat "$work/module.err"
    fail "the installed facet did not draw with toon.so"
}
# Distinct byte values of a PPM's pixels (its header is the first three lines): a blank image has one
# colour, at most three values.
values() { tail -n +4 "$1" | od -An -v -tu1 | tr -s ' ' '\n' | sed '/^$/d' | sort -u | wc -l; }
[ "$(values "$work/module.ppm")" -gt 3 ] || fail "the image drawn with toon.so is blank"
cmp -s "$work/builtin.ppm" "$work/module.ppm" && fail "the image drawn with toon.so is the built-in shader's"

# 2. Another key: refused, not run. (Breaks if facet loads a module without checking its key.)
if "$facet" render "$model" "${size[@]}" --shader "$work/consumer/toon_other.so" -o "$work/other.ppm" \
    2>"$work/other.err"; then
    fail "facet drew with a module built for another Facet"
fi
grep -q "^facet: error: .*toon_other.so: the shader module was built for facet 0.0.0, headers 0123456789abcdef, another build, and this is facet " \
    "$work/other.err" || fail "unexpected message for a module of another Facet: $(cat "$work/other.err")"
[ "$(wc -l <"$work/other.err")" -eq 1 ] || fail "more than one line for a module of another Facet: $(cat "$work/other.err")"

# 3. The installed facet compiles the .cpp against the installed headers. (Breaks if the headers are not
# installed, or headerFolders() looks anywhere but relative to the program.)
"$facet" render "$model" "${size[@]}" --shader "$work/shader/toon.cpp" -o "$work/compiled.ppm" 2>"$work/compiled.err" || {
    cat "$work/compiled.err"
    fail "the installed facet did not compile toon.cpp"
}
grep -q "^facet: compiling .*toon.cpp" "$work/compiled.err" || fail "no compile reported: $(cat "$work/compiled.err")"
cmp -s "$work/module.ppm" "$work/compiled.ppm" || fail "toon.cpp compiled by facet draws otherwise than toon.so"

# 4. The headers come from the prefix: without them (and with an empty cache, since the module of 3
# would load without compiling) facet says where it looked.
rm "$prefix/include/facet/shaders/user_shader.h"
rm -rf "$FACET_SHADER_CACHE"
if "$facet" render "$model" "${size[@]}" --shader "$work/shader/toon.cpp" -o "$work/none.ppm" 2>"$work/none.err"; then
    fail "facet compiled toon.cpp without the installed headers (from elsewhere, e.g. the source tree?)"
fi
grep -qF "compiling a shader needs facet's headers, which are not in $prefix/include/facet" "$work/none.err" ||
    fail "unexpected message without the installed headers: $(cat "$work/none.err")"
echo "facet_add_shader built toon.so against the moved prefix, the installed facet drew with it, refused a" \
    "module of another Facet, and compiled toon.cpp against the installed headers"
