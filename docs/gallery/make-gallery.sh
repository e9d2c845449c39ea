#!/usr/bin/env bash
# Renders the README's gallery: small images of the models and scenes bundled in models/.
#
#   docs/gallery/make-gallery.sh FACET_BINARY OUTPUT_DIR
#
# e.g. docs/gallery/make-gallery.sh build/src/facet docs/gallery (the committed images were made so).
# Every image is rendered with explicit options, so the script gives the same images whatever the
# defaults become; any failure of facet stops the script with a non-zero status.
set -euo pipefail

if [[ $# -ne 2 ]]; then
    echo "usage: $0 FACET_BINARY OUTPUT_DIR" >&2
    exit 2
fi
facet=$1
out=$2
models="$(cd "$(dirname "$0")/../../models" && pwd)"
mkdir -p "$out"

# 320×240, two threads (any thread count gives the same bytes), PNG at the smallest size.
common=(--width 320 --height 240 --threads 2 --png-compression 9 -q)

# Spot, every default: framed from the front, one white key light, per-pixel Blinn-Phong, its texture.
"$facet" render "$models/spot/spot_triangulated.obj" -o "$out/spot.png" "${common[@]}"

# The same cow shaded per face (flat shading) from another viewpoint, with 4× multisampling.
"$facet" render "$models/spot/spot_triangulated.obj" -o "$out/spot-flat.png" "${common[@]}" \
    --shading flat --eye 1.6,0.8,2.2 --aa msaa4

# Cook-Torrance gold, a flat-shaded Phong cube, a smooth spot light and an attenuated point light.
"$facet" render "$models/lighting-scene.json" -o "$out/lighting.png" "${common[@]}"

# Ray-cast shadows of a spot light and a directional light on a ground plane.
"$facet" render "$models/shadows.json" -o "$out/shadows.png" "${common[@]}" --shadows ray

# Exponential-squared fog and a glass cube blended over the nearest cow.
"$facet" render "$models/fog-and-glass.json" -o "$out/fog-and-glass.png" "${common[@]}"

# Intersecting transparent quads, drawn right by per-pixel fragment lists.
"$facet" render "$models/intersecting-quads.json" -o "$out/transparency-exact.png" "${common[@]}" \
    --transparency exact
