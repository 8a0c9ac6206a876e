#!/usr/bin/env python3
"""Pressure noise at a point probe (docs/methods/corrections.md): the
standard deviation of p(t) about a smoothed p(t), from a run's probes.csv
(cases/dam_break_mm.case records the left wall's pressure near the floor,
probe `left_wall`, every millisecond).

  pressure_noise.py [--probe NAME] [--window W] [--from T0] [--to T1] [--plot PNG] RUN_DIR [RUN_DIR ...]

Smooth signal: a Savitzky-Golay filter (local least-squares quadratic) over
a centred window of W samples (default 41: 41 ms at probe_interval 1 ms,
which keeps the surge's slow decay, time scale ~0.1 s, and takes out the
acoustic ringing of the column, period ~2 H / c0 ~ 25 ms, and faster).
Noise: the standard deviation of p - p_smooth over the samples whose
window is complete, from T0 to T1 (default: all); also in units of rho0 g H0
(H0: the column's height, the top of block_max).
"""
import argparse
import json
import os
import sys

import numpy as np


def savitzky_golay(y, window, order=2):
    half = window // 2
    k = np.arange(-half, half + 1)
    A = np.vander(k, order + 1, increasing=True)
    coeff = np.linalg.pinv(A)[0]  # value at the centre of the local fit
    out = np.full(len(y), np.nan)
    for i in range(half, len(y) - half):
        out[i] = coeff @ y[i - half:i + half + 1]
    return out


def noise(folder, probe, window, t0, t1=float("inf")):
    with open(os.path.join(folder, "probes.csv")) as f:
        header = f.readline().strip().split(",")
    data = np.genfromtxt(os.path.join(folder, "probes.csv"), delimiter=",", skip_header=1)
    col = next(k for k, name in enumerate(header) if name.startswith(probe + " pressure"))
    t, p = data[:, 0], data[:, col]
    ok = np.isfinite(p)
    t, p = t[ok], p[ok]
    smooth = savitzky_golay(p, window)
    m = np.isfinite(smooth) & (t >= t0) & (t <= t1)
    r = p[m] - smooth[m]
    with open(os.path.join(folder, "run.json")) as f:
        case = json.load(f)["case"]
    scale = case["rho0"] * case["g"] * case["block_max"][-1]
    return t[m], p[m], smooth[m], r.std(), scale


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--probe", default="left_wall")
    ap.add_argument("--window", type=int, default=41)
    ap.add_argument("--from", dest="t0", type=float, default=0.0)
    ap.add_argument("--to", dest="t1", type=float, default=float("inf"))
    ap.add_argument("--plot", help="p(t) and its smoothed signal of each run, one panel each")
    a = ap.parse_args()
    if a.window % 2 == 0 or a.window < 5:
        raise SystemExit("--window must be odd and >= 5")
    print(f"| run | samples | mean p [N/m] | std(p - SG{a.window}) [N/m] | in rho0 g H0 |")
    print("|---|---|---|---|---|")
    curves = []
    for folder in a.runs:
        t, p, smooth, s, scale = noise(folder, a.probe, a.window, a.t0, a.t1)
        name = os.path.basename(os.path.normpath(folder))
        print(f"| {name} | {len(t)} | {p.mean():.0f} | {s:.1f} | {s / scale:.2%} |")
        curves.append((name, t, p, smooth, s))
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(len(curves), 1, figsize=(7, 1.6 * len(curves) + 0.6), sharex=True, sharey=True)
        for ax, (name, t, p, smooth, s) in zip(np.atleast_1d(axes), curves):
            ax.plot(t, p, lw=0.6, label="p")
            ax.plot(t, smooth, lw=1.2, label=f"SG{a.window}")
            ax.set_title(f"{name}: std {s:.0f} N/m", fontsize=8, loc="left")
            ax.set_ylabel("p [N/m]", fontsize=8)
        np.atleast_1d(axes)[-1].set_xlabel("t [s]")
        np.atleast_1d(axes)[0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main())
