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

Other modes (--mode; each appends to its own CSV in DIR and draws its map
with atlas_chart.py):
  euler    explicit Euler's energy growth per step on the same lattice
           against the theory ln(1 + (omega_max dt)^2) (euler.csv)
  pairing  the h/dx from which a kernel pairs on a lattice under pressure
           (pairing.csv)
  tensile  the expanding Tait block of cases/tensile_block.case (negative
           pressure) with Monaghan's artificial pressure eps = 0 ... 0.3:
           the smallest particle gap over time and when it first falls
           below 0.5 dx (tensile.csv)
  leakage  the largest c0 dt / h at which the dam break keeps its fluid
           inside the walls, per boundary treatment and number of wall
           layers (leakage.csv)

Prints the threshold, the reference, their ratio, and (with --check) fails
when the threshold is more than 5% off the reference (the issue's
tolerance; summation density linearises to the same acoustic system: the bisection brackets it to 0.5%, and near the limit an
unstable mode's growth per step is small, so the measured threshold sits a
little above the linear one). Appends a row to DIR/thresholds.csv.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "..", "tests", "reference", "acoustic_cfl_limits.csv")


# The trial's case: a fully periodic box, nothing but pressure and density
# (the pairing trial replaces the viscosity).
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
g = 0
density = "{density}"
integrator = "{integrator}"
dt = {dt!r}
end_time = {end!r}
output_every = {every}
regime_check = "off"
"""
NO_VISCOSITY = 'viscosity = "none"\n'


# omega_max dt at which the two-step leap-frog's filtered pair turns unstable
# (integrators/two_step_leap_frog.hpp: the largest z with both roots of the
# filtered two-step map inside the unit circle, nu = 0.05).
TWO_STEP_LIMIT = 0.952


def reference(kernel, dim, hdx, integrator):
    with open(REFERENCE) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    head = rows[0]
    for r in rows[1:]:
        if r[0].lower() == kernel.lower() and int(r[1]) == dim and abs(float(r[2]) - hdx) < 1e-9:
            col = "Ccrit_RK4" if integrator == "rk4" else "Ccrit_leapfrog"
            # The two-step leap-frog with its Robert-Asselin filter (nu = 0.05)
            # is stable to omega dt = 0.952, leap-frog to 2: its own analysis
            # (integrators/two_step_leap_frog.hpp) on the reference's omega_max.
            scale = TWO_STEP_LIMIT / 2 if integrator == "two_step_leap_frog" else 1
            return scale * float(r[head.index(col)])
    return None


def write_lattice(path, n, dx, point):
    """An n x n lattice particle file; point(i, j) gives (x, y, vx, vy)."""
    with open(path, "w") as f:
        f.write("x,y,vx,vy\n")
        for j in range(n):
            for i in range(n):
                f.write(",".join(repr(float(v)) for v in point(i, j)) + "\n")


def run_sph(a, case, extra=()):
    """sph run of a case (with extra flags) into WORKDIR/run, from the
    repository's root (the cases' particle files are relative to it):
    (exit status, output folder, what sph printed); exit statuses other than
    0 and 3 (stopped: blew up or leaked) stop the atlas."""
    out = os.path.abspath(os.path.join(a.workdir, "run"))
    cmd = [os.path.abspath(a.sph), "run", os.path.abspath(case), "--output", out, "--overwrite", "--no-progress",
           "--threads", "1", *extra]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       cwd=os.path.join(HERE, ".."))
    if r.returncode not in (0, 3):
        raise SystemExit("sph failed:\n" + " ".join(cmd) + "\n" + r.stdout)
    return r.returncode, out, r.stdout


def lattice_case(a, name, n, dx, h, c, dt, steps, every, point, kernel, density, integrator, extra=""):
    """Writes the lattice and its case (CASE plus `extra` lines) into
    WORKDIR; returns the case's path."""
    path = os.path.join(a.workdir, name + ".csv")
    write_lattice(path, n, dx, point)
    case = os.path.join(a.workdir, name + ".case")
    with open(case, "w") as f:
        f.write(CASE.format(L=n * dx, dx=dx, h=h, k=c * c, dt=dt, end=steps * dt, every=every, kernel=kernel,
                            density=density, integrator=integrator, particles=path) + extra)
    return case


def energy(out):
    with open(os.path.join(out, "energy.csv")) as f:
        return np.array([float(row[1]) for row in list(csv.reader(f))[1:]])


def trial(a, C):
    n, dx, c = 16, 0.01, 10.0
    h = a.hdx * dx
    rng = np.random.default_rng(1)
    v = rng.normal(0, 1e-4 * c, (n, n, 2))
    case = lattice_case(a, "lattice", n, dx, h, c, C * h / c, a.steps, a.steps,
                        lambda i, j: ((i + 0.5) * dx, (j + 0.5) * dx, *v[j, i]), a.kernel, a.density, a.integrator, NO_VISCOSITY)
    rc, out, _ = run_sph(a, case)
    if rc == 3:
        return False, "blew up"
    e = energy(out)
    return e[-1] < 100 * e[0], f"kinetic energy x{e[-1] / e[0]:.3g}"


def max_g(kernel, dim, hdx):
    """max |G| dx of the reference row: omega_max dt = C (h/dx) max|G| dx."""
    with open(REFERENCE) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    head = rows[0]
    for r in rows[1:]:
        if r[0].lower() == kernel.lower() and int(r[1]) == dim and abs(float(r[2]) - hdx) < 1e-9:
            return float(r[head.index("max_G_dx")])
    return None


def append(path, header, row):
    new = not os.path.exists(path)
    with open(path, "a") as f:
        if new:
            f.write(header + "\n")
        f.write(row + "\n")


def bisect(stable, lo, hi, rel=0.005):
    """The largest stable parameter in [lo, hi] (stable(lo) must hold);
    returns (threshold, the failure seen just above it)."""
    ok, why = stable(hi)
    if ok:
        return hi, f"stable at the top of the search ({why})"
    failure = why
    while hi - lo > rel * lo:
        mid = 0.5 * (lo + hi)
        ok, why = stable(mid)
        print(f"  {mid:.4f}: {'stable' if ok else 'unstable'} ({why})", flush=True)
        if ok:
            lo = mid
        else:
            hi, failure = mid, why
    return 0.5 * (lo + hi), failure


def mode_timestep(a):
    ok, why = trial(a, a.lo)
    if not ok:
        raise SystemExit(f"FAILED: unstable already at C = {a.lo} ({why})")
    threshold, _ = bisect(lambda C: trial(a, C), a.lo, a.hi)
    ref = reference(a.kernel, 2, a.hdx, a.integrator) if a.integrator in ("leap_frog", "symplectic_euler", "rk4",
                                                                     "two_step_leap_frog") else None
    line = (f"{a.integrator}, {a.kernel}, {a.density} density, h/dx {a.hdx}: largest stable c dt / h = "
            f"{threshold:.3f}")
    if ref:
        line += f"; linear analysis {ref:.3f} (ratio {threshold / ref:.3f})"
    print(line)
    append(os.path.join(a.workdir, "thresholds.csv"), "integrator,kernel,density,h_over_dx,threshold,reference",
           f"{a.integrator},{a.kernel},{a.density},{a.hdx},{threshold:.4f},{ref if ref else ''}")
    if a.check and ref:
        ok = abs(threshold / ref - 1) <= 0.05
        print(f"  |threshold / reference - 1| = {abs(threshold / ref - 1):.3f} (limit 0.05)  {'ok' if ok else 'FAILED'}")
        print("PASSED" if ok else "FAILED")
        sys.exit(0 if ok else 1)


def mode_euler(a):
    """Explicit Euler multiplies a sound mode of frequency omega by
    1 + i omega dt per step: its energy grows by 1 + (omega dt)^2 per step,
    and after a few hundred steps the fastest lattice mode (omega_max dt =
    C (h/dx) max|G| dx, the reference's max_G_dx) dominates the total. The
    measured growth rate is the slope of ln E over the last half of the
    steps, while the velocities are still small (linear)."""
    G = max_g(a.kernel, 2, a.hdx)
    worst = 0.0
    for C in a.courant:
        steps = int(min(4000, max(40, 20.0 / math.log1p((C * a.hdx * G) ** 2))))
        e = lattice_energy(a, C, steps)
        n = len(e)
        k = np.arange(n // 2, n)
        slope = np.polyfit(k, np.log(e[n // 2:]), 1)[0]
        theory = math.log1p((C * a.hdx * G) ** 2)
        err = slope / theory - 1
        worst = max(worst, abs(err))
        print(f"explicit Euler, {a.kernel}, h/dx {a.hdx}, C = {C}: energy growth per step {slope:.5f}, "
              f"theory ln(1 + (omega_max dt)^2) = {theory:.5f} ({100 * err:+.1f}%) over {steps} steps")
        append(os.path.join(a.workdir, "euler.csv"), "kernel,h_over_dx,courant,steps,growth_per_step,theory",
               f"{a.kernel},{a.hdx},{C},{steps},{slope:.6g},{theory:.6g}")
    if a.check:
        ok = worst <= 0.10
        print(f"  worst |growth / theory - 1| = {worst:.3f} (limit 0.10: the fastest mode dominates only "
              f"asymptotically)  {'ok' if ok else 'FAILED'}")
        print("PASSED" if ok else "FAILED")
        sys.exit(0 if ok else 1)


def lattice_energy(a, C, steps):
    """Kinetic energy after every step of explicit Euler on the lattice,
    started from a velocity field small enough (1e-7 c) to stay linear."""
    n, dx, c = 16, 0.01, 10.0
    h = a.hdx * dx
    rng = np.random.default_rng(1)
    v = rng.normal(0, 1e-7 * c, (n, n, 2))
    case = lattice_case(a, "lattice", n, dx, h, c, C * h / c, steps, 1,
                        lambda i, j: ((i + 0.5) * dx, (j + 0.5) * dx, *v[j, i]), a.kernel, "continuity", "euler", NO_VISCOSITY)
    rc, out, _ = run_sph(a, case)
    if rc != 0:
        raise SystemExit(f"explicit Euler at C = {C} blew up within {steps} steps: fewer steps")
    return energy(out)


# The pairing trial: a periodic lattice under a uniform pressure p_b (linear
# EOS with a background pressure), positions jittered by 2% of dx, at rest.
# A kernel whose lattice is unstable under pressure (the pairing instability
# of Schuessler & Schmitt 1981; Dehnen & Aly 2012) lets the jitter grow
# until particles sit in pairs; a stable one keeps the lattice.
PAIRING_EXTRA = """background_pressure = {pb!r}
viscosity = "monaghan"
alpha = 0.1
beta = 0
"""


def paired_fraction(a, kernel, hdx):
    n, dx, c = 20, 0.01, 10.0
    h = hdx * dx
    dt = 0.3 * min(h, dx) / c
    steps = int(a.pairing_time * h / c / dt)
    rng = np.random.default_rng(2)
    jitter = rng.uniform(-0.02, 0.02, (n, n, 2)) * dx
    case = lattice_case(a, "pairing_lattice", n, dx, h, c, dt, steps, steps,
                        lambda i, j: ((i + 0.5) * dx + jitter[j, i, 0], (j + 0.5) * dx + jitter[j, i, 1], 0, 0),
                        kernel, "summation", "leap_frog", PAIRING_EXTRA.format(pb=a.pairing_pressure * 1000.0 * c * c))
    rc, out, _ = run_sph(a, case)
    if rc == 3:
        return 1.0, "blew up"
    sys.path.insert(0, HERE)
    import observables
    x = observables.Run(out).last().x[:, :2]
    L = n * dx
    d = x[:, None, :] - x[None, :, :]
    d -= L * np.round(d / L)
    r2 = (d ** 2).sum(axis=2)
    np.fill_diagonal(r2, np.inf)
    nearest = np.sqrt(r2.min(axis=1)) / dx
    return float((nearest < 0.6).mean()), f"nearest neighbour min {nearest.min():.2f} dx, median {np.median(nearest):.2f} dx"


def mode_pairing(a):
    """The paired fraction (a neighbour closer than 0.6 dx) after
    --pairing-time h/c, over h/dx; a kernel pairs at the h/dx where more
    than 10% of the particles are paired."""
    for kernel in a.kernels:
        paired = []
        for hdx in a.hdx_list:
            frac, why = paired_fraction(a, kernel, hdx)
            print(f"{kernel} h/dx {hdx}: paired {100 * frac:.0f}% ({why})", flush=True)
            append(os.path.join(a.workdir, "pairing.csv"), "kernel,h_over_dx,paired_fraction",
                   f"{kernel},{hdx},{frac:.4f}")
            if frac > 0.10:
                paired.append(hdx)
        print(f"{kernel}: pairs at h/dx {', '.join(str(h) for h in paired)}" if paired
              else f"{kernel}: no pairing at h/dx {a.hdx_list[0]} ... {a.hdx_list[-1]}")


def nearest_gaps(x):
    """Each particle's distance to its nearest neighbour (no periodicity)."""
    d = x[:, None, :] - x[None, :, :]
    r2 = (d ** 2).sum(axis=2)
    np.fill_diagonal(r2, np.inf)
    return np.sqrt(r2.min(axis=1))


def mode_tensile(a):
    """The tensile instability, provoked: a free block whose Tait pressure
    goes negative as it expands; without a correction its particles clump
    (the smallest gap collapses), Monaghan's artificial pressure delays it."""
    sys.path.insert(0, HERE)
    import observables
    case = os.path.join(HERE, "..", "cases", "tensile_block.case")
    for eps in a.eps:
        _, out, _ = run_sph(a, case, ["--artificial_pressure", repr(eps), "--end_time", repr(a.tensile_time),
                                      "--regime_check", "off"])
        dx = 0.01
        onset = None
        for snap in observables.Run(out).snapshots():
            gap = nearest_gaps(snap.x[snap.fluid][:, :2]).min() / dx
            append(os.path.join(a.workdir, "tensile.csv"), "artificial_pressure,time,smallest_gap_dx",
                   f"{eps},{snap.time:.4g},{gap:.4f}")
            if onset is None and gap < 0.5:
                onset = snap.time
        print(f"artificial pressure eps = {eps}: smallest gap {gap:.3f} dx at t = {snap.time:.3g} s; "
              + (f"below 0.5 dx from t = {onset:.3g} s" if onset is not None else "never below 0.5 dx"), flush=True)


def leak_trial(a, boundary, layers, C):
    """The dam break (coarse: dx 0.02) with c0 dt / h = C: (kept its fluid,
    what happened)."""
    h, c0 = 1.5 * a.leak_dx, 44.0
    dt = C * h / c0
    extra = ["--spacing", repr(a.leak_dx), "--h", repr(h), "--dt", repr(dt), "--end_time", repr(a.leak_time),
             "--output_interval", repr(a.leak_time), "--boundary", boundary,
             "--no-wall_guard"]  # the bare boundary: the guard would hold every particle
    if boundary != "repulsive":
        extra += ["--wall_layers", str(layers), "--wall_layers_override"]
    rc, _, text = run_sph(a, os.path.join(HERE, "..", "cases", "dam_break.case"), extra)
    if rc == 0:
        return True, "kept its fluid"
    return False, "leaked" if "leak" in text.lower() else "blew up"


def mode_leakage(a):
    for boundary in a.boundaries:
        for layers in ([1] if boundary == "repulsive" else a.layers):
            ok, why = leak_trial(a, boundary, layers, a.leak_lo)
            if not ok:
                threshold, failure = 0.0, why
                print(f"{boundary}, {layers} layers: fails already at c0 dt / h = {a.leak_lo} ({why})")
            else:
                threshold, failure = bisect(lambda C: leak_trial(a, boundary, layers, C), a.leak_lo, a.leak_hi, 0.02)
                print(f"{boundary}, {layers} layers: largest c0 dt / h that keeps the fluid = {threshold:.3f} "
                      f"(above it: {failure})", flush=True)
            append(os.path.join(a.workdir, "leakage.csv"), "boundary,wall_layers,threshold,failure_above",
                   f"{boundary},{layers},{threshold:.4f},{failure}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sph", default="build/sph")
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--mode", default="timestep", choices=["timestep", "euler", "pairing", "tensile", "leakage"])
    ap.add_argument("--integrator", default="leap_frog")
    ap.add_argument("--kernel", default="cubic_spline")
    ap.add_argument("--density", default="continuity")
    ap.add_argument("--hdx", type=float, default=1.3)
    ap.add_argument("--steps", type=int, default=1500)
    ap.add_argument("--lo", type=float, help="timestep: a stable C to start from (1.0; two_step_leap_frog 0.3)")
    ap.add_argument("--hi", type=float, help="timestep: the top of the search (3.6; two_step_leap_frog 1.2)")
    ap.add_argument("--courant", type=float, nargs="+", default=[0.1, 0.2, 0.5], help="euler: the c dt / h to run")
    ap.add_argument("--kernels", nargs="+", default=["cubic_spline", "wendland_c2", "gaussian"], help="pairing")
    ap.add_argument("--hdx-list", type=float, nargs="+", default=[1.0, 1.2, 1.3, 1.4, 1.5, 1.6, 1.8, 2.0, 2.2],
                    help="pairing: the h/dx to run")
    ap.add_argument("--pairing-time", type=float, default=300, help="pairing: run length in h / c")
    ap.add_argument("--pairing-pressure", type=float, default=0.01,
                    help="pairing: the uniform pressure in rho0 c^2 (the dam break floor, rho0 g 2a: 0.0025)")
    ap.add_argument("--eps", type=float, nargs="+", default=[0, 0.05, 0.1, 0.2, 0.3], help="tensile")
    ap.add_argument("--tensile-time", type=float, default=0.4, help="tensile: run length [s]")
    ap.add_argument("--boundaries", nargs="+", default=["dummy", "dynamic", "repulsive"], help="leakage")
    ap.add_argument("--layers", type=int, nargs="+", default=[1, 2, 3], help="leakage: wall layers to try")
    ap.add_argument("--leak-dx", type=float, default=0.02)
    ap.add_argument("--leak-time", type=float, default=0.6)
    ap.add_argument("--leak-lo", type=float, default=0.05)
    ap.add_argument("--leak-hi", type=float, default=4.0)
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    one_walk = a.integrator == "two_step_leap_frog"  # stable to about half leap-frog's C
    a.lo = a.lo if a.lo is not None else (0.3 if one_walk else 1.0)
    a.hi = a.hi if a.hi is not None else (1.2 if one_walk else 3.6)
    os.makedirs(a.workdir, exist_ok=True)
    {"timestep": mode_timestep, "euler": mode_euler, "pairing": mode_pairing, "tensile": mode_tensile,
     "leakage": mode_leakage}[a.mode](a)


if __name__ == "__main__":
    main()
