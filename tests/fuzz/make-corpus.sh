#!/usr/bin/env bash
# Seed corpora for the fuzz targets, made from the models and scenes the project already has:
#   tests/fuzz/make-corpus.sh OUT   →   OUT/obj, OUT/scene, OUT/render (one file per seed)
# The inputs are converted to each target's format (tests/fuzz/*_fuzzer.cpp): an OBJ's `mtllib` lines
# become `mtllib model.mtl` and its MTL files follow it after a NUL byte; a scene's model paths become
# "model.obj"; a render input is a scene, a NUL, and an OBJ seed. The shared models are read where they
# are (../shared/models beside the repository; absent: the bundled models alone).
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
shared=$(cd "$repo/../shared/models" 2>/dev/null && pwd || true)
out=${1:?usage: make-corpus.sh OUT_FOLDER}
mkdir -p "$out/obj" "$out/scene" "$out/render"

max_bytes=65536        # larger models make slow inputs that teach the fuzzer nothing new
max_render_bytes=8192  # a render input draws its model: keep those tiny

# The OBJ file in the OBJ target's format, on standard output.
obj_seed() {
    local obj=$1 folder mtls=() line name part
    folder=$(dirname "$obj")
    while IFS= read -r line; do
        name=${line#*mtllib}
        name=$(printf '%s' "$name" | sed -E 's/^[[:space:]]+|[[:space:]]+$//g')
        if [[ -f "$folder/$name" ]]; then
            mtls+=("$folder/$name")
        else
            for part in $name; do [[ -f "$folder/$part" ]] && mtls+=("$folder/$part"); done
        fi
    done < <(grep -E '^[[:space:]]*mtllib[[:space:]]' "$obj" | tr -d '\r' || true)
    if ((${#mtls[@]} == 0)); then
        cat "$obj"
        return
    fi
    sed -E 's/^[[:space:]]*mtllib[[:space:]].*$/mtllib model.mtl/' "$obj"
    printf '\0'
    cat "${mtls[@]}"
}

# A scene with every model path (a string ending in .obj) replaced by model.obj, on standard output.
scene_seed() {
    sed -E 's/"model"([[:space:]]*):([[:space:]]*)"[^"]*\.obj"/"model"\1:\2"model.obj"/g' "$1"
}

seed_name() { printf '%s' "$1" | sed -E "s|^$repo/||; s|^$shared/|shared-|; s|[^A-Za-z0-9._-]+|-|g"; }

objs=("$repo"/models/*/*.obj)
if [[ -n "$shared" ]]; then
    objs+=("$shared"/cube-mcguire/*.obj "$shared"/suzanne/*.obj "$shared"/cornell-box/*.obj
           "$shared"/tinyobjloader-tests/*.obj)
fi
for obj in "${objs[@]}"; do
    (($(stat -c %s "$obj") <= max_bytes)) || continue
    obj_seed "$obj" >"$out/obj/$(seed_name "$obj")"
done

for scene in "$repo"/models/*.json "$repo"/tests/conformance/scenes/*.json; do
    scene_seed "$scene" >"$out/scene/$(seed_name "$scene")"
done

# Render inputs: every scene with the bundled cube, and every small OBJ seed in the smallest scene.
cube=$(obj_seed "$repo/models/cube/cube.obj" | base64 -w0)
for seed in "$out"/scene/*; do
    { cat "$seed"; printf '\0'; printf '%s' "$cube" | base64 -d; } >"$out/render/$(basename "$seed")"
done
for seed in "$out"/obj/*; do
    (($(stat -c %s "$seed") <= max_render_bytes)) || continue
    { printf '{"model": "model.obj"}\0'; cat "$seed"; } >"$out/render/model-$(basename "$seed")"
done
# Inputs that once were findings, each in its target's format: kept as seeds so that CI replays them.
for target in obj scene render; do
    for seed in "$repo/tests/fuzz/regressions/$target"/*; do
        [[ -f "$seed" ]] && cp "$seed" "$out/$target/regression-$(basename "$seed")"
    done
done
echo "make-corpus.sh: $(ls "$out/obj" | wc -l) OBJ, $(ls "$out/scene" | wc -l) scene and" \
     "$(ls "$out/render" | wc -l) render seeds in $out"
