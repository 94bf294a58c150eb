#!/usr/bin/env python3
"""Start-up time: `penumbra --version`, `plan` and `check` of a small scene, each run
many times in turns with an older binary (old, new, old, new, ...), so both see the
same machine load. Prints each command's median wall and CPU (user + sys) seconds.

Usage: scripts/bench_startup.py [--runs N] [--scene SCENE] NEW_PENUMBRA [OLD_PENUMBRA]
"""
import argparse
import os
import pathlib
import resource
import statistics
import subprocess
import time

root = pathlib.Path(__file__).resolve().parent.parent
parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("new")
parser.add_argument("old", nargs="?")
parser.add_argument("--runs", type=int, default=20)
parser.add_argument("--scene", default=str(root / "scenes" / "fig03_shadows.json"))
args = parser.parse_args()

commands = {"--version": ["--version"], "plan": ["plan", args.scene], "check": ["check", args.scene]}
binaries = {"new": args.new} | ({"old": args.old} if args.old else {})


def timed(argv):
    """Wall and CPU seconds of one run (the child's rusage, not this script's)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


times = {(c, b): [] for c in commands for b in binaries}
for _ in range(args.runs):
    for c, argv in commands.items():
        for b, path in binaries.items():
            times[(c, b)].append(timed([path] + argv))

print(f"penumbra start-up, median of {args.runs} runs interleaved, load {os.getloadavg()[0]:.2f} at end")
print(f"{'command':12s} " + " ".join(f"{b + ' wall':>9s} {b + ' cpu':>8s}" for b in binaries))
for c in commands:
    cells = []
    for b in binaries:
        runs = times[(c, b)]
        cells.append(f"{statistics.median(w for w, _ in runs):9.3f} {statistics.median(u for _, u in runs):8.3f}")
    print(f"{c:12s} " + " ".join(cells))
