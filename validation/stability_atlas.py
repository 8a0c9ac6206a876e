#!/usr/bin/env python3
"""Stability atlas, the time step: the largest stable C = c dt / h of a
method, found by bisection, against the linear acoustic stability limit of
tests/reference/acoustic_cfl_limits.csv (nobody here wrote it).

The setting the reference was derived for: a fluid at rest on a periodic
lattice (no walls, no gravity, no viscosity), linear EOS (c = 10 m/s),
continuity density, h/dx = 1.3. Each trial: 16 x 16 particles in a fully
periodic box, velocities a small random field (1e-4 c, seeded), N steps;
the trial is unstable when the kinetic energy grows by more than a factor
100 (an unstable acoustic mode grows exponentially; stable modes keep their
energy) or the run blows up.

  stability_atlas.py --sph build/sph --workdir DIR [--integrator leap_frog]
                     [--kernel cubic_spline] [--density continuity]
                     [--steps 1500] [--check]

Prints the threshold, the reference, their ratio, and (with --check) fails
when the threshold is more than 5% off the reference (the issue's
tolerance; summation density linearises to the same acoustic system: the bisection brackets it to 0.5%, and near the limit an
unstable mode's growth per step is small, so the measured threshold sits a
little above the linear one). Appends a row to DIR/thresholds.csv.
"""
import argparse
import csv
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "..", "tests", "reference", "acoustic_cfl_limits.csv")


# The trial's case: a fully periodic box, nothing but pressure and density.
CASE = """model = "wcsph"
dimension = 2
periodic = "xy"
walls = false
domain_min = [0, 0]
domain_max = [{L!r}, {L!r}]
particle_file = "{particles}"
spacing = {dx!r}
h = {h!r}
kernel = "{kernel}"
rho0 = 1000
eos = "linear"
k = {k!r}
viscosity = "none"
g = 0
density = "{density}"
integrator = "{integrator}"
dt = {dt!r}
end_time = {end!r}
output_every = {every}
regime_check = "off"
"""


def reference(kernel, dim, hdx, integrator):
    with open(REFERENCE) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    head = rows[0]
    for r in rows[1:]:
        if r[0].lower() == kernel.lower() and int(r[1]) == dim and abs(float(r[2]) - hdx) < 1e-9:
            col = "Ccrit_RK4" if integrator == "rk4" else "Ccrit_leapfrog"
            return float(r[head.index(col)])
    return None


def trial(a, C, work):
    n, dx, c = 16, 0.01, 10.0
    h = a.hdx * dx
    dt = C * h / c
    rng = np.random.default_rng(1)
    path = os.path.join(work, "lattice.csv")
    with open(path, "w") as f:
        f.write("x,y,vx,vy\n")
        for j in range(n):
            for i in range(n):
                vx, vy = rng.normal(0, 1e-4 * c, 2)
                f.write(f"{(i + 0.5) * dx!r},{(j + 0.5) * dx!r},{vx!r},{vy!r}\n")
    case = os.path.join(work, "lattice.case")
    with open(case, "w") as f:
        f.write(CASE.format(L=n * dx, dx=dx, h=h, k=c * c, dt=dt, end=a.steps * dt, every=a.steps,
                            kernel=a.kernel, density=a.density, integrator=a.integrator, particles=path))
    out = os.path.join(work, "run")
    cmd = [a.sph, "run", case, "--output", out, "--overwrite", "--no-progress", "--threads", "1"]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode == 3:
        return False, "blew up"
    if r.returncode != 0:
        raise SystemExit("sph failed:\n" + " ".join(cmd) + "\n" + r.stdout)
    with open(os.path.join(out, "energy.csv")) as f:
        rows = list(csv.reader(f))[1:]
    e0, e1 = float(rows[0][1]), float(rows[-1][1])
    return e1 < 100 * e0, f"kinetic energy x{e1 / e0:.3g}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sph", default="build/sph")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--integrator", default="leap_frog")
    ap.add_argument("--kernel", default="cubic_spline")
    ap.add_argument("--density", default="continuity")
    ap.add_argument("--hdx", type=float, default=1.3)
    ap.add_argument("--steps", type=int, default=1500)
    ap.add_argument("--lo", type=float, default=1.0)
    ap.add_argument("--hi", type=float, default=3.6)
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    lo, hi = a.lo, a.hi
    ok, why = trial(a, lo, a.workdir)
    if not ok:
        raise SystemExit(f"FAILED: unstable already at C = {lo} ({why})")
    ok, why = trial(a, hi, a.workdir)
    if ok:
        print(f"stable up to C = {hi} (the top of the search; {why})")
        lo = hi
    else:
        while hi - lo > 0.005 * lo:
            mid = 0.5 * (lo + hi)
            ok, why = trial(a, mid, a.workdir)
            print(f"  C = {mid:.4f}: {'stable' if ok else 'unstable'} ({why})", flush=True)
            lo, hi = (mid, hi) if ok else (lo, mid)
    ref = reference(a.kernel, 2, a.hdx, a.integrator) if a.integrator in ("leap_frog", "symplectic_euler", "rk4") else None
    threshold = 0.5 * (lo + hi)
    line = (f"{a.integrator}, {a.kernel}, {a.density} density, h/dx {a.hdx}: largest stable c dt / h = "
            f"{threshold:.3f}")
    if ref:
        line += f"; linear analysis {ref:.3f} (ratio {threshold / ref:.3f})"
    print(line)
    new = not os.path.exists(os.path.join(a.workdir, "thresholds.csv"))
    with open(os.path.join(a.workdir, "thresholds.csv"), "a") as f:
        if new:
            f.write("integrator,kernel,density,h_over_dx,threshold,reference\n")
        f.write(f"{a.integrator},{a.kernel},{a.density},{a.hdx},{threshold:.4f},{ref if ref else ''}\n")
    if a.check and ref:
        ok = abs(threshold / ref - 1) <= 0.05
        print(f"  |threshold / reference - 1| = {abs(threshold / ref - 1):.3f} (limit 0.05)  {'ok' if ok else 'FAILED'}")
        print("PASSED" if ok else "FAILED")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
