#!/usr/bin/env python3
"""The hydrostatic tank near its free surface, for the kernel-correction
study (docs/methods/corrections.md): the pressure error of the layers of
particles within one kernel support of the free surface, against the
compressible column dp/dy = -g rho(p), in units of rho0 g H, from the last
snapshot of a run of cases/hydrostatic_tank.case; beside it the figures of
validation/validate.py hydrostatic (the deep layers).

  corrections_surface.py [--time T] RUN_DIR [RUN_DIR ...]

--time T: the snapshot at (or last before) simulated time T instead of the
last one (the deep figures are always those of the last snapshot).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "validation"))
import observables  # noqa: E402


def surface_errors(folder, time=None):
    run = observables.Run(folder)
    c = run.case
    s = run.last()
    if time is not None:
        path = [p for t, p in run.entries if t <= time + 1e-9][-1]
        s = observables.Snapshot(path)
    rho0, g, dx = c["rho0"], c["g"], c["spacing"]
    up = c["dimension"] - 1
    support = {"cubic_spline": 2, "wendland_c2": 2, "gaussian": 3, "muller": 1}[c["kernel"]] * c["h"]
    y = s.x[s.fluid, up]
    p = s["pressure"][s.fluid]
    rho = s["density"][s.fluid]
    width = int(round((c["domain_max"][0] - c["domain_min"][0]) / dx))
    columns = width ** (len(c["domain_min"]) - 1)
    top = np.sort(y)[-columns:].mean()
    H = top + dx / 2
    B = rho0 * c["c0"] ** 2 / c["gamma"]
    ye, pe = observables.compressible_hydrostatic(H, g, lambda q: rho0 * (1 + q / B) ** (1 / c["gamma"]))
    exact = np.interp(y, ye[::-1], pe[::-1])
    depth0 = c["block_max"][-1] - c["block_min"][-1]
    err = (p - exact) / (rho0 * g * depth0)
    near = y >= H - support
    layers = np.round((H - dx / 2 - y) / dx).astype(int)  # 0: the top layer
    per_layer = {k: float(err[(layers == k) & near].mean()) for k in sorted(np.unique(layers[near]))}
    return {
        "time": s.time,
        "near_mean_abs": float(np.abs(err[near]).mean()),
        "near_worst_layer": max(abs(v) for v in per_layer.values()),
        "near_std": float(err[near].std()),
        "per_layer": per_layer,
        "deep": observables.hydrostatic_errors(run, depth0),
        "v_max": float(np.abs(s["velocity"][s.fluid]).max()),
    }


def main():
    args = sys.argv[1:]
    time = None
    if args and args[0] == "--time":
        time = float(args[1])
        args = args[2:]
    for folder in args:
        e = surface_errors(folder, time)
        d = e["deep"]
        layers = ", ".join(f"{k}: {v * 100:+.2f}%" for k, v in e["per_layer"].items())
        print(f"{folder}: t = {e['time']:.3f} s")
        print(f"  near the surface (within one support): mean |err| {e['near_mean_abs'] * 100:.2f}%, "
              f"worst layer {e['near_worst_layer'] * 100:.2f}%, std {e['near_std'] * 100:.2f}%")
        print(f"  layers from the top: {layers}")
        print(f"  deep (validate.py): mean {d['mean_error'] * 100:.2f}%, worst layer {d['worst_layer_error'] * 100:.2f}%, "
              f"drop {d['drop'] * 1e3:.3f} mm (theory {d['drop_theory'] * 1e3:.3f}), |v|max {e['v_max']:.4f} m/s")


if __name__ == "__main__":
    main()
