#!/usr/bin/env bash
# The six exercises of docs/teaching.md still show their answers: each command the page gives is run
# and every number or phrase the page quotes from its screens must be in the output. When a change
# moves an answer (a renumbered triangle, a retitled screen), this fails and the page must follow.
# Run by ctest as Docs.TeachingExercisesShowTheirAnswers: teaching_exercises.sh FACET SOURCE_DIR.
set -uo pipefail
facet=$1
cd "$2" || exit 1
failures=0
# shows "QUOTE" ARGS...: the output of `facet step ARGS...` holds QUOTE (a fixed string).
shows() {
    local quote=$1
    shift
    local output
    output=$("$facet" step "$@" 2>&1)
    if ! grep -q -F -- "$quote" <<< "$output"; then
        echo "docs/teaching.md quotes \"$quote\" from: facet step $*; the output does not show it"
        failures=$((failures + 1))
    fi
}

# 1. Why is this pixel black?
black=(models/cube/cube.obj --eye 0,0,0.2 --target 0,0,-1 --pixel 640,480 --print)
shows "everything was rejected (2 culled): the pixel keeps" "${black[@]}"
shows "culled: faces the culled side" "${black[@]}"
shows "6. Setup: culled for its facing" "${black[@]}"
shows "Back-facing, and that side is culled" "${black[@]}"

# 2. Where did the highlight go under Gouraud?
gouraud=(models/spot/spot_triangulated.obj --pixel 462,391 --versus "--shading gouraud")
shows 'They first differ in "Pixel history of (462, 391)"' "${gouraud[@]}"
shows "c_add.r  0.0196066" "${gouraud[@]}"
shows "The image file holds 206, 192, 186" "${gouraud[@]}"
shows "The image file holds 80, 75, 73" "${gouraud[@]}"

# 3. What did the near plane do to this triangle?
near=(models/near-plane.json --pixel 320,420 --print)
shows "Clipping: near cuts the triangle" "${near[@]}"
shows "v2 (0, 0, -0.831579, 0.2): outside near" "${near[@]}"
shows "p2 d = -0.631579" "${near[@]}"
shows "p0 d = 5.26316" "${near[@]}"
shows "= 0.892857" "${near[@]}"
shows "left: 4 vertices" "${near[@]}"
shows "drawn as a fan of 2 triangles" "${near[@]}"
shows "Fan piece 1" "${near[@]}"
shows "Clipping: inside the view, nothing to clip" models/near-plane.json --eye 0,0,4 --pixel 320,300 --print

# 4. Who owns a pixel on a shared edge?
edge=(models/shared-edge.json --pixel 10,7 --print)
shows "triangle 0: lost a tie: exactly on edge 1 (E1 = 0), not top-left; triangle 1" "${edge[@]}"
shows "* triangle 1: depth" "${edge[@]}"
shows "top or left edge: a centre exactly on it is inside" "${edge[@]}"
shows "not top-left: bias −1" "${edge[@]}"
shows "[+]" "${edge[@]}"
shows "[:]" "${edge[@]}" --triangle 0
shows "Rasterization: a tie lost to the top-left rule" "${edge[@]}" --triangle 0

# 5. Why does unsorted transparency look wrong here?
unsorted=(models/intersecting-quads.json --transparency unsorted --pixel 390,264)
shows "* triangle 9 (transparent, drawn 6.): depth 0.978955" "${unsorted[@]}" --print
shows "triangle 5 (transparent, drawn 2.): depth 0.977708" "${unsorted[@]}" --print
shows "Blending: the over operator" "${unsorted[@]}" --print
shows "c_o = α·c_s + (1 − α)·c_d" "${unsorted[@]}" --print
shows "mixed triangle 5's colour" "${unsorted[@]}" --versus "--transparency sorted"

# 6. Why is this part of the ground dark?
shadow=(models/shadows.json --pixel 600,400)
shows "shadow: another surface blocks the light from P: v = 0" "${shadow[@]}" --print
shows "shadow: nothing blocks the light from P (or it casts none): v = 1" "${shadow[@]}" --print
shows "att·spot·v·max(N·L,0)·l_d⊗m_d" "${shadow[@]}" --print

if [ $failures -ne 0 ]; then
    echo "$failures quotes of docs/teaching.md are not in facet step's output"
    exit 1
fi
echo "every exercise of docs/teaching.md shows the answer the page quotes"
