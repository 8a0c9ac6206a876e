"""Ranks against threads: the water dam break (full water physics) at a given
particle spacing, run as 1 rank x 1 thread, 1 rank x 2 threads and 2 MPI
ranks x 1 thread, interleaved, several times each. Prints the median
stepping seconds per step (run.json's stepping_seconds, so the set-up and
the first snapshot are left out), particle-steps per second, the ratio
against 1 x 1 measured in the same rounds, and the 2-rank runs' work
balance (run.json's work_imbalance: the busiest rank's pairs + particles
over the mean), their time communicating a step (run.json's
communication_per_step: halo refreshes, reductions and the re-sort's
exchanges, the waits for the other rank included, mean of the ranks; its
share of the step; and the least of the ranks', about the messages' cost
without waiting) and halo particles per owned particle.

    python3 bench/mpi_ranks.py --build build --spacing 0.00125 --steps 100 --repeats 3
    python3 bench/mpi_ranks.py --dimension 3 --spacing 0.0073 --steps 20
    python3 bench/mpi_ranks.py --weak --spacing 0.0025 --steps 100 --ranks 1 2 4

2D: cases/dam_break.case (Adami dummy walls, continuity + delta-SPH, Tait),
h = 1.5 spacing and dt = 5e-5 spacing / 0.01 (the case's acoustic CFL).
3D: cases/dam_break_3d.case (its walls reflect: no wall particles), h =
spacing and a fixed dt = 2.4e-4 spacing / 0.016 (the case's CFL 0.3 at
c = 20 m/s). No snapshot but the first and the last. --weak: the particles
per rank held (spacing R^(-1/D) times the given one on R ranks x 1 thread),
the time per step against 1 rank; more ranks than cores are marked
oversubscribed. As root, mpirun needs --allow-run-as-root (added);
--oversubscribe lets 2 ranks start on a machine whose other core is busy
(the figures then say so: quote the load printed).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile


CASES = {  # dimension: case file, h / spacing, dt / spacing, extra keys
    2: ("dam_break.case", 1.5, 5e-5 / 0.01, []),
    3: ("dam_break_3d.case", 1.0, 2.4e-4 / 0.016, ["--cfl", "0"]),
}


def run(build, config, spacing, steps, out, dimension=2):
    ranks, threads = config
    case, h_ratio, dt_ratio, extra = CASES[dimension]
    dt = dt_ratio * spacing
    end = steps * dt
    args = [os.path.join(build, "sph"), "run", os.path.join(os.path.dirname(__file__), "..", "cases", case),
            "--spacing", repr(spacing), "--h", repr(h_ratio * spacing), "--dt", repr(dt), "--end_time", repr(end),
            "--output_interval", repr(end), "--threads", str(threads), "--output", out, "--overwrite",
            "--no-progress"] + extra
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
    return {"time": s["stepping_seconds"] / s["steps"], "n": s["particles"], "neighbours": s["neighbours_per_particle"],
            "bytes": s["bytes_per_particle"], "imbalance": record.get("work_imbalance", 1.0),
            "balances": record.get("balances", 1), "halo_fraction": record.get("halo_fraction", 0.0),
            "communication": sum(record.get("communication_per_step", {}).get(k, 0.0)
                                 for k in ("halo_seconds", "reduction_seconds", "resort_seconds")),
            "least": record.get("communication_per_step", {}).get("least_of_the_ranks_seconds", 0.0)}


def load():
    return " ".join(open("/proc/loadavg").read().split()[:3])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default="build")
    p.add_argument("--dimension", type=int, choices=(2, 3), default=2)
    p.add_argument("--spacing", type=float, default=0.00125)
    p.add_argument("--steps", type=int, default=100)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--weak", action="store_true", help="weak scaling: the particles per rank held")
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2], help="--weak: the rank counts")
    a = p.parse_args()
    D = a.dimension
    if a.weak:
        configs = [(r, 1) for r in a.ranks]
        spacing = {c: a.spacing * c[0] ** (-1.0 / D) for c in configs}
    else:
        configs = [(1, 1), (1, 2), (2, 1)]
        spacing = {c: a.spacing for c in configs}
    results = {c: [] for c in configs}
    tmp = tempfile.mkdtemp(prefix="sph_mpi_ranks_")
    try:
        for _ in range(a.repeats):
            for c in configs:
                results[c].append(run(a.build, c, spacing[c], a.steps, os.path.join(tmp, f"r{c[0]}t{c[1]}"), D))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    cores = os.cpu_count() or 1
    first = results[configs[0]][-1]
    print(f"{D}D dam break ({CASES[D][0]}), {'weak scaling from ' if a.weak else ''}spacing {a.spacing} m: "
          f"N = {first['n']} particles, {first['neighbours']:.1f} neighbours per particle, {first['bytes']:.0f} bytes "
          f"per particle (all ranks), {a.steps} steps, median of {a.repeats}; {cores} cores, load {load()}")
    base = statistics.median(r["time"] for r in results[configs[0]])
    if a.weak:
        print("| ranks x threads | particles | per rank | s per step | particle-steps/s | efficiency (t1 / tR) | "
              "work imbalance | communicating a step | halo per owned |")
        print("|---|---|---|---|---|---|---|---|---|")
    else:
        print("| ranks x threads | s per step | particle-steps/s | vs 1 x 1 | work imbalance | communicating a step | "
              "halo per owned |")
        print("|---|---|---|---|---|---|---|")
    for c in configs:
        m = statistics.median(r["time"] for r in results[c])
        last = results[c][-1]
        n = last["n"]
        imbalance = f"{last['imbalance']:.3f} ({last['balances']} shares)" if c[0] > 1 else "-"
        talk = statistics.median(r["communication"] for r in results[c])
        least = statistics.median(r["least"] for r in results[c])
        comm = (f"{1e3 * talk:.3g} ms ({100 * talk / m:.1f}%; least rank {1e3 * least:.3g}) | "
                f"{last['halo_fraction']:.3f}" if c[0] > 1 else "- | -")
        marked = " (oversubscribed)" if c[0] * c[1] > cores else ""
        if a.weak:
            print(f"| {c[0]} x {c[1]}{marked} | {n} | {n // c[0]} | {m:.4f} | {n / m:.3g} | {base / m:.2f} | {imbalance} | {comm} |")
        else:
            print(f"| {c[0]} x {c[1]}{marked} | {m:.4f} | {n / m:.3g} | {base / m:.2f} | {imbalance} | {comm} |")


if __name__ == "__main__":
    main()
