#!/bin/bash
# Fuzz.ReadersAndPipelineCarryCoverageCounters: every object file of the libraries the fuzz targets read
# and draw with (given as static libraries) holds libFuzzer's coverage counters (the __sancov_cntrs
# section that -fsanitize=fuzzer-no-link adds), so the fuzzers are guided through that code, not only
# through their own files (tests/fuzz/CMakeLists.txt, facet_fuzz_coverage).
# Usage: coverage_test.sh LIBRARY.a...
set -euo pipefail
missing=0
for library in "$@"; do
    objects=0
    while read -r object has_counters; do
        objects=$((objects + 1))
        if [ "$has_counters" = 0 ]; then
            echo "$(basename "$library"): $object has no coverage counters (compiled without -fsanitize=fuzzer-no-link)"
            missing=1
        fi
    done < <(objdump -h "$library" |
        awk '/file format/ {object = $1; sub(/:$/, "", object); seen[object] = 0}
             /__sancov_cntrs/ {seen[object] = 1}
             END {for (o in seen) print o, seen[o]}')
    # objdump's failure (a missing or unreadable library) is not seen through the pipe: no object is.
    if [ "$objects" = 0 ]; then
        echo "$library: no object files read"
        missing=1
    fi
done
[ "$missing" = 0 ] && echo "every object of the $# libraries carries coverage counters"
