#!/usr/bin/env bash
# Renders docs/shaders.md's images: each example shader of examples/shaders/ on the bundled cow.
#
#   docs/shaders/make-images.sh FACET_BINARY OUTPUT_DIR
#
# e.g. docs/shaders/make-images.sh build/src/facet docs/shaders (the committed images were made so).
# The shaders are compiled on first use into facet's shader cache ($FACET_SHADER_CACHE); any failure
# of facet stops the script with a non-zero status.
set -euo pipefail

if [[ $# -ne 2 ]]; then
    echo "usage: $0 FACET_BINARY OUTPUT_DIR" >&2
    exit 2
fi
facet=$1
out=$2
root="$(cd "$(dirname "$0")/../.." && pwd)"
cow="$root/models/spot/spot_triangulated.obj"
shaders="$root/examples/shaders"
mkdir -p "$out"

common=(--width 240 --height 180 --threads 2 --png-compression 9 -q --eye 1.6,0.8,2.2)

"$facet" render "$cow" -o "$out/builtin.png" "${common[@]}"
"$facet" render "$cow" -o "$out/normals.png" "${common[@]}" --shader "$shaders/normals.cpp"
"$facet" render "$cow" -o "$out/toon.png" "${common[@]}" --shader "$shaders/toon.cpp" --uniform bands=3
"$facet" render "$cow" -o "$out/checker.png" "${common[@]}" --shader "$shaders/checker.cpp" --uniform scale=12
"$facet" render "$root/models/cube/cube.obj" -o "$out/wireframe.png" "${common[@]}" --shader "$shaders/wireframe.cpp" \
    --uniform hollow=true --cull none
"$facet" render "$cow" -o "$out/displace.png" "${common[@]}" --shader "$shaders/displace.cpp" \
    --uniform amplitude=0.04 --uniform frequency=40
"$facet" render "$cow" -o "$out/phong-assignment.png" "${common[@]}" --reflection phong \
    --shader "$shaders/phong_assignment.cpp"
"$facet" render "$cow" -o "$out/phong-solution.png" "${common[@]}" --reflection phong \
    --shader "$shaders/phong_solution.cpp"
