#!/usr/bin/env bash
# The exercises of docs/teaching.md still show their answers: each command the page gives is run
# and every number or phrase the page quotes from its screens must be in the output. When a change
# moves an answer (a renumbered triangle, a retitled screen), this fails and the page must follow.
# Run by ctest as Docs.TeachingExercisesShowTheirAnswers: teaching_exercises.sh FACET SOURCE_DIR.
set -uo pipefail
facet=$1
cd "$2" || exit 1
failures=0
# Each command's output, run once however many quotes are checked in it (keyed by its words).
declare -A outputs
# output_of ARGS...: the output of `facet step ARGS...`, in $output.
output_of() {
    local key="$*"
    if [ -z "${outputs[$key]+set}" ]; then
        outputs[$key]=$("$facet" step "$@" 2>&1)
    fi
    output=${outputs[$key]}
}
# shows "QUOTE" ARGS...: the output of `facet step ARGS...` holds QUOTE (a fixed string).
shows() {
    local quote=$1
    shift
    output_of "$@"
    if ! grep -q -F -- "$quote" <<< "$output"; then
        echo "docs/teaching.md quotes \"$quote\" from: facet step $*; the output does not show it"
        failures=$((failures + 1))
    fi
}
# number_after "TEXT" ARGS...: the number that follows the first TEXT in the output of
# `facet step ARGS...` (in the walk's left column under --versus), in $number.
number_after() {
    local text=$1
    shift
    output_of "$@"
    number=$(grep -F -m1 -- "$text" <<< "$output" | awk -v t="$text" '{ i = index($0, t);
        rest = substr($0, i + length(t)); if (match(rest, /-?[0-9.]+(e-?[0-9]+)?/))
        print substr(rest, RSTART, RLENGTH) }')
}
# holds "CONDITION" "TEXT" ARGS...: the number after TEXT (number_after) makes CONDITION true, with
# the number as x (an awk expression: "x > 0.5"): the premise an exercise rests on still holds.
holds() {
    local condition=$1 text=$2
    shift 2
    number_after "$text" "$@"
    if [ -z "$number" ] || ! awk -v x="$number" "BEGIN { exit !($condition) }"; then
        echo "docs/teaching.md's exercise needs $condition for the number after \"$text\" in:" \
             "facet step $*; it is \"$number\""
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
gouraud=(models/gouraud-highlight.json --pixel 160,128 --versus "--shading gouraud")
shows 'They first differ in "Pixel history of (160, 128)"' "${gouraud[@]}"
shows "c_add.r = 4.99927e-11" "${gouraud[@]}"
shows "spec = max(R·V, 0)^e = max(0.9999, 0)^32 = 0.9976" "${gouraud[@]}"
shows "spec = max(R·V, 0)^e = max(0.4807, 0)^32 = 6.588e-11" "${gouraud[@]}"
shows "spec = max(R·V, 0)^e = max(-0.682, 0)^32 = 0" "${gouraud[@]}"
shows "The image file holds 255, 255, 255" "${gouraud[@]}"
shows "The image file holds 20, 33, 73" "${gouraud[@]}"
# The premise: a substantial highlight per pixel, next to none per vertex.
holds "x > 0.5" "0)^32 = " models/gouraud-highlight.json --pixel 160,128 --print
holds "x < 1e-6" "c_add.r = " models/gouraud-highlight.json --pixel 160,128 --print --shading gouraud

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
shows "c_o = α_s·c_s + (1 − α_s)·c_d" "${unsorted[@]}" --print
shows "mixed triangle 5's colour" "${unsorted[@]}" --versus "--transparency sorted"

# 6. Why is this part of the ground dark?
shadow=(models/shadows.json --pixel 600,400)
shows "shadow: another surface blocks the light from P: v = 0" "${shadow[@]}" --print
shows "shadow: nothing blocks the light from P (or it casts none): v = 1" "${shadow[@]}" --print
shows "att·spot·v·max(N·L,0)·l_d⊗m_d" "${shadow[@]}" --print

# 7. How bright is P2, the point facing the light?
p2=(models/red-sphere.json --pixel 360,112 --print)
shows "N·L = 1" "${p2[@]}"
shows "diffuse  = RGB(1, 0, 0)" "${p2[@]}"
shows "spec = max(R·V, 0)^e = max(0.6411, 0)^1 = 0.6411" "${p2[@]}"
holds "x > 0.999" "N·L = " "${p2[@]}"

# 8. And P1, the point facing the camera?
p1=(models/red-sphere.json --pixel 320,240 --print)
shows "N·L = 0.6278" "${p1[@]}"
shows "diffuse  = RGB(0.6278, 0, 0)" "${p1[@]}"
shows "spec = max(R·V, 0)^e = max(0.6263, 0)^1 = 0.6263" "${p1[@]}"

# 9. Why is P3 black?
p3=(models/red-sphere.json --pixel 302,376 --print)
shows "N·L = -0.1961" "${p3[@]}"
shows "R·V = -0.8933" "${p3[@]}"
shows "diffuse  = RGB(0, 0, 0)" "${p3[@]}"
shows "specular = RGB(0, 0, 0)" "${p3[@]}"
shows "The specular term is 0 where N·L ≤ 0.0001" "${p3[@]}"

# 10. The reflection vector by projection
r=(models/red-sphere.json --pixel 380,180 --print)
shows "N = normalize(N) = (0.3316, 0.3261, 0.8853)" "${r[@]}"
shows "L = normalize(p_light − P) = (0.2137, 0.7299, 0.6493)" "${r[@]}"
shows "N·L = 0.8837" "${r[@]}"
shows "R = 2(N·L)N − L = (0.3723, -0.1536, 0.9153)" "${r[@]}"
shows "R·V = 0.91" "${r[@]}"

# 11. The highlight's exponent
shows "spec = max(R·V, 0)^e = max(0.91, 0)^8 = 0.4703" "${r[@]}" --shininess 8
shows "spec = max(R·V, 0)^e = max(0.91, 0)^32 = 0.04893" "${r[@]}" --shininess 32
shows "spec = max(R·V, 0)^e = max(0.91, 0)^128 = 5.73e-06" models/red-sphere.json --pixel 380,180 \
    --versus "--shininess 128"
shows "The image file holds 255, 245, 245" models/red-sphere.json --pixel 380,180 --versus "--shininess 128"
shows "The image file holds 241, 0, 0" models/red-sphere.json --pixel 380,180 --versus "--shininess 128"

# 12. Blinn against Phong: e′ ≈ 4e
blinn=(models/red-sphere.json --pixel 380,180 --shininess 32 --reflection blinn-phong)
shows "N·H = 0.972" "${blinn[@]}" --versus "--blinn-exponent matched"
shows "spec = max(N·H, 0)^e = max(0.972, 0)^32 = 0.4031" "${blinn[@]}" --versus "--blinn-exponent matched"
shows "e′ = 4e = 128: max(0.972, 0)^128 = 0.0264" "${blinn[@]}" --versus "--blinn-exponent matched"

# 13. How much does glass reflect at 80°?
glass=(models/glass-fresnel.json --pixel 160,120)
shows "V·H = 0.1742" "${glass[@]}" --print
shows "η = (1 + √F0)/(1 − √F0) = (1.5, 1.5, 1.5)" "${glass[@]}" --print
shows "= RGB(0.3866, 0.3866, 0.3866)" "${glass[@]}" --print
shows "= RGB(0.4087, 0.4087, 0.4087)" "${glass[@]}" --versus "--fresnel schlick"
shows "V·H = 0.1255" "${glass[@]}" --print --eye 4.98553,0.380135,0
shows "= RGB(0.4986, 0.4986, 0.4986)" "${glass[@]}" --print --eye 4.98553,0.380135,0

# 14. Why is the highlight bigger under Gouraud?
vertex=(models/gouraud-vertex.json --pixel 190,120)
shows "spec = max(R·V, 0)^e = max(0.6823, 0)^64 = 2.377e-11" "${vertex[@]}" --versus "--shading gouraud"
shows "spec = max(R·V, 0)^e = max(1, 0)^64 = 1" "${vertex[@]}" --versus "--shading gouraud"
shows "c_add.r = 0.584908" "${vertex[@]}" --versus "--shading gouraud"
shows "The image file holds 24, 73, 24" "${vertex[@]}" --versus "--shading gouraud"
shows "The image file holds 202, 210, 202" "${vertex[@]}" --versus "--shading gouraud"
# The premise: no highlight per pixel, a bright one per vertex.
holds "x < 1e-6" "0)^64 = " "${vertex[@]}" --print
holds "x > 0.3" "c_add.r = " "${vertex[@]}" --print --shading gouraud

# 15. Flat, Gouraud and Phong shading on one model
shows "Lighting once per triangle (flat shading)" "${vertex[@]}" --print --shading flat
shows "spec = max(R·V, 0)^e = max(0.1815, 0)^64 = 1.175e-38" "${vertex[@]}" --print --shading flat
shows "The image file holds 21, 67, 21" "${vertex[@]}" --print --shading flat
shows "The image file holds 202, 210, 202" "${vertex[@]}" --print --shading gouraud
shows "The image file holds 24, 73, 24" "${vertex[@]}" --print --shading phong

# 16. The F0 table
gold=(models/lighting-scene.json --width 400 --height 300 --pixel 120,130 --textures off --print)
shows "c_base = RGB(1, 0.782, 0.344), metalness = 1" "${gold[@]}"
shows "F0 = mix(F0_dielectric, c_base, metalness) = RGB(1, 0.782, 0.344)" "${gold[@]}"
shows "V·H = 0.8943" "${gold[@]}"

# 17. How far does the point light reach? 18. Inside the spot light's cone
lights=(models/lighting-scene.json --width 400 --height 300 --pixel 260,190 --print)
shows "att = 1/(c0 + c1·d + c2·d²) = 1/(1 + 0.2·3.851 + 0.05·3.851²) = 0.3981" "${lights[@]}"
shows "att = 1/(c0 + c1·d + c2·d²) = 1/(0 + 0·3.404 + 1·3.404²) = 0.08631" "${lights[@]}"
shows "cos angle = −L·s = 0.9504" "${lights[@]}"
shows "smoothstep(0.8829, 0.9511, 0.9504) = 0.9997" "${lights[@]}"

# 19. Fog: linear, exponential, exponential squared
fog=(models/fog-and-glass.json --width 400 --height 300 --pixel 296,96 --print)
shows "z = |P_eye| (radial distance) = |(2.884, 1.599, -12.32)| = 12.75" "${fog[@]}" --fog linear \
    --fog-start 4 --fog-end 14
shows "f = (end − z)/(end − start) = (14 − 12.75)/(14 − 4) = 0.1249" "${fog[@]}" --fog linear \
    --fog-start 4 --fog-end 14
shows "f = e^(−density·z) = e^(−0.1·12.75) = 0.2794" "${fog[@]}" --fog exp --fog-density 0.1
shows "f = e^(−(density·z)²) = e^(−(0.1·12.75)²) = 0.1967" "${fog[@]}" --fog exp2 --fog-density 0.1
shows "f = e^(−(density·z)²) = e^(−(0.1·12.75)²) = 0.1967" "${fog[@]}"
shows "Fog is off" "${fog[@]}" --fog none

# 20. Two reasons for gamma
gamma=(models/red-sphere.json --pixel 329,350)
shows "N·L = 0.04152" "${gamma[@]}" --print
shows "R: 0.0415217 → 0.225242 → 57" "${gamma[@]}" --versus "--gamma 2.2"
shows "R: 0.0415217^(1/2.2) = 0.235474, 255·c′ = 60.0459 → 60" "${gamma[@]}" --versus "--gamma 2.2"
shows "R: 0.0415217 → 11" "${gamma[@]}" --print --encode linear

# 21. Sorting transparent triangles with coherence (facet render's --stats)
panes=$(mktemp -d)
stats=$("$facet" render models/intersecting-quads.json -o "$panes/panes.png" --width 160 --height 120 \
    --frames 0-2 --turntable 10 --stats 2>&1)
rm -rf "$panes"
for quote in "frame 0: " "sorted from scratch (radix sort)" \
    "frame 1: " "sorted by insertion from the last frame's order: 5 comparisons, 0 moves" \
    "frame 2: " "6 comparisons, 2 moves"; do
    if ! grep -q -F -- "$quote" <<< "$stats"; then
        echo "docs/teaching.md quotes \"$quote\" from facet render --stats; the output does not show it"
        failures=$((failures + 1))
    fi
done

# 22. Putting it together: the notes' physically based form (the lecture preset)
together=(models/red-sphere.json --pixel 360,112 --reflection cook-torrance --versus "--lighting lecture")
shows "<   F = F0 + (1 − F0)(1 − V·H)^5   (Schlick)" "${together[@]}"
shows ">   F = F0 + (1 − F0)(1 − N·L)^5   (Schlick)" "${together[@]}"
shows "<   D·G/(4(N·L)(N·V)) = 0.4021·0.8316/(4·1·0.6374) = 0.1311" "${together[@]}"
shows ">   D·G/(π(N·V)(N·L)) = 0.4021·0.8316/(π·0.6374·1) = 0.167" "${together[@]}"
shows "< The image file holds 17, 0, 0" "${together[@]}"
shows "> The image file holds 24, 4, 4" "${together[@]}"

# 23. A mirror in the sky: the environment map
mirror=(models/red-sphere.json --pixel 327,200 --reflection cook-torrance --environment models/environment/sky.png)
shows "    = (0.08214, 0.4326, 0.8978) (eye space)" "${mirror[@]}"
shows "uv = (0.03669, 0.6424)" "${mirror[@]}"
shows "texel (9, 45) from the top left" "${mirror[@]}"
shows "E(R) = RGB(0.3042, 0.4371, 0.7856)" "${mirror[@]}"
shows "reflection = F ⊗ E(R) = RGB(0.01217, 0.01749, 0.03143)" "${mirror[@]}"

# Screens for slides: the LaTeX the page shows is, line for line, what its command prints.
slide=(models/fog-and-glass.json --width 400 --height 300 --pixel 296,96 --fog exp2 --fog-density 0.1
       --screen fog --format latex)
shown=$(awk '/^## Screens for slides/ { section = 1 } section && /^```latex$/ { inside = 1; next }
             inside && /^```$/ { exit } inside' docs/teaching.md)
printed=$("$facet" step "${slide[@]}" 2>&1)
if [ -z "$shown" ] || [ "$shown" != "$printed" ]; then
    echo "docs/teaching.md's exported screen is not what facet step ${slide[*]} prints:"
    diff <(echo "$shown") <(echo "$printed") | head -20
    failures=$((failures + 1))
fi
joined=$(sed -e ':a' -e '/\\$/{N;s/\\\n *//;ba' -e '}' docs/teaching.md)  # its continued lines joined
if ! grep -q -F -- "facet step ${slide[*]}" <<< "$joined"; then
    echo "docs/teaching.md does not show the command of its exported screen: facet step ${slide[*]}"
    failures=$((failures + 1))
fi

if [ $failures -ne 0 ]; then
    echo "$failures quotes of docs/teaching.md are not in facet step's output"
    exit 1
fi
echo "every exercise of docs/teaching.md shows the answer the page quotes"
