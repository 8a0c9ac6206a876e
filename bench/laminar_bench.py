#!/usr/bin/env python3
"""Interleaved benchmark of the internal-flow cases: `sph run` of the
Taylor-Green vortex (cases/taylor_green_2d.case, periodic xy, Morris
viscosity, continuity + delta) with particle shifting on and off, and of the
plane Poiseuille flow (cases/poiseuille_2d.case, periodic x, dummy walls),
beside the pair-loop yardstick (bench/yardstick_pairloop.cpp) at the same N
and thread count; one repeat of each in turn, medians over the repeats.

  bench/laminar_bench.py [--build build] [--threads 1,2] [--repeats 3] [--steps 400]

Figures: particle-steps per second from sph's summary (stepping time, no
output), neighbours per particle, the ratio to the yardstick, and the cost
of shifting per step (time per step with it / without it - 1). Printed,
never asserted; `uptime` before and after tells how busy the machine was.
"""
import argparse
import os
import re
import statistics
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = os.path.join(HERE, "..", "cases")


def run(cmd, env=None):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env).stdout


def yardstick_run(exe, n, threads, steps, hdx=1.3):
    """The yardstick at about n particles: (N, neighbours, particle-steps per second)."""
    nx = max(2, round((n / 2) ** 0.5))
    out = run([exe, str(nx), str(steps), str(hdx)], dict(os.environ, OMP_NUM_THREADS=str(threads)))
    m = re.search(r"N=(\d+) threads=\d+ neighbours=([\d.]+) particle-steps/s=([\d.e+]+)", out)
    return int(m.group(1)), float(m.group(2)), float(m.group(3))


def sph_run(exe, case, flags, threads, steps, dt, work):
    out = run([exe, "run", os.path.join(CASES, case), "--output", work, "--overwrite", "--no-progress",
               "--threads", str(threads), "--end_time", repr(steps * dt), "--output_every", str(10 * steps)] + flags)
    m = re.search(r"throughput\s+([\d.e+]+) particle-steps/s", out)
    nb = re.search(r"neighbours\s+([\d.]+) per particle", out)
    n = re.search(r"particles\s+(\d+)", out)
    if not (m and nb and n):
        raise SystemExit("sph run failed:\n" + out)
    return int(n.group(1)), float(nb.group(1)), float(m.group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=400)
    a = ap.parse_args()
    exe = os.path.join(a.build, "sph")
    ys = os.path.join(a.build, "sph-yardstick")
    scenarios = [
        ("taylor_green 50x50, shifting", "taylor_green_2d.case", [], 5e-4),
        ("taylor_green 50x50, no shifting", "taylor_green_2d.case", ["--shifting", "none"], 5e-4),
        ("taylor_green 100x100, shifting", "taylor_green_2d.case",
         ["--spacing", "0.01", "--h", "0.015", "--dt", "2.5e-4"], 2.5e-4),
        ("taylor_green 100x100, no shifting", "taylor_green_2d.case",
         ["--spacing", "0.01", "--h", "0.015", "--dt", "2.5e-4", "--shifting", "none"], 2.5e-4),
        ("poiseuille 25 across", "poiseuille_2d.case", [], 2.5e-4),
    ]
    print("# uptime before:", run(["uptime"]).strip())
    print(f"# {a.repeats} interleaved repeats of {a.steps} steps; medians; p-s/s = particle-steps per second (2D)")
    print(f"{'scenario':36s} {'N':>6s} {'thr':>3s} {'nbrs':>5s} {'p-s/s':>10s} {'yardstick':>10s} {'ratio':>6s}")
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for threads in [int(t) for t in a.threads.split(",")]:
            samples = {name: [] for name, *_ in scenarios}
            ysamples = {name: [] for name, *_ in scenarios}
            info = {}
            for _ in range(a.repeats):
                for name, case, flags, dt in scenarios:
                    n, nb, ps = sph_run(exe, case, flags, threads, a.steps, dt, os.path.join(work, "run"))
                    samples[name].append(ps)
                    info[name] = (n, nb)
                    ysamples[name].append(yardstick_run(ys, n, threads, max(20, a.steps // 4), hdx=1.5)[2])
            for name, *_ in scenarios:
                n, nb = info[name]
                ps, y = statistics.median(samples[name]), statistics.median(ysamples[name])
                results[(name, threads)] = ps
                print(f"{name:36s} {n:6d} {threads:3d} {nb:5.1f} {ps:10.3e} {y:10.3e} {ps / y:6.2f}")
    for threads in [int(t) for t in a.threads.split(",")]:
        for size in ("50x50", "100x100"):
            on = results[(f"taylor_green {size}, shifting", threads)]
            off = results[(f"taylor_green {size}, no shifting", threads)]
            print(f"# shifting costs {off / on - 1:+.1%} per step (taylor_green {size}, {threads} thread(s))")
    print("# uptime after:", run(["uptime"]).strip())


if __name__ == "__main__":
    main()
