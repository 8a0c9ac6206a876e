#!/usr/bin/env python3
"""Oscillation period of a slightly elliptic 2D drop (cases/droplet_oscillation.case)
from the run's own snapshots, against Rayleigh's frequency for a cylinder
(tests/reference/droplet_laplace_rayleigh.csv: w^2 = n (n^2 - 1) sigma /
((rho_in + rho_out) R^3), mode n = 2).

  droplet_oscillation.py RUN_DIR [--plot PNG]

Per snapshot, of the drop's particles (colour > 0.5): the central second
moments Ixx, Iyy, the aspect ratio sqrt(Ixx/Iyy) and the deformation
d = (Ixx - Iyy) / (Ixx + Iyy), which changes sign each time the long axis
swaps between x and y. Period: twice the mean time between successive
zero crossings of d - mean(d) (linear interpolation between snapshots),
the first half period left out (the start from rest is not a crossing of a
free oscillation). Damping rate gamma: from the log of the successive
extremum amplitudes |d| (least squares). The undamped frequency of a
damped oscillator is w0 = sqrt(w_d^2 + gamma^2); both are printed.
R: the equal-area radius sqrt(N_drop dx^2 / pi).

Rayleigh's frequency is inviscid. With the case's viscosity the interface
between two fluids carries an oscillating (Stokes) boundary layer, which
both damps the mode and lengthens its period by a fraction of order
(n/2R) sqrt(nu/(2 omega)) (equal fluids; 5.7% for the case's nu = 0.005). The script also prints the viscous normal mode of the same
cylinder (linearised Navier-Stokes inside and out, equal rho and mu: a
potential part r^(+-n) and a vortical part I_n(q r), K_n(q r), q^2 = s/nu,
with u_r, u_theta and the shear stress continuous and the normal stress
jumping by sigma times the curvature's perturbation; the complex rate s
solves the 4 x 4 determinant), so that a run can be told apart from the
physics it resolves: e.g. nu = 0.005 m^2/s and R = 0.2 give a period 6.0%
longer than Rayleigh's and a damping rate 1.2/s; nu = 0.002: 3.7%, 0.73/s.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import observables  # noqa: E402


def rayleigh_omega(sigma, rho_in, rho_out, R, n=2):
    """The 2D mode-n frequency, scaled from the reference row with the same
    mode and rho_in = rho_out (the case's two fluids) by the law in its header."""
    # columns: mode_n, sigma, rho_in, rho_out, R, dp_2D, dp_3D, omega_2D, ...
    rows = observables.reference_table("droplet_laplace_rayleigh.csv")
    row = next(r for r in rows if int(r[0]) == n and r[3] == r[2])
    w_ref = row[7]
    scale = (sigma / row[1]) * ((row[2] + row[3]) / (rho_in + rho_out)) * (row[4] / R) ** 3
    return w_ref * np.sqrt(scale)


def viscous_mode(sigma, rho, mu, R, n=2):
    """The complex rate s = -gamma + i omega of mode n of a 2D cylinder of
    radius R in a second fluid with the same rho and mu (see the header);
    None without scipy."""
    try:
        from scipy.optimize import fsolve
        from scipy.special import iv, ivp, kv, kvp
    except ImportError:
        return None
    nu = mu / rho

    def det(s):
        q = np.sqrt(s / nu)
        if q.real < 0:
            q = -q
        z = q * R
        Ip, Ipp = q * ivp(n, z) / iv(n, z), q * q * ivp(n, z, 2) / iv(n, z)
        Kp, Kpp = q * kvp(n, z) / kv(n, z), q * q * kvp(n, z, 2) / kv(n, z)
        r = R
        cols = []
        # (f, f', f'') of the potential and (g, g', g'') of the stream function at r = R,
        # the Bessel parts scaled to 1 there: inside r^n, I_n; outside r^-n, K_n.
        for f, g in [((r ** n, n * r ** (n - 1), n * (n - 1) * r ** (n - 2)), (0, 0, 0)), ((0, 0, 0), (1, Ip, Ipp)),
                     ((r ** -n, -n * r ** (-n - 1), n * (n + 1) * r ** (-n - 2)), (0, 0, 0)), ((0, 0, 0), (1, Kp, Kpp))]:
            F, F1, F2 = f
            G, G1, G2 = g
            ur, ur1 = F1 + n * G / r, F2 + n * G1 / r - n * G / r ** 2
            ut, ut1 = -n * F / r - G1, -n * F1 / r + n * F / r ** 2 - G2
            cols.append((ur, ut, mu * (ut1 - ut / r - n * ur / r), rho * s * F + 2 * mu * ur1))
        A = np.zeros((4, 4), complex)
        for j, sign in enumerate([1, 1, -1, -1]):
            A[:3, j] = [sign * cols[j][0], sign * cols[j][1], sign * cols[j][2]]
            A[3, j] = -cols[j][3] - sigma * (n * n - 1) * cols[j][0] / (s * R * R) if j < 2 else cols[j][3]
        A /= np.linalg.norm(A, axis=0)
        return np.linalg.det(A)

    w0 = np.sqrt(n * (n * n - 1) * sigma / (2 * rho * R ** 3))
    grid = [complex(a, b) for a in np.linspace(-0.4 * w0, 0, 41) for b in np.linspace(0.5 * w0, 1.1 * w0, 61)]
    s0 = min(grid, key=lambda s: abs(det(s)))
    v = fsolve(lambda v: [det(complex(*v)).real, det(complex(*v)).imag], [s0.real, s0.imag])
    return complex(*v)


def deformation_series(run):
    t, d, aspect = [], [], []
    n_drop = None
    for s in run.snapshots():
        drop = s.fluid & (s["colour"] > 0.5)
        x = s.x[drop, :2]
        c = x - x.mean(axis=0)
        Ixx, Iyy = (c[:, 0] ** 2).mean(), (c[:, 1] ** 2).mean()
        t.append(s.time)
        d.append((Ixx - Iyy) / (Ixx + Iyy))
        aspect.append(np.sqrt(Ixx / Iyy))
        n_drop = int(drop.sum())
    return np.array(t), np.array(d), np.array(aspect), n_drop


def period(t, d):
    y = d - d.mean()
    crossings = []
    for k in range(len(y) - 1):
        if y[k] == 0 or y[k] * y[k + 1] < 0:
            crossings.append(t[k] + (t[k + 1] - t[k]) * y[k] / (y[k] - y[k + 1]) if y[k] != y[k + 1] else t[k])
    crossings = np.array(crossings)
    if len(crossings) < 3:
        return None, crossings
    half = np.diff(crossings)
    return 2 * half.mean(), crossings


def damping(t, d, crossings):
    """gamma from the extremum of |d - mean| between successive crossings."""
    y = d - d.mean()
    peaks_t, peaks = [], []
    for a, b in zip(crossings[:-1], crossings[1:]):
        m = (t > a) & (t < b)
        if m.sum() == 0:
            continue
        k = np.argmax(np.abs(y[m]))
        peaks_t.append(t[m][k])
        peaks.append(abs(y[m][k]))
    if len(peaks) < 2:
        return None, peaks_t, peaks
    slope = np.polyfit(peaks_t, np.log(peaks), 1)[0]
    return -slope, peaks_t, peaks


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("--plot")
    a = ap.parse_args()
    run = observables.Run(a.run)
    c = run.case
    t, d, aspect, n_drop = deformation_series(run)
    R = np.sqrt(n_drop * c["spacing"] ** 2 / np.pi)
    w_ref = rayleigh_omega(c["sigma"], c["rho0"], c["rho0"], R)
    T_ref = 2 * np.pi / w_ref
    T, crossings = period(t, d)
    print(f"drop: {n_drop} particles, R = {R:.4f} m (equal area), sigma = {c['sigma']}, rho = {c['rho0']}")
    print(f"aspect ratio sqrt(Ixx/Iyy): t = 0 {aspect[0]:.3f}, min {aspect.min():.3f}, max {aspect.max():.3f}")
    print(f"Rayleigh (n = 2, 2D): omega = {w_ref:.3f} 1/s, period = {T_ref:.4f} s")
    mu = c.get("mu", 0) if c.get("viscosity") == "laplacian" else 0
    s_visc = viscous_mode(c["sigma"], c["rho0"], mu, R) if mu > 0 else None
    if s_visc is not None:
        T_visc = 2 * np.pi / s_visc.imag
        print(f"viscous normal mode (mu = {mu}): omega = {s_visc.imag:.3f} 1/s, period = {T_visc:.4f} s "
              f"({T_visc / T_ref - 1:+.1%} of Rayleigh's), damping rate {-s_visc.real:.3f} 1/s")
    if T is None:
        print(f"fewer than 3 zero crossings of the deformation ({len(crossings)}): no period")
        return 1
    gamma, peaks_t, peaks = damping(t, d, crossings)
    w_d = 2 * np.pi / T
    print(f"zero crossings at t = {', '.join(f'{x:.4f}' for x in crossings)}")
    print(f"measured period (damped) = {T:.4f} s ({T / T_ref - 1:+.1%} of Rayleigh's), omega_d = {w_d:.3f} 1/s")
    if gamma is not None:
        w0 = np.sqrt(w_d ** 2 + gamma ** 2)
        if s_visc is not None:
            print(f"measured period against the viscous normal mode: {T / T_visc - 1:+.1%}")
        print(f"damping rate gamma = {gamma:.3f} 1/s (extremum amplitudes {', '.join(f'{p:.4f}' for p in peaks)}); "
              f"undamped omega_0 = {w0:.3f} 1/s, period {2 * np.pi / w0:.4f} s ({2 * np.pi / w0 / T_ref - 1:+.1%})")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.2))
        ax.plot(t, aspect, "o-", ms=2, label="sph: sqrt(Ixx/Iyy)")
        ax.axhline(1, color="k", lw=0.5)
        for k in range(1, 5):
            ax.axvline(k * T_ref / 2, color="r", lw=0.5, ls="--", label="Rayleigh half periods" if k == 1 else None)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("aspect ratio")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
