#!/usr/bin/env python3
"""End to end, Facet against a plain OpenGL program (../shared/glref, Mesa llvmpipe): the same model
loaded, rendered at 1920x1080 on two threads and written to PNG, the two programs alternating so that a
slow spell of the machine falls on both. Prints each one's median and fastest wall time and their ratio,
and the median CPU time (user + system, all threads) and minor page faults of each program's runs.

    ../shared/glref/build.sh /tmp/glref
    python3 src/bench/end_to_end.py [--rounds 25] [--glref /tmp/glref/glref] [--facet build/src/facet] [MODEL]
"""
import argparse
import os
import statistics
import subprocess
import time

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("model", nargs="?", default="../shared/models/stanford-bunny/stanford-bunny.obj")
parser.add_argument("--rounds", type=int, default=25)
parser.add_argument("--glref", default="/tmp/glref/glref")
parser.add_argument("--facet", default="build/src/facet")
args = parser.parse_args()

commands = {
    "glref (llvmpipe)": [args.glref, "--fit", "--width", "1920", "--height", "1080", "--shade", "blinn",
                         "--mat-specular", "1,1,1", "--shininess", "32", "--out", "/tmp/end-to-end-glref.png",
                         args.model],
    "facet": [args.facet, "render", args.model, "--width", "1920", "--height", "1080", "--threads", "2",
              "-o", "/tmp/end-to-end-facet.png", "-q"],
}
environment = dict(os.environ, LP_NUM_THREADS="2")
seconds = {name: [] for name in commands}
cpu_seconds = {name: [] for name in commands}
minor_faults = {name: [] for name in commands}
for _ in range(args.rounds):
    for name, command in commands.items():
        start = time.perf_counter()
        child = subprocess.Popen(command, env=environment, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(child.pid, 0)
        seconds[name].append(time.perf_counter() - start)
        child.returncode = os.waitstatus_to_exitcode(status)
        if child.returncode != 0:
            raise SystemExit(f"{' '.join(command)} exited with {child.returncode}")
        cpu_seconds[name].append(usage.ru_utime + usage.ru_stime)
        minor_faults[name].append(usage.ru_minflt)
for name, times in seconds.items():
    print(f"{name:18} median {statistics.median(times) * 1000:7.1f} ms   fastest {min(times) * 1000:7.1f} ms   "
          f"CPU {statistics.median(cpu_seconds[name]) * 1000:7.1f} ms   "
          f"minor faults {statistics.median(minor_faults[name]):7.0f}")
facet, peer = seconds["facet"], seconds["glref (llvmpipe)"]
print(f"facet / glref: {statistics.median(facet) / statistics.median(peer):.3f} (medians), "
      f"{min(facet) / min(peer):.3f} (fastest runs); {args.rounds} alternating rounds")
