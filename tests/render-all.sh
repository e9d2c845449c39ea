#!/usr/bin/env bash
# Renders every bundled and shared model and scene, plus the command line's shading, lighting,
# transparency and encoding variants, with one facet binary, and prints one checksum per image.
# A refactoring must not change a byte: run it with the binaries before and after and diff the lists.
#
#   tests/render-all.sh BINARY OUT_DIR > sums.txt
#   diff sums-before.txt sums-after.txt
#
# Models that fail to load (the shared set holds deliberately broken files) are listed with their exit
# status instead of a checksum, so a change in which files are refused shows up in the diff too.
set -uo pipefail
if [ $# -ne 2 ]; then
    echo "usage: $0 BINARY OUT_DIR" >&2
    exit 2
fi
facet=$(realpath "$1")
out=$2
here=$(cd "$(dirname "$0")/.." && pwd)
shared="$here/../shared/models"
mkdir -p "$out"

count=0
render() {  # render NAME ARGS...: one image, then its checksum (or the exit status) on one line
    local name=$1
    shift
    count=$((count + 1))
    local image="$out/$(printf '%03d' $count)-$name"
    if "$facet" render -q --threads 2 "$@" -o "$image" 2>/dev/null; then
        for file in "${image%.*}"*; do
            echo "$(sha256sum <"$file" | cut -c1-16) $name $(basename "$file") :: $*"
        done
    else
        echo "exit=$? $name :: $*"
    fi
}
size=(--width 320 --height 240)

# Every scene file of the project: bundled samples and the conformance scenes.
for scene in "$here"/models/*.json "$here"/tests/conformance/scenes/*.json; do
    render "$(basename "$scene" .json).png" "$scene" "${size[@]}"
done

# Every OBJ model, bundled and shared, with the defaults.
while IFS= read -r -d '' model; do
    render "$(basename "$model" .obj).png" "$model" "${size[@]}"
done < <(find "$here/models" "$shared" -name '*.obj' -print0 | sort -z)

# The command line's choices on a few models, each choice at least once.
spot="$shared/spot/spot_triangulated.obj"
teapot="$shared/utah-teapot/teapot.obj"
bunny="$shared/stanford-bunny/stanford-bunny.obj"
for model in "$spot" "$teapot"; do
    for shading in flat gouraud phong; do
        for reflection in phong blinn-phong cook-torrance; do
            for lighting in facet gl; do
                render variant.png "$model" "${size[@]}" --shading $shading --reflection $reflection \
                    --lighting $lighting
            done
        done
    done
    for term in emission ambient diffuse specular; do
        render only.png "$model" "${size[@]}" --only $term
    done
    render components.png "$model" "${size[@]}" --components
    render framing.png "$model" "${size[@]}" --eye 3,2,5 --target 0,0.2,0 --fovy 25
done
for encode in srgb power linear; do
    render encode.png "$bunny" "${size[@]}" --encode $encode
done
render gamma.png "$bunny" "${size[@]}" --gamma 2.2
render float.exr "$bunny" "${size[@]}"
render crease.png "$teapot" "${size[@]}" --crease-angle 20 --shading gouraud
render turntable.png "$spot" "${size[@]}" --frames 0-3 --turntable 90
for scene in "$here"/models/fog-and-glass.json "$here"/models/intersecting-quads.json \
    "$here"/tests/conformance/scenes/gl-fog-exp-transparent-teapots.json; do
    for transparency in sorted unsorted exact; do
        for key in centroid farthest; do
            render transparency.png "$scene" "${size[@]}" --transparency $transparency --sort-key $key
        done
    done
done
# The back end's variants, small: every anti-aliasing mode, depth format and colour buffer format, alone
# and multisampled, on scenes with transparency, every blend mode and shadows, and a plain model.
small=(--width 160 --height 120)
for scene in "$here"/models/fog-and-glass.json "$here"/tests/conformance/scenes/facet-blend-modes-spheres.json \
    "$here"/models/shadows.json "$spot"; do
    for aa in none ssaa2 ssaa4 msaa2 msaa4 msaa8 msaa16; do
        render aa.png "$scene" "${small[@]}" --aa $aa
    done
    for depth in float unorm16 unorm24 reversed-float; do
        for color in float half unorm8; do
            render formats.png "$scene" "${small[@]}" --depth $depth --color-buffer $color
            render formats-msaa.png "$scene" "${small[@]}" --depth $depth --color-buffer $color --aa msaa4
        done
    done
    for aa in none msaa4; do  # exact transparency is per pixel: supersampled instead
        render cull.png "$scene" "${small[@]}" --cull none --aa $aa
        render cull-front.png "$scene" "${small[@]}" --cull front --aa $aa
        render affine.png "$scene" "${small[@]}" --interpolation affine --aa $aa
        render exact.png "$scene" "${small[@]}" --transparency exact --aa ${aa/msaa/ssaa}
        render exact-formats.png "$scene" "${small[@]}" --transparency exact --aa ${aa/msaa/ssaa} --depth unorm16 \
            --color-buffer half
        render unsorted.png "$scene" "${small[@]}" --transparency unsorted --aa $aa
        for shadows in map ray; do
            render shadows.png "$scene" "${small[@]}" --shadows $shadows --aa $aa
            render shadows-formats.png "$scene" "${small[@]}" --shadows $shadows --aa $aa --depth unorm24 \
                --color-buffer unorm8
        done
    done
    render infinite.png "$scene" "${small[@]}" --infinite-far --depth reversed-float
    render nearest.png "$scene" "${small[@]}" --texture-filter trilinear --subpixel-bits 4
done
render large.png "$shared/lost-empire/lost_empire.obj" --width 1280 --height 960
render large-glass.png "$here/models/fog-and-glass.json" --width 1280 --height 960 --transparency exact
echo "$count renders" >&2
