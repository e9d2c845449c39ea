#!/usr/bin/env bash
# facet render --shard on a real scheduler: a one-node Slurm cluster of the test's own (munged,
# slurmctld, slurmd, root, everything in a temporary folder and on free ports) runs a job array of 4
# tasks, each `facet render --list LIST --shard $SLURM_ARRAY_TASK_ID/4`. Every image of the list must be
# written by exactly one task and be the bytes of a batch rendered in one process. Then the job file of
# docs/batch/ runs as docs/batch.md submits it. The daemons are stopped on every exit (their logs printed
# when something failed), and no step waits forever.
# Run by ctest as Batch.SlurmJobArray: slurm_array_test.sh FACET SOURCE_DIR.
# Exits 77 (ctest's skip) without root or without the Debian packages slurmctld, slurmd, slurm-client and
# munge; a cluster running on the machine already does not matter (own socket, ports and state).
set -euo pipefail
facet=$(realpath "$1")
root=$(realpath "$2")

for program in munged slurmctld slurmd sbatch squeue sinfo scancel; do
    if ! command -v "$program" > /dev/null && ! [ -x "/usr/sbin/$program" ]; then
        echo "skipped: the test needs $program (Debian packages slurmctld slurmd slurm-client munge)"
        exit 77
    fi
done
if ! command -v python3 > /dev/null; then
    echo "skipped: the test needs python3 (to find free ports)"
    exit 77
fi
if [ "$(id -u)" != 0 ]; then
    echo "skipped: the test starts munged, slurmctld and slurmd as root"
    exit 77
fi
PATH=$PATH:/usr/sbin
job_timeout=${FACET_SLURM_JOB_TIMEOUT:-300}  # seconds for the whole job array

work=$(mktemp -d /tmp/facet-slurm.XXXXXX)
chmod 700 "$work"
host=$(hostname -s)
export SLURM_CONF=$work/slurm.conf
daemons=()  # "name pid" of every daemon started here
# Each daemon gets SIGTERM should this script die without its cleanup (SIGKILL, as on a timeout of ctest).
with_parent=(setpriv --pdeathsig TERM)

print_logs() {
    for log in "$work"/slurmctld.log "$work"/slurmd.log "$work"/*.out "$work"/jobs/*.out "$work"/logs/*.out; do
        [ -f "$log" ] || continue
        echo "---- $log (last 100 lines)"
        tail -n 100 "$log"
    done
}

# stop PID NAME: SIGTERM, then SIGKILL after 10 s.
stop() {
    local pid=$1 name=$2
    kill -TERM "$pid" 2> /dev/null || return 0
    for _ in $(seq 100); do
        kill -0 "$pid" 2> /dev/null || return 0
        sleep 0.1
    done
    echo "$name ($pid) still runs 10 s after SIGTERM: SIGKILL"
    kill -KILL "$pid" 2> /dev/null || true
}

cleanup() {
    local status=$?
    trap - EXIT INT TERM
    if [ "$status" != 0 ]; then
        echo "FAILED (status $status); the daemons' logs:"
        print_logs
    fi
    # The jobs first (their steps outlive slurmd), then the daemons in the reverse order of their start.
    if [ "${#daemons[@]}" -ge 2 ]; then
        scancel --full --quiet --user=root 2> /dev/null || true
        for _ in $(seq 100); do
            [ -z "$(squeue -h 2> /dev/null)" ] && break
            sleep 0.2
        done
        # And the steps' processes on the node, which slurmd lists (a header line when there are none).
        for _ in $(seq 100); do
            [ "$(scontrol listpids 2> /dev/null | wc -l)" -le 1 ] && break
            sleep 0.2
        done
    fi
    local k
    for ((k = ${#daemons[@]} - 1; k >= 0; k--)); do
        read -r name pid <<< "${daemons[$k]}"
        stop "$pid" "$name"
    done
    rm -rf "$work"
    exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# wait_until SECONDS WHAT COMMAND...: runs COMMAND every 0.2 s until it succeeds; fails after SECONDS.
wait_until() {
    local seconds=$1 what=$2
    shift 2
    local deadline=$((SECONDS + seconds))
    until "$@" > /dev/null 2>&1; do
        if [ "$SECONDS" -ge "$deadline" ]; then
            echo "timed out after $seconds s waiting for $what"
            return 1
        fi
        sleep 0.2
    done
}

files_in() { find "$1" -mindepth 1 -maxdepth 1 | wc -l; }

# Two TCP ports nobody listens on, for slurmctld and slurmd.
read -r ctld_port slurmd_port < <(python3 -c '
import socket
sockets = [socket.socket() for _ in range(2)]
for s in sockets:
    s.bind(("127.0.0.1", 0))
print(*(s.getsockname()[1] for s in sockets))')

# ---- munge: a key of its own (owned by root, 0400 in a 0700 folder), its own socket.
mkdir -m 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
"${with_parent[@]}" munged --foreground --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
    --pid-file="$work/munge/munged.pid" --seed-file="$work/munge/munged.seed" \
    --log-file="$work/munged.log" > "$work/munged.out" 2>&1 &
daemons+=("munged $!")
wait_until 20 "munged's socket" test -S "$work/munge/munge.socket"

# ---- slurm.conf: one node (this machine, 2 CPUs), root everywhere, no cgroups, state in $work.
mkdir -m 700 "$work/state" "$work/spool" "$work/jobs"
cat > "$SLURM_CONF" << EOF
ClusterName=facettest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
PlugStackConfig=$work/plugstack.conf
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
: > "$work/plugstack.conf"

"${with_parent[@]}" slurmctld -D -i -f "$SLURM_CONF" > "$work/slurmctld.out" 2>&1 &
daemons+=("slurmctld $!")
wait_until 30 "slurmctld to answer" sinfo
"${with_parent[@]}" slurmd -D -f "$SLURM_CONF" -N "$host" > "$work/slurmd.out" 2>&1 &
daemons+=("slurmd $!")
node_idle() { [ "$(sinfo -h -n "$host" -o %t)" = idle ]; }
wait_until 60 "node $host to be idle" node_idle

# ---- the list: the bundled models, two of them copied under other names, and two scenes.
mkdir "$work/copies"
cp "$root/models/spot/spot_triangulated.obj" "$work/copies/cow.obj"
cp "$root/models/spot/spot.mtl" "$root/models/spot/spot_texture.png" "$work/copies/"
cp "$root/models/cube/cube.obj" "$work/copies/box.obj"
cp "$root/models/cube/default.mtl" "$root/models/cube/default.png" "$work/copies/"
cat > "$work/models.txt" << EOF
# the bundled models, by absolute paths
$root/models/spot/spot_triangulated.obj
$root/models/cube/cube.obj
$root/models/shared-edge/two-triangles.obj
$root/models/intersecting-quads/quads.obj
$root/models/near-plane/wedge.obj
$root/models/fog-and-glass/ground.obj

# copies under other names, relative to the list's folder
copies/cow.obj
copies/box.obj
$root/models/example-scene.json
$root/models/shared-edge.json
EOF
items=$(grep -cv -e '^#' -e '^$' "$work/models.txt")

# ---- the job array: 4 tasks, each its shard of the list.
mkdir "$work/images" "$work/reference"
cat > "$work/render-array.sbatch" << EOF
#!/bin/bash
#SBATCH --job-name=facet-batch-test
#SBATCH --array=0-3
#SBATCH --cpus-per-task=1
#SBATCH --output=$work/jobs/%A_%a.out
'$facet' render --list '$work/models.txt' --shard \$SLURM_ARRAY_TASK_ID/4 -o '$work/images/{name}.png' \\
    --width 128 --height 96
EOF
echo "+ sbatch --wait --array=0-3 (a list of $items inputs)"
status=0
timeout "$job_timeout" sbatch --wait --array=0-3 "$work/render-array.sbatch" || status=$?
if [ "$status" = 124 ]; then
    echo "the job array did not end within $job_timeout s"
    exit 1
elif [ "$status" != 0 ]; then
    echo "sbatch --wait failed with status $status (a task failed)"
    exit 1
fi
tasks=$(find "$work/jobs" -name '*.out' | wc -l)
if [ "$tasks" != 4 ]; then
    echo "expected the output of 4 array tasks, found $tasks"
    exit 1
fi

# ---- the check: the same list in one process; every image exactly once, the same bytes.
"$facet" render --list "$work/models.txt" -o "$work/reference/{name}.png" --width 128 --height 96 -q
failed=0
cat "$work"/jobs/*.out | sed -n 's/^facet: wrote \([^ ]*\) .*/\1/p' | sort > "$work/written.txt"
duplicates=$(uniq -d "$work/written.txt")
if [ -n "$duplicates" ]; then
    echo "written by more than one task: $duplicates"
    failed=1
fi
if [ "$(wc -l < "$work/written.txt")" != "$items" ]; then
    echo "the tasks wrote $(wc -l < "$work/written.txt") images, the list has $items inputs"
    failed=1
fi
for reference in "$work"/reference/*.png; do
    image=$work/images/$(basename "$reference")
    if ! cmp "$reference" "$image"; then
        echo "$image differs from the one-process batch's (or is missing)"
        failed=1
    fi
done
if [ "$(files_in "$work/images")" != "$items" ] || [ "$(files_in "$work/reference")" != "$items" ]; then
    echo "expected $items images in each folder: $(files_in "$work/images") from the array," \
        "$(files_in "$work/reference") from one process"
    failed=1
fi
[ "$failed" = 0 ] || exit 1
echo "ok: $items images from 4 array tasks, each written once, the bytes of one process's batch"

# ---- docs/batch/render-array.sbatch as docs/batch.md submits it (facet on the PATH, LIST and OUT in
# the environment), as an array of 3; what this one-node cluster cannot give is overridden: 1 CPU a task,
# no memory request.
mkdir "$work/bin" "$work/logs"
ln -s "$facet" "$work/bin/facet"
echo "+ sbatch --wait --array=0-2 docs/batch/render-array.sbatch"
status=0
(cd "$work" && PATH=$work/bin:$PATH LIST=$work/models.txt OUT=$work/doc-images \
    timeout "$job_timeout" sbatch --wait --array=0-2 --cpus-per-task=1 --mem=0 \
    "$root/docs/batch/render-array.sbatch") || status=$?
if [ "$status" != 0 ]; then
    echo "docs/batch/render-array.sbatch failed with status $status (124: timed out after $job_timeout s)"
    exit 1
fi
cat "$work"/logs/facet-render-*.out | sed -n 's/^facet: wrote \([^ ]*\) .*/\1/p' | sort > "$work/doc-written.txt"
if [ "$(files_in "$work/logs")" != 3 ] || [ -n "$(uniq -d "$work/doc-written.txt")" ] ||
    [ "$(wc -l < "$work/doc-written.txt")" != "$items" ] || [ "$(files_in "$work/doc-images")" != "$items" ]; then
    echo "docs/batch/render-array.sbatch: expected 3 task logs and $items images each written once;" \
        "the images written:"
    cat "$work/doc-written.txt"
    exit 1
fi
echo "ok: docs/batch/render-array.sbatch rendered the $items images in 3 tasks"
