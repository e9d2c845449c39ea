#!/usr/bin/env bash
# Every OBJ of ../shared/models (the public models and tinyobjloader's test files) through `facet render`,
# against the checked-in table of what each gives: rendered, rendered with warnings (each warning a row),
# or refused (with the message). A change of any model's outcome or message fails this test, which prints
# the difference; a rendered image must not be blank unless Facet warned that nothing was drawn.
# Run by ctest as EndToEnd.SharedModelsGiveTheirTabledOutcome:
#   shared_models_table.sh FACET SOURCE_DIR            compare with tests/cli/shared_models_table.tsv
#   shared_models_table.sh FACET SOURCE_DIR --update   rewrite the table from this run
# Exit 77 (ctest: skipped) when ../shared/models is missing.
set -uo pipefail
facet=$1
source_dir=$(cd "$2" && pwd) || exit 1
update=${3:-}
shared="$source_dir/../shared/models"
table="$source_dir/tests/cli/shared_models_table.tsv"
if [[ ! -d $shared ]]; then
    echo "skipped: $shared is missing"
    exit 77
fi
shared=$(cd "$shared" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/facet-shared-models.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT

# One process per model: its exit status, warnings and error are its own (a batch prints a failed
# input's warnings before the next input's, with nothing between to tell them apart). Small images
# keep the 80-odd renders to a few seconds.
actual="$work/table.tsv"
blank_failures=0
{
    printf '# What facet render gives for each OBJ of ../shared/models at 64x48 (tests/cli/shared_models_table.sh).\n'
    printf '# Regenerate: bash tests/cli/shared_models_table.sh FACET . --update   (then review the diff)\n'
    printf '# model\toutcome\tmessage (one row per warning)\n'
} > "$actual"
while IFS= read -r -d '' model; do
    name=${model#"$shared"/}
    rm -f "$work/image.ppm"
    "$facet" render "$model" -o "$work/image.ppm" --width 64 --height 48 > /dev/null 2> "$work/stderr"
    status=$?
    # Paths in messages, relative to the models folder and the work folder, so the table holds no machine's.
    sed -e "s|$shared/||g" -e "s|$work/||g" "$work/stderr" > "$work/messages"
    if ((status == 0)); then
        if grep -q '^facet: warning: ' "$work/messages"; then
            grep '^facet: warning: ' "$work/messages" | sed -e 's/^facet: warning: //' -e "s|^|$name\trendered with warnings\t|"
        else
            printf '%s\trendered\t\n' "$name"
        fi
        # The image is not blank: more than one distinct pixel after the PPM header (3 lines).
        colours=$(tail -n +4 "$work/image.ppm" 2> /dev/null | od -An -v -tx1 -w3 | sort -u | wc -l)
        if ((colours < 2)) && ! grep -q 'nothing was drawn' "$work/messages"; then
            echo "$name: reported as rendered, but the image is blank (one colour) and no warning says so" >&2
            blank_failures=$((blank_failures + 1))
        fi
    elif ((status == 1)) && grep -q '^facet: error: ' "$work/messages"; then
        grep '^facet: error: ' "$work/messages" | sed -e 's/^facet: error: //' -e "s|^|$name\trefused\t|"
    else
        printf '%s\tfailed (exit status %d)\t%s\n' "$name" "$status" "$(tr '\n' ' ' < "$work/messages")"
    fi
done < <(find "$shared" -name '*.obj' -type f -print0 | LC_ALL=C sort -z) >> "$actual"

models() { grep -v '^#' "$1" | cut -f1 | sort -u | wc -l; }
count() { grep -v '^#' "$1" | cut -f1,2 | sort -u | cut -f2 | grep -c -x "$2"; }
summary="$(models "$actual") models: $(count "$actual" rendered) rendered, $(count "$actual" 'rendered with warnings') rendered with warnings, $(count "$actual" refused) refused"

if [[ $update == --update ]]; then
    cp "$actual" "$table"
    echo "wrote $table ($summary)"
    exit $((blank_failures > 0))
fi
if ! diff -u "$table" "$actual"; then
    echo
    echo "The outcome of a shared model changed (- the table, + this run): $summary."
    echo "If the change is intended, regenerate the table and review its diff:"
    echo "  bash tests/cli/shared_models_table.sh $facet $source_dir --update"
    exit 1
fi
((blank_failures == 0)) || exit 1
echo "$summary, as tabled"
