#!/usr/bin/env python3
"""Ranks against threads: the 2D water dam break (cases/dam_break.case, full
water physics) at a given particle spacing, run as 1 rank x 1 thread, 1 rank
x 2 threads and 2 MPI ranks x 1 thread, interleaved, several times each.
Prints the median stepping seconds per step (run.json's stepping_seconds,
so the set-up and the first snapshot are left out), particle-steps per
second and the ratio against 1 x 1 measured in the same rounds.

    python3 bench/mpi_ranks.py --build build --spacing 0.00125 --steps 100 --repeats 3

h = 1.5 spacing and dt = 5e-5 spacing / 0.01 (the case's acoustic CFL);
no snapshot but the first and the last. As root, mpirun needs
--allow-run-as-root (added); --oversubscribe lets 2 ranks start on a
machine whose other core is busy (the figures then say so: quote `uptime`).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile


def run(build, config, spacing, steps, out):
    ranks, threads = config
    dt = 5e-5 * spacing / 0.01
    end = steps * dt
    args = [os.path.join(build, "sph"), "run", os.path.join(os.path.dirname(__file__), "..", "cases", "dam_break.case"),
            "--spacing", repr(spacing), "--h", repr(1.5 * spacing), "--dt", repr(dt), "--end_time", repr(end),
            "--output_interval", repr(end), "--threads", str(threads), "--output", out, "--overwrite",
            "--no-progress"]
    if ranks > 1:
        args = ["mpirun", "--oversubscribe", "--allow-run-as-root", "-n", str(ranks)] + args
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    done = subprocess.run(args, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.exit(f"failed ({ranks} x {threads}): {done.stdout[-400:]} {done.stderr[-400:]}")
    with open(os.path.join(out, "run.json")) as f:
        record = json.load(f)
    s = record["summary"]
    return s["stepping_seconds"] / s["steps"], s["particles"], s["neighbours_per_particle"], s["bytes_per_particle"]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default="build")
    p.add_argument("--spacing", type=float, default=0.00125)
    p.add_argument("--steps", type=int, default=100)
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args()
    configs = [(1, 1), (1, 2), (2, 1)]
    times = {c: [] for c in configs}
    info = None
    tmp = tempfile.mkdtemp(prefix="sph_mpi_ranks_")
    try:
        for _ in range(a.repeats):
            for c in configs:
                t, n, nb, bpp = run(a.build, c, a.spacing, a.steps, os.path.join(tmp, f"r{c[0]}t{c[1]}"))
                times[c].append(t)
                info = (n, nb, bpp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    n, nb, bpp = info
    load = open("/proc/loadavg").read().split()[:3]
    print(f"2D dam break, spacing {a.spacing} m: N = {n} particles, {nb:.1f} neighbours per particle, "
          f"{bpp:.0f} bytes per particle (all ranks), {a.steps} steps, median of {a.repeats}; load {' '.join(load)}")
    print("| ranks x threads | s per step | particle-steps/s | vs 1 x 1 |")
    print("|---|---|---|---|")
    base = statistics.median(times[(1, 1)])
    for c in configs:
        m = statistics.median(times[c])
        print(f"| {c[0]} x {c[1]} | {m:.4f} | {n / m:.3g} | {base / m:.2f} |")


if __name__ == "__main__":
    main()
