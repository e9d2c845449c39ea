#!/bin/bash
# One facet binary runs on every x86-64 CPU (src/render/frame_kernels.h): on CPUs narrower than this
# machine's, emulated by QEMU's user mode, it chooses the copy of the frame's code that CPU runs and
# writes the same bytes as it does natively here:
#   qemu64   SSE2 and SSE3 only (no SSE4, no AVX): the baseline copy
#   Nehalem  SSE4.2, no AVX: the baseline copy
#   Haswell  AVX2, FMA, F16C, no AVX-512: the avx2 copy
# An AVX instruction anywhere on the baseline path (the program's own code, or an inline function of
# a wider copy that the linker let replace the baseline one) stops the emulated run with SIGILL. Where
# the CPU has no AVX2, FACET_ISA=avx2 must be refused with one line of error.
# QEMU emulates no AVX-512, so the avx512 copy is compared natively (tests/render/frame_kernels_test.cpp).
# Usage: other_cpus_test.sh FACET SOURCE_DIR. Exit 77 (skipped) without qemu-x86_64 (Debian: qemu-user).
set -euo pipefail
facet=$1
source=$2
qemu=$(command -v qemu-x86_64) || {
    echo "skipped: no qemu-x86_64 (apt-get install qemu-user)"
    exit 77
}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# What each case renders: the textured model with the defaults; a scene with fog, glass and sorted
# transparency; one with ray-cast shadows (Embree); multisampling into a half-float colour buffer;
# exact transparency's fragment lists; flat shading with Cook-Torrance.
cases=(
    "spot|$source/models/spot/spot_triangulated.obj"
    "fog-and-glass|$source/models/fog-and-glass.json"
    "shadows|$source/models/shadows.json"
    "msaa-half|$source/models/spot/spot_triangulated.obj --aa msaa4 --color-buffer half"
    "exact|$source/models/fog-and-glass.json --transparency exact"
    "flat-ct|$source/models/spot/spot_triangulated.obj --shading flat --reflection cook-torrance"
)

render() {  # render OUTPUT CASE [launcher…]: one case at 128×96 on two threads
    local output=$1 spec=$2
    shift 2
    local args
    read -r -a args <<<"${spec#*|}"
    "$@" "$facet" render "${args[@]}" --width 128 --height 96 --threads 2 -o "$output" >/dev/null
}

for spec in "${cases[@]}"; do
    render "$work/${spec%%|*}-native.png" "$spec"
done

failed=0
for cpu_and_copy in "qemu64 baseline" "Nehalem baseline" "Haswell avx2"; do
    read -r cpu copy <<<"$cpu_and_copy"
    emulated=("$qemu" -cpu "$cpu")
    # TCG warns about CPU features it cannot emulate (pcid, x2apic…), which the program does not use.
    version=$("${emulated[@]}" "$facet" --version 2>/dev/null) || {
        echo "FAIL $cpu: facet --version exited $?"
        failed=1
        continue
    }
    if [[ $version != *"frame code: $copy (widest this CPU runs: $copy;"* ]]; then
        echo "FAIL $cpu: expected the $copy copy, facet --version says: ${version//$'\n'/ | }"
        failed=1
    fi
    # Forcing a copy this CPU cannot run is one line of error and exit 1, never an illegal instruction.
    if [[ $copy == baseline ]]; then
        status=0
        FACET_ISA=avx2 "${emulated[@]}" "$facet" render "$source/models/cube/cube.obj" -o "$work/refused.png" \
            >/dev/null 2>"$work/refusal" || status=$?
        refusal=$(grep -v 'TCG doesn.t support' "$work/refusal" || true)
        if [[ $status -ne 1 || -e $work/refused.png ||
            $refusal != "facet: error: FACET_ISA=avx2: this CPU cannot run avx2 instructions (it runs: baseline)" ]]; then
            echo "FAIL $cpu: FACET_ISA=avx2 was not refused as expected (exit $status): $refusal"
            failed=1
        else
            echo "ok   $cpu: FACET_ISA=avx2 refused: $refusal"
        fi
    fi
    for spec in "${cases[@]}"; do
        name=${spec%%|*}
        if ! render "$work/$name-$cpu.png" "$spec" "${emulated[@]}" 2>"$work/stderr"; then
            echo "FAIL $cpu $name: the emulated run failed: $(grep -v 'TCG doesn.t support' "$work/stderr" | tail -1)"
            failed=1
        elif ! cmp -s "$work/$name-native.png" "$work/$name-$cpu.png"; then
            echo "FAIL $cpu $name: the image differs from the native one"
            failed=1
        else
            echo "ok   $cpu ($copy copy) $name: the same bytes as natively"
        fi
    done
done
exit $failed
