"""Observables of sph runs, read from their own output files, and the
references they are compared with (tests/reference/*.csv, nobody here wrote
them). Used by validate.py (ctest label `validation`) and by sph study.

Needs Debian's python3 with VTK (/usr/bin/python3; python3-paraview brings
vtkmodules) and numpy.
"""
import glob
import json
import math
import os
import xml.etree.ElementTree as ET

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "..", "tests", "reference")


class Snapshot:
    """One .vtp of a run: positions, point arrays, time; fluid/wall split."""

    def __init__(self, path):
        r = vtkXMLPolyDataReader()
        r.SetFileName(path)
        r.Update()
        o = r.GetOutput()
        self.x = vtk_to_numpy(o.GetPoints().GetData())
        pd = o.GetPointData()
        self.arrays = {pd.GetArrayName(k): vtk_to_numpy(pd.GetArray(k)) for k in range(pd.GetNumberOfArrays())}
        self.time = o.GetFieldData().GetArray("TimeValue").GetValue(0)
        kind = self.arrays.get("kind")
        self.fluid = np.ones(len(self.x), bool) if kind is None else kind == 0

    def __getitem__(self, name):
        return self.arrays[name]


class Run:
    """A run folder: its series (.pvd), run.json and the case it resolved."""

    def __init__(self, folder):
        self.folder = folder
        pvds = glob.glob(os.path.join(folder, "*.pvd"))
        if len(pvds) != 1:
            raise SystemExit(f"{folder}: expected one .pvd, found {len(pvds)}")
        root = ET.parse(pvds[0]).getroot()
        self.entries = [(float(e.get("timestep")), os.path.join(folder, e.get("file"))) for e in root.iter("DataSet")]
        with open(os.path.join(folder, "run.json")) as f:
            self.record = json.load(f)
        self.case = self.record["case"]

    def snapshots(self):
        for _, path in self.entries:
            yield Snapshot(path)

    def last(self):
        return Snapshot(self.entries[-1][1])


def reference_table(name):
    """A reference CSV of tests/reference as an array (comment lines skipped)."""
    rows = []
    with open(os.path.join(REFERENCE, name)) as f:
        for line in f:
            if line.startswith("#") or not line.strip() or not (line[0].isdigit() or line[0] in "-."):
                continue
            rows.append([float(v) for v in line.split(",")])
    return np.array(rows)


# ---- Hydrostatic column ----

def compressible_hydrostatic(H, g, rho_of_p, n=20001):
    """p(y) of a column at rest with its free surface at H: dp/dy = -g rho(p),
    integrated down from p(H) = 0. Returns (y descending, p)."""
    y = np.linspace(H, 0, n)
    p = np.zeros(n)
    for k in range(1, n):
        p[k] = p[k - 1] + g * rho_of_p(p[k - 1]) * (y[k - 1] - y[k])
    return y, p


def hydrostatic_errors(run, depth0):
    """Pressure of the last snapshot against the hydrostatic column, in units
    of rho0 g H0: mean |error| over the fluid, the worst layer (mean of a row of
    particles) and the worst particle deeper than one support below the free
    surface; errors against rho0 g (H - y) and against the compressible
    profile dp/dy = -g rho(p). Also the column drop against g H^2/(2 c0^2)."""
    c = run.case
    s = run.last()
    rho0, g, dx = c["rho0"], c["g"], c["spacing"]
    up = c["dimension"] - 1  # snapshots hold 3 coordinates, z = 0 in 2D
    kernel_support = {"cubic_spline": 2, "wendland_c2": 2, "gaussian": 3, "muller": 1}[c["kernel"]] * c["h"]
    y = s.x[s.fluid, up]
    p = s["pressure"][s.fluid]
    width = int(round((c["domain_max"][0] - c["domain_min"][0]) / dx))
    columns = width ** (len(c["domain_min"]) - 1)
    top = np.sort(y)[-columns:].mean()
    H = top + dx / 2  # the free surface: half a spacing above the top layer
    if c["eos"] == "tait":
        B = rho0 * c["c0"] ** 2 / c["gamma"]
        rho_of_p = lambda q: rho0 * (1 + q / B) ** (1 / c["gamma"])
        c0 = c["c0"]
    else:
        rho_of_p = lambda q: rho0 + q / c["k"]
        c0 = np.sqrt(c["k"])
    ye, pe = compressible_hydrostatic(H, g, rho_of_p)
    exact = np.interp(y, ye[::-1], pe[::-1])
    scale = rho0 * g * depth0
    err_linear = (p - rho0 * g * (H - y)) / scale
    err_exact = (p - exact) / scale
    deep = y < H - kernel_support
    layers = np.round((y - y.min()) / dx).astype(int)
    worst_layer = max(abs(err_exact[(layers == k) & deep].mean()) for k in np.unique(layers[deep]))
    worst_layer_linear = max(abs(err_linear[(layers == k) & deep].mean()) for k in np.unique(layers[deep]))
    drop = depth0 - H
    drop_theory = g * depth0 ** 2 / (2 * c0 ** 2)
    xf = s.x[s.fluid][:, : c["dimension"]]
    outside = np.any(xf < np.array(c["domain_min"]) - dx / 2) or np.any(
        xf[:, :up] > np.array(c["domain_max"][:up]) + dx / 2)
    return {
        "time": s.time,
        "mean_error": float(np.abs(err_exact).mean()),
        "worst_layer_error": float(worst_layer),
        "worst_particle_error": float(np.abs(err_exact[deep]).max()),
        "mean_error_linear": float(np.abs(err_linear).mean()),
        "worst_layer_error_linear": float(worst_layer_linear),
        "drop": float(drop),
        "drop_theory": float(drop_theory),
        "drop_ratio": float(drop / drop_theory),
        "fluid_outside": bool(outside),
        "rho_min": float(s["density"][s.fluid].min()),
        "rho_max": float(s["density"][s.fluid].max()),
        "v_max": float(np.abs(s["velocity"][s.fluid]).max()),
    }


# ---- Toy star (Monaghan & Price 2004) ----

def toy_star_lambda(dim, M, R, k, n):
    """lambda of the polytrope of mass M and radius R (include/sph/toy_star.hpp
    gives its derivation): 2 k (1+n) pi^(-D/2n) [M Gamma(n+1+D/2) /
    (R^D Gamma(1+n))]^(1/n) / R^2."""
    return (2 * k * (1 + n) * math.pi ** (-dim / (2 * n))
            * (M * math.gamma(n + 1 + dim / 2) / (R ** dim * math.gamma(1 + n))) ** (1 / n) / R ** 2)


def toy_star_errors(run, inside=0.9):
    """The last snapshot's density against the analytic polytrope
    rho(r) = [lambda / (2 k (1+n)) (R^2 - r^2)]^n about the centre of mass:
    relative L2 over the particles inside `inside` R (the measure sph prints,
    but per particle, not per radial bin), and the mean and worst relative
    error inside 0.5 R (the core, away from the thinning edge)."""
    c = run.case
    s = run.last()
    dim, k, n = c["dimension"], c["k"], c["polytropic_index"]
    R = c["star_radius"]
    M = c["star_mass"]
    lam = toy_star_lambda(dim, M, R, k, n)
    x = s.x[:, :dim]
    m = s["mass"]
    centre = (m[:, None] * x).sum(axis=0) / m.sum()
    r = np.linalg.norm(x - centre, axis=1)
    rho = s["density"]
    exact = np.where(r < R, np.maximum(lam / (2 * k * (1 + n)) * (R * R - r * r), 0) ** n, 0)
    sel = r < inside * R
    core = r < 0.5 * R
    rel = np.abs(rho[core] / exact[core] - 1)
    return {
        "time": s.time,
        "l2_error": float(np.sqrt(((rho[sel] - exact[sel]) ** 2).sum() / (exact[sel] ** 2).sum())),
        "core_mean_error": float(rel.mean()),
        "core_max_error": float(rel.max()),
        "particles": int(len(r)),
    }


# ---- Dam break (Martin & Moyce 1952, n^2 = 2) ----

def dam_break_curves(run):
    """Front Z = x_front / a against T = t sqrt(2 g / a), and the residual
    height H = eta / (2 a) at the left wall against tau = t sqrt(g / a), from
    every snapshot. a: the column's width (block_max - block_min along x);
    x_front: the furthest fluid particle plus dx/2; eta: the highest fluid
    particle within 1.5 dx of the left wall plus dx/2."""
    c = run.case
    a = c["block_max"][0] - c["block_min"][0]
    x0 = c["domain_min"][0]
    dx, g = c["spacing"], c["g"]
    up = c["dimension"] - 1
    T, Z, tau, H = [], [], [], []
    for s in run.snapshots():
        xf = s.x[s.fluid]
        T.append(s.time * np.sqrt(2 * g / a))
        Z.append((xf[:, 0].max() + dx / 2 - x0) / a)
        near = xf[:, 0] < x0 + 1.5 * dx
        tau.append(s.time * np.sqrt(g / a))
        H.append((xf[near, up].max() + dx / 2) / (2 * a) if near.any() else 0.0)
    return np.array(T), np.array(Z), np.array(tau), np.array(H)


# The gate-release offset of the Martin & Moyce comparison, in T = t sqrt(2g/a):
# their gate took time to clear the column, so their front lags an
# instantaneous release by a nearly constant time. Lethe's validation of
# the same experiment (chaos-polymtl/lethe, examples/multiphysics/dam-break/
# dam-break-2d.py, time_correction = 0.175) adds 0.175 to the simulated T
# before comparing: the simulated Z at T_exp - 0.175 is compared with the
# measured Z at T_exp. That is the direction used here.
GATE_OFFSET_T = 0.175


def dam_break_front(run, source="auto"):
    """The surge front Z = x_front / a against T = t sqrt(2 g / a) from the
    run's own files: front.csv (the front probe, furthest fluid particle +
    dx/2, sampled every probe_interval) when the run wrote it and source is
    "auto" or "probe", else from every snapshot (the same definition)."""
    import csv
    c = run.case
    a = c["block_max"][0] - c["block_min"][0]
    x0 = c["domain_min"][0]
    k = np.sqrt(2 * c["g"] / a)
    path = os.path.join(run.folder, "front.csv")
    if source in ("auto", "probe") and os.path.exists(path):
        with open(path) as f:
            rows = list(csv.reader(f))[1:]
        t = np.array([float(r[0]) for r in rows])
        x = np.array([float(r[1]) for r in rows])
        ok = np.isfinite(x)
        return t[ok] * k, (x[ok] - x0) / a
    if source == "probe":
        raise SystemExit(f"{run.folder}: no front.csv (front_probe = true writes it)")
    T, Z, _, _ = dam_break_curves(run)
    return T, Z


def front_relative_errors(T, Z, shift=0.0, T_range=(1.0, 3.0)):
    """(Z_sim(T_exp - shift) - Z_exp) / Z_exp at Martin & Moyce's times
    T_exp within T_range (and within the run: T_exp - shift <= T.max())."""
    front = reference_table("martin_moyce_1952_front_n2_table.csv")
    sel = (front[:, 0] >= T_range[0]) & (front[:, 0] <= T_range[1]) & (front[:, 0] - shift <= T.max() + 1e-9)
    Zs = np.interp(front[sel, 0] - shift, T, Z)
    return (Zs - front[sel, 1]) / front[sel, 1], front[sel, 0]


def front_volume_ahead(run, area, T_range=None):
    """A front that no lone particle decides: the x past which the fluid
    ahead holds `area` (m^2 per unit depth in 2D: volumes m/rho summed from
    the furthest particle back), from every snapshot. With area = dx^2 it is
    the furthest particle's centre; a fixed area (e.g. (0.01 m)^2) is the
    same amount of water at every resolution. Returns T, Z and the gap from
    the furthest particle to the next, in dx (a lone particle ahead: > 1.5)."""
    c = run.case
    a = c["block_max"][0] - c["block_min"][0]
    x0 = c["domain_min"][0]
    dx = c["spacing"]
    k = np.sqrt(2 * c["g"] / a)
    T, Z, gap = [], [], []
    for s in run.snapshots():
        xs = s.x[s.fluid][:, 0]
        vol = (s["mass"] / s["density"])[s.fluid]
        o = np.argsort(-xs)
        cum = np.cumsum(vol[o])
        n = int(np.searchsorted(cum, area * (1 - 1e-9)))
        T.append(s.time * k)
        Z.append((xs[o][min(n, len(o) - 1)] + dx / 2 - x0) / a)
        gap.append((xs[o][0] - xs[o][1]) / dx if len(o) > 1 else 0.0)
    return np.array(T), np.array(Z), np.array(gap)


def dam_break_errors(run, T_range=(1.0, 3.0)):
    """Front: relative error of Z against the Martin & Moyce table at their
    times within T_range (mean, mean of |.|, max |.|); height: absolute error
    of H at their times within the run. Also the best time shift of the
    front (the experiment's gate delay) and the errors after it, and the
    errors with the fixed gate-release offset GATE_OFFSET_T (the simulated
    Z at T_exp - 0.175 against the measured Z at T_exp)."""
    T, Z, tau, H = dam_break_curves(run)
    front = reference_table("martin_moyce_1952_front_n2_table.csv")
    height = reference_table("martin_moyce_1952_height_n2_table.csv")
    sel = (front[:, 0] >= T_range[0]) & (front[:, 0] <= T_range[1]) & (front[:, 0] <= T.max())
    Zs = np.interp(front[sel, 0], T, Z)
    ez = (Zs - front[sel, 1]) / front[sel, 1]
    shifts = np.linspace(0, 0.6, 61)
    shifted = [np.abs((np.interp(front[sel, 0] - d, T, Z) - front[sel, 1]) / front[sel, 1]).mean() for d in shifts]
    best = int(np.argmin(shifted))
    selh = height[:, 0] <= tau.max()
    eh = np.interp(height[selh, 0], tau, H) - height[selh, 1]
    eo, _ = front_relative_errors(T, Z, GATE_OFFSET_T, T_range)
    return {
        "front_mean_error": float(ez.mean()),
        "front_mean_abs_error_offset": float(np.abs(eo).mean()),
        "front_mean_error_offset": float(eo.mean()),
        "front_max_abs_error_offset": float(np.abs(eo).max()),
        "front_mean_abs_error": float(np.abs(ez).mean()),
        "front_max_abs_error": float(np.abs(ez).max()),
        "front_points": int(sel.sum()),
        "front_best_shift_T": float(shifts[best]),
        "front_mean_abs_error_shifted": float(shifted[best]),
        "height_max_abs_error": float(np.abs(eh).max()) if selh.any() else float("nan"),
        "height_mean_abs_error": float(np.abs(eh).mean()) if selh.any() else float("nan"),
        "height_points": int(selh.sum()),
    }


# ---- Channel flows (Morris, Fox & Zhu 1997): Poiseuille and Couette ----

def channel_scale(c, flow):
    """The velocity scale of a channel case: u_max = F L^2 / (8 nu) with
    F = gravity[0] (Poiseuille), or the plate speed V0 = lid_velocity[0]
    (Couette); L the channel width along the last axis."""
    L = c["domain_max"][-1] - c["domain_min"][-1]
    return c["gravity"][0] * L * L / (8 * c["nu"]) if flow == "poiseuille" else c["lid_velocity"][0]


def channel_profile_errors(run, flow):
    """The velocity profile u(y) against the series solution of Morris et al.
    (1997) at each time of the reference table (the snapshot at that time;
    its last column, "steady", against the last snapshot). flow: "poiseuille"
    (scale u_max = F L^2 / (8 nu), F = gravity[0]) or "couette" (scale V0 =
    lid_velocity[0]). Per time: the worst row (fluid particles of one y
    lattice row, their u_x averaged) and the worst particle, both as
    |u - u_series| / scale; the rows are the profile the paper plots."""
    c = run.case
    L = c["domain_max"][-1] - c["domain_min"][-1]
    y0 = c["domain_min"][-1]
    scale = channel_scale(c, flow)
    table = reference_table(f"{flow}_morris1997_series.csv")
    times = [0.0225, 0.045, 0.1125, 0.225, 0.45, 1.0]
    entries = run.entries
    out = []
    for k, t in enumerate(times + [None]):
        if t is None:
            tt, path = entries[-1]
            label = "steady (t = %.3g s)" % tt
        else:
            near = [e for e in entries if abs(e[0] - t) < 1e-9]
            if not near:
                continue
            tt, path = near[0]
            label = "t = %.4g s" % t
        s = Snapshot(path)
        xf = s.x[s.fluid]
        u = s["velocity"][s.fluid][:, 0]
        eta = (xf[:, len(c["domain_min"]) - 1] - y0) / L
        ref = np.interp(eta, table[:, 0], table[:, k + 1])
        err = (u / scale - ref)
        rows = np.round(eta * 1e6).astype(np.int64)
        row_err = [abs(err[rows == r].mean()) for r in np.unique(rows)]
        out.append({"label": label, "time": tt, "row_max": float(max(row_err)),
                    "particle_max": float(np.abs(err).max()), "rows": len(row_err),
                    "u_mid": float(np.interp(0.5, np.sort(eta), (u / scale)[np.argsort(eta)]))})
    return out, scale


def midline_history_errors(run, flow):
    """u(L/2, t) from the point probe named "midline" (probes.csv, Shepard
    interpolation) against channel_midline_history.csv (Morris et al. 1997
    series): the worst |u - u_ref| / scale over the reference times the probe
    file covers (linear interpolation between samples)."""
    import csv
    scale = channel_scale(run.case, flow)
    with open(os.path.join(run.folder, "probes.csv")) as f:
        rows = list(csv.reader(f))
    head = rows[0]
    col = head.index("midline vx [m/s]")
    t = np.array([float(r[0]) for r in rows[1:]])
    u = np.array([float(r[col]) for r in rows[1:]])
    table = reference_table("channel_midline_history.csv")
    ref_t = table[:, 0]
    ref = table[:, 1 if flow == "poiseuille" else 2]
    keep = ref_t <= t[-1] + 1e-12
    err = np.abs(np.interp(ref_t[keep], t, u) / scale - ref[keep])
    return {"points": int(keep.sum()), "max_error": float(err.max()), "mean_error": float(err.mean()),
            "t_worst": float(ref_t[keep][np.argmax(err)])}


def taylor_green_errors(run, t_l2=1.0, t_range=(0.0, 2.0)):
    """The 2D Taylor-Green vortex (initial_flow taylor_green): max|u|(t) of
    each snapshot and the mode amplitude a(t) = sum u . phi / sum phi . phi
    (phi the vortex mode at the particles' positions: max|u| of a smooth
    field without one noisy particle deciding it), the decay rates b of
    least-squares fits of log max|u| and log a against t over t_range, against the exact 8 pi^2 nu / L^2 (= 8 pi^2 / Re
    for U = L = 1), and the velocity L2 error at t_l2,
    sqrt(sum |u - u_exact|^2 / sum |u_exact|^2) over the particles, with
    u_exact at each particle's position."""
    c = run.case
    L = c["domain_max"][0] - c["domain_min"][0]
    U = c["flow_speed"]
    nu = c["nu"]
    k = 2 * np.pi / L
    b_exact = 2 * nu * k * k
    times, umax, amp, l2 = [], [], [], None
    for tt, path in run.entries:
        if tt < t_range[0] - 1e-12 or tt > t_range[1] + 1e-12:
            continue
        s = Snapshot(path)
        v = s["velocity"][s.fluid][:, :2]
        x = s.x[s.fluid][:, 0] - c["domain_min"][0]
        y = s.x[s.fluid][:, 1] - c["domain_min"][1]
        mode = np.stack([-np.cos(k * x) * np.sin(k * y), np.sin(k * x) * np.cos(k * y)], axis=1)
        times.append(tt)
        umax.append(float(np.sqrt((v ** 2).sum(axis=1)).max()))
        amp.append(float((v * mode).sum() / (mode * mode).sum()))
        if abs(tt - t_l2) < 1e-9:
            ue = U * np.exp(-b_exact * tt) * mode
            l2 = float(np.sqrt(((v - ue) ** 2).sum() / (ue ** 2).sum()))
    times, umax, amp = np.array(times), np.array(umax), np.array(amp)
    b = -np.polyfit(times, np.log(umax / U), 1)[0]
    b_mode = -np.polyfit(times, np.log(amp / U), 1)[0]
    return {"decay_rate": float(b), "decay_rate_exact": float(b_exact), "decay_rate_error": float(b / b_exact - 1),
            "mode_decay_rate": float(b_mode), "mode_decay_rate_error": float(b_mode / b_exact - 1),
            "umax_end": float(umax[-1]), "umax_end_exact": float(U * np.exp(-b_exact * times[-1])),
            "mode_end": float(amp[-1]),
            "time_end": float(times[-1]), "l2_at": t_l2, "l2_error": l2, "snapshots": len(times)}


def wave_paddle_heights(run, gauge=0, window=(2.0, 4.5)):
    """Wave height at a height gauge (heights.csv column `gauge`) of the
    piston wave maker (keys paddle, paddle_amplitude, paddle_period): the
    mean over the whole periods in `window` of max - min of the water level,
    against the linear piston wave-maker theory of Biesel (Dean & Dalrymple
    1991, eq. 6.19), H / S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh), S = 2 A,
    omega^2 = g k tanh(kh), h the still-water depth."""
    import csv
    c = run.case
    with open(os.path.join(run.folder, "heights.csv")) as f:
        rows = list(csv.reader(f))
    head = rows[0]
    t = np.array([float(r[0]) for r in rows[1:]])
    z = np.array([float(r[1 + gauge]) for r in rows[1:]])
    T = c["paddle_period"]
    A = abs(c["paddle_amplitude"][0])
    depth = c["block_max"][-1] - c["block_min"][-1]
    g = abs(c.get("g", 9.81)) if not c.get("gravity") else abs(c["gravity"][-1])
    w = 2 * np.pi / T
    k = w * w / g
    for _ in range(200):  # omega^2 = g k tanh(kh), by fixed point on k
        k = w * w / (g * np.tanh(k * depth))
    kh = k * depth
    ratio = 2 * (np.cosh(2 * kh) - 1) / (np.sinh(2 * kh) + 2 * kh)
    heights = []
    n = int(np.floor((window[1] - window[0]) / T + 1e-9))
    for p in range(n):
        m = (t >= window[0] + p * T - 1e-9) & (t <= window[0] + (p + 1) * T + 1e-9)
        if m.sum() > 2:
            heights.append(float(z[m].max() - z[m].min()))
    H = float(np.mean(heights)) if heights else float("nan")
    return {"gauge": head[1 + gauge], "kh": float(kh), "wavelength": float(2 * np.pi / k),
            "H_theory": float(ratio * 2 * A), "H": H, "periods": len(heights),
            "H_each": heights, "error": float(H / (ratio * 2 * A) - 1)}


# ---- SPHERIC Test 2 (MARIN dam break with a box) ----

def csv_columns(path):
    """A CSV with a header line as {column name: array}."""
    with open(path) as f:
        names = f.readline().rstrip("\n").split(",")
    data = np.genfromtxt(path, delimiter=",", skip_header=1, ndmin=2)
    return {n: data[:, k] for k, n in enumerate(names)}


def spheric2_reference():
    """tests/reference/spheric2_kleefsman2005_figures.csv as a list of dicts."""
    rows = []
    with open(os.path.join(REFERENCE, "spheric2_kleefsman2005_figures.csv")) as f:
        lines = [l.strip() for l in f if l.strip() and not l.startswith("#")]
    names = lines[0].split(",")
    for line in lines[1:]:
        cells = line.split(",")
        row = {}
        for n, c in zip(names, cells):
            try:
                row[n] = float(c) if c else None
            except ValueError:
                row[n] = c
        rows.append(row)
    return rows


def first_time_above(t, y, level, after=0.0):
    """The first time t >= after at which y > level (linear between samples), or nan."""
    y = np.nan_to_num(y, nan=0.0)
    k = np.where((y > level) & (t >= after))[0]
    if len(k) == 0:
        return float("nan")
    k = k[0]
    if k == 0 or y[k - 1] > level:
        return float(t[k])
    return float(t[k - 1] + (level - y[k - 1]) / (y[k] - y[k - 1]) * (t[k] - t[k - 1]))


def window_mean(t, y, t0, t1):
    """Time average of a sampled series over [t0, t1] (trapezoid; nan reads 0: dry), nan when the
    run does not reach t1."""
    if t[-1] < t1 - 1e-9:
        return float("nan")
    m = (t >= t0) & (t <= t1)
    y = np.nan_to_num(y[m], nan=0.0)
    return float(np.trapz(y, t[m]) / (t[m][-1] - t[m][0]))


def moving_average(t, y, window):
    """Trailing moving average over `window` seconds of a sampled series (as probe_window)."""
    y = np.nan_to_num(y, nan=0.0)
    out = np.empty_like(y)
    j = 0
    c = np.concatenate([[0.0], np.cumsum(y)])
    for i in range(len(t)):
        while t[j] <= t[i] - window * (1 - 1e-9):
            j += 1
        out[i] = (c[i + 1] - c[j]) / (i + 1 - j)
    return out


def spheric2_observables(run):
    """The run's figures next to SPHERIC Test 2's: arrival of 1 cm of water at
    H1-H3, maximum heights, P1's rise above 1 kPa, its first-impact peak (the
    sensor's raw reading and its moving average, probe_window), P1's mean over
    0.45-1.0 s and 1-2 s, and when the top sensors P5-P8 are loaded."""
    heights = csv_columns(os.path.join(run.folder, "heights.csv"))
    probes = csv_columns(os.path.join(run.folder, "probes.csv"))
    th = heights["time [s]"]
    tp = probes["time [s]"]
    gauge_cols = [n for n in heights if n.startswith("height at")]
    gauges = dict(zip(["H1", "H2", "H3", "H4"], gauge_cols))
    unit = " [Pa]"
    window = run.case.get("probe_window") or 0.0

    def raw(name):
        return probes[name + " pressure" + unit]

    def filt(name):
        col = name + " pressure filtered" + unit
        return probes[col] if col in probes else moving_average(tp, raw(name), 0.005)

    out = {"end_time": float(max(th[-1], tp[-1])), "window": window, "rows": []}
    for ref in spheric2_reference():
        q, g = ref["quantity"], ref["gauge"]
        sim = float("nan")
        sim_time = None
        if q == "arrival_1cm":
            sim = first_time_above(th, heights[gauges[g]], 0.01)
        elif q == "max_height":
            if th[-1] >= ref["time [s]"] + 0.2:
                y = np.nan_to_num(heights[gauges[g]])
                m = th >= 1.0  # after the first passage of the surge (before it, the splash)
                k = np.argmax(np.where(m, y, -1))
                sim, sim_time = float(y[k]), float(th[k])
        elif q == "rise_above_1kPa":
            sim = first_time_above(tp, raw(g), 1000.0)
            out["rise_filtered"] = first_time_above(tp, filt(g), 1000.0)
        elif q == "first_impact_peak":
            m = (tp >= 0.3) & (tp <= 0.6)
            if m.any():
                r, f = np.nan_to_num(raw(g)[m]), filt(g)[m]
                sim, sim_time = float(r.max()), float(tp[m][np.argmax(r)])
                out["peak_filtered"] = float(f.max())
                out["peak_filtered_time"] = float(tp[m][np.argmax(f)])
                for w in (0.002, 0.005, 0.01, 0.02):
                    out[f"peak_ma_{w*1e3:g}ms"] = float(moving_average(tp, raw(g), w)[m].max())
        elif q == "mean_pressure":
            sim = window_mean(tp, raw(g), ref["t_from [s]"], ref["t_to [s]"])
        elif q == "top_loaded_from":
            if tp[-1] >= 1.8:
                top = np.max([filt(n) for n in ("P5", "P6", "P7", "P8")], axis=0)
                sim = first_time_above(tp, top, 500.0, after=1.0)
        elif q == "top_peak":
            if tp[-1] >= 2.0:
                m = tp >= 1.0
                top = np.max([filt(n) for n in ("P5", "P6", "P7", "P8")], axis=0)
                k = np.argmax(np.where(m, top, -1))
                sim, sim_time = float(top[k]), float(tp[k])
        out["rows"].append({"quantity": q, "gauge": g, "ref": ref["value"], "ref_time": ref["time [s]"],
                            "window": (ref["t_from [s]"], ref["t_to [s]"]), "unit": ref["unit"], "sim": sim,
                            "sim_time": sim_time})
    # The start-up offset, as the gate-release offset of dam-break
    # validations: the delay of the first gauge's arrival (H3) against the
    # experiment's; the later events measured from it.
    rows = {(r["quantity"], r["gauge"], r["window"][0]): r for r in out["rows"]}
    shift = rows[("arrival_1cm", "H3", None)]["sim"] - rows[("arrival_1cm", "H3", None)]["ref"]
    out["shift"] = shift
    out["arrival_H2_shifted"] = rows[("arrival_1cm", "H2", None)]["sim"] - shift
    out["arrival_H1_shifted"] = rows[("arrival_1cm", "H1", None)]["sim"] - shift
    out["rise_P1_shifted"] = rows[("rise_above_1kPa", "P1", None)]["sim"] - shift
    t1 = min(1.0 + shift, float(tp[-1])) if shift == shift else float("nan")
    out["level_window_shifted"] = (0.45 + shift, t1)
    out["level_P1_shifted"] = (window_mean(tp, raw("P1"), 0.45 + shift, t1)
                               if shift == shift and t1 > 0.5 + shift else float("nan"))
    return out
