#!/usr/bin/env bash
# The layering of src/ (src/CMakeLists.txt): each folder includes only itself, the folders above it and
# the pipeline; the pipeline includes nothing of src/. Prints every include that reaches up or sideways,
# and fails if there is one. Run by ctest as Layering.NoUpwardIncludes.
set -uo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
declare -A allowed=(
    [base]="base"
    [shading]="base shading"
    [raycast]="base raycast"
    [scene]="base shading raycast scene"
    [shaders]="base shading raycast scene shaders"
    [io]="base shading raycast scene io"
    [render]="base shading raycast scene shaders io render"
    [reference]="base shading raycast scene shaders io render reference"
    [step]="base shading raycast scene shaders io render step"
    [oracle]="base shading raycast scene shaders io render reference oracle"
    [bench]="base shading raycast scene shaders io render reference oracle bench"
    [trade]="base shading raycast scene shaders io render reference oracle bench trade"
    [microbench]="base shading raycast scene shaders io render microbench"
    [cli]="base shading raycast scene shaders io render reference step oracle bench trade cli"
)
status=0
for folder in "$root"/src/*/; do
    name=$(basename "$folder")
    if [ -z "${allowed[$name]+set}" ]; then
        echo "src/$name: a folder the layering does not know (add it to tests/layering.sh and src/CMakeLists.txt)"
        status=1
        continue
    fi
    while IFS=: read -r file line include; do
        layer=${include%%/*}
        [ "$layer" = pipeline ] && continue
        if [[ " ${allowed[$name]} " != *" $layer "* ]]; then
            echo "${file#"$root"/}:$line: src/$name includes \"$include\" from a layer below it"
            status=1
        fi
    done < <(grep -Hn -o '#include "[a-z_]*/[^"]*"' "$folder"* | sed 's/#include "\(.*\)"$/\1/')
done
# The pipeline links GLM only: no header of src/.
while IFS=: read -r file line include; do
    layer=${include%%/*}
    if [ "$layer" != pipeline ]; then
        echo "${file#"$root"/}:$line: the pipeline includes \"$include\" from src/"
        status=1
    fi
done < <(grep -Hn -o '#include "[a-z_]*/[^"]*"' "$root"/pipeline/* | sed 's/#include "\(.*\)"$/\1/')
exit $status
