#!/usr/bin/env bash
# Runs a command as if OSMesa were not installed, to try the test suite's second CI pass (.ci/run)
# on a machine that keeps its Mesa:
#
#   tests/support/without-osmesa.sh ctest --test-dir build --output-on-failure -j2
#
# Facet loads libOSMesa.so.8 with dlopen (src/oracle/mesa_peer.cpp), which reads no variable of ours and
# finds the library through the loader's cache and its default folders. So the command runs in a mount
# namespace of its own where an overlay on the library's folder whites out every libOSMesa.so* name:
# dlopen fails with "No such file or directory", as after `apt-get remove libosmesa6`, while every
# other library stays. Nothing changes outside the command (other users of the machine keep OSMesa).
# Needs root (or CAP_SYS_ADMIN), unshare(1) and overlayfs. Without OSMesa installed, runs the command.
set -euo pipefail
if [ $# -eq 0 ]; then
    echo "usage: $0 COMMAND [ARGUMENT...]" >&2
    exit 2
fi

# awk reads the whole list: leaving early would end ldconfig with SIGPIPE, which pipefail turns into exit 141.
library=$(ldconfig -p | awk '$1 == "libOSMesa.so.8" && !found {print $NF; found = 1}')
if [ -z "$library" ]; then
    exec "$@"
fi
folder=$(dirname "$(readlink -f "$library")")

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/upper" "$scratch/work"
for file in "$folder"/libOSMesa.so*; do
    mknod "$scratch/upper/$(basename "$file")" c 0 0  # an overlay whiteout: the name is gone
done

unshare --mount --propagation private -- sh -c '
    folder=$1 scratch=$2
    shift 2
    mount -t overlay overlay -o "lowerdir=$folder,upperdir=$scratch/upper,workdir=$scratch/work" "$folder"
    exec "$@"' sh "$folder" "$scratch" "$@"
