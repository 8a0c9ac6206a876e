#!/usr/bin/env python3
"""Stability maps from the CSVs that stability_atlas.py appends to a folder:

  thresholds.csv  the largest stable c dt / h per integrator x kernel x
                  density, against the linear acoustic analysis
  euler.csv       explicit Euler's energy growth per step against theory
  pairing.csv     the paired fraction over h/dx per kernel
  tensile.csv     the smallest particle gap over time per artificial pressure
  leakage.csv     the largest c0 dt / h that keeps the dam break's fluid,
                  per boundary x wall layers

  atlas_chart.py DIR    writes DIR/<name>.png and .svg for each CSV present

matplotlib (Debian's, Agg backend: no display).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def save(fig, folder, name):
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(folder, f"{name}.{ext}"), dpi=120, bbox_inches="tight")
    plt.close(fig)
    print(os.path.join(folder, f"{name}.png"))


def latest(data, *keys):
    """The last row of each setting (a re-run replaces an earlier one)."""
    last = {}
    for r in data:
        last[tuple(r[k] for k in keys)] = r
    return list(last.values())


def finish_bars(fig, ax, folder, name, labels, xmax, xlabel, title):
    ax.set_yticks(range(len(labels)), labels)
    ax.set_xlim(0, xmax)
    ax.set_xlabel(xlabel)
    ax.set_title(title)
    save(fig, folder, name)


def timestep_map(folder, data):
    data = latest(data, "integrator", "kernel", "density", "h_over_dx")
    fig, ax = plt.subplots(figsize=(8, 0.5 * len(data) + 1.5))
    labels = []
    for k, r in enumerate(data):
        t = float(r["threshold"])
        ax.barh(k, t, color="tab:green", alpha=0.6)
        ax.barh(k, 4 - t, left=t, color="tab:red", alpha=0.25)
        if r["reference"]:
            ax.plot(float(r["reference"]), k, "kx", ms=9, mew=2)
        labels.append(f"{r['integrator']}, {r['kernel']}, {r['density']}, h/dx {r['h_over_dx']}")
    finish_bars(fig, ax, folder, "timestep", labels, 4,
                "c dt / h  (green: stable, red: unstable; x: linear acoustic analysis)",
                "Largest stable time step, periodic lattice at rest")


def euler_map(folder, data):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for kernel in sorted({r["kernel"] for r in data}):
        sel = sorted((float(r["courant"]), float(r["growth_per_step"]), float(r["theory"]))
                     for r in data if r["kernel"] == kernel)
        ax.loglog([s[0] for s in sel], [s[1] for s in sel], "o", label=f"{kernel}: measured")
        ax.loglog([s[0] for s in sel], [s[2] for s in sel], "-", label=f"{kernel}: ln(1 + (omega_max dt)^2)")
    ax.set_xlabel("c dt / h")
    ax.set_ylabel("growth of ln(kinetic energy) per step")
    ax.set_title("Explicit Euler: unstable at every time step")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    save(fig, folder, "euler")


def pairing_map(folder, data):
    data = latest(data, "kernel", "h_over_dx")
    kernels = sorted({r["kernel"] for r in data})
    fig, ax = plt.subplots(figsize=(8, 0.7 * len(kernels) + 1.8))
    for k, kernel in enumerate(kernels):
        sel = sorted((float(r["h_over_dx"]), float(r["paired_fraction"])) for r in data if r["kernel"] == kernel)
        for hdx, frac in sel:
            ax.scatter(hdx, k, s=40 + 400 * frac, c="tab:red" if frac > 0.10 else "tab:green",
                       edgecolors="k", zorder=3)
            ax.annotate(f"{100 * frac:.0f}%", (hdx, k), textcoords="offset points", xytext=(0, 12),
                        ha="center", fontsize=7)
    ax.set_yticks(range(len(kernels)), kernels)
    ax.set_ylim(-0.6, len(kernels) - 0.2)
    ax.set_xlabel("h / dx  (red: more than 10% of the particles paired closer than 0.6 dx)")
    ax.set_title("Pairing on a periodic lattice under pressure")
    ax.grid(True, axis="x", alpha=0.3)
    save(fig, folder, "pairing")


def tensile_map(folder, data):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for eps in sorted({r["artificial_pressure"] for r in data}, key=float):
        sel = sorted((float(r["time"]), float(r["smallest_gap_dx"])) for r in data if r["artificial_pressure"] == eps)
        ax.plot([t for t, _ in sel], [g for _, g in sel], "o-", ms=3,
                label="no correction" if float(eps) == 0 else f"artificial pressure eps = {eps}")
    ax.axhline(0.5, color="k", ls=":", lw=1)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("smallest particle gap / dx")
    ax.set_title("Tensile instability: an expanding Tait block")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    save(fig, folder, "tensile")


def leakage_map(folder, data):
    data = sorted(latest(data, "boundary", "wall_layers"), key=lambda r: (r["boundary"], int(r["wall_layers"])))
    fig, ax = plt.subplots(figsize=(8, 0.5 * len(data) + 1.5))
    colour = {"leaked": "tab:orange", "blew up": "tab:red"}
    labels = []
    for k, r in enumerate(data):
        t = float(r["threshold"])
        ax.barh(k, t, color="tab:green", alpha=0.6)
        fail = "leaked" if r["failure_above"].startswith("leaked") else (
            "blew up" if r["failure_above"].startswith("blew") else None)
        if fail:
            ax.barh(k, 4 - t, left=t, color=colour[fail], alpha=0.35)
            ax.text(t + 0.05, k, fail, va="center", fontsize=8)
        labels.append(f"{r['boundary']}, {r['wall_layers']} layer{'s' if r['wall_layers'] != '1' else ''}")
    finish_bars(fig, ax, folder, "leakage", labels, 4,
                "c0 dt / h  (green: the fluid stays inside the walls to the end)",
                "Dam break: wall layers and time step against leakage")


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    folder = sys.argv[1]
    made = 0
    for name, draw in (("thresholds", timestep_map), ("euler", euler_map), ("pairing", pairing_map),
                       ("tensile", tensile_map), ("leakage", leakage_map)):
        path = os.path.join(folder, f"{name}.csv")
        if os.path.exists(path):
            draw(folder, rows(path))
            made += 1
    if not made:
        raise SystemExit(f"{folder}: no thresholds.csv, euler.csv, pairing.csv or leakage.csv")


if __name__ == "__main__":
    main()
