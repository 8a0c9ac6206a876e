#!/usr/bin/python3
"""Convergence of the Martin & Moyce (1952) dam-break front with resolution,
from the runs' own files (front.csv, the front probe; .vtp for the
detection check):

  front_convergence.py RUN_COARSE RUN_MEDIUM RUN_FINE [--check] [--limit X]
                       [--shrink R] [--markdown]
  front_convergence.py --study STUDY_FOLDER [...]   (its runs, coarse to fine)

For each run: the front Z = x/a against T = t sqrt(2g/a) (a = the column's
width), its relative error against the experiment at their times 1 <= T <= 3,
raw and with the gate-release offset (observables.GATE_OFFSET_T = 0.175: the
simulated Z at T_exp - 0.175 against the measured Z at T_exp, as Lethe's
validation does). Between successive resolutions (each dx half the last):
the difference of Z at the offset comparison's times, mean |dZ|, and the
observed order p = log2(mean|Z1 - Z2| / mean|Z2 - Z3|) (Richardson; the
differences are compared at the same T, so the offset does not enter), the
Richardson-extrapolated front Z3 + (Z3 - Z2) / (2^p - 1) and its error.

Detection check (from the .vtp snapshots): the front as the x past which
the water ahead holds (0.01 m)^2 per unit depth (one particle of the dx =
0.01 run, 16 of the dx = 0.0025 run) instead of the furthest particle, and
the largest gap from the furthest particle to the next (a lone particle
ahead would show a gap over 1.5 dx).

--detect volume takes the volume-ahead front (from the .vtp) for the table's
error columns, the differences, the order and --check.

--check fails (prints FAILED, exit 1) unless the successive differences
shrink (mean|Z2 - Z3| < R mean|Z1 - Z2|, R = --shrink, default 0.9) and the
finest run's mean |error| with the offset is within --limit (default 0.05).
"""
import argparse
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import observables  # noqa: E402

T_RANGE = (1.0, 3.0)
AREA = 0.01 ** 2


def study_runs(folder):
    with open(os.path.join(folder, "study.json")) as f:
        st = json.load(f)
    runs = [os.path.join(folder, r["folder"]) if not os.path.isabs(r["folder"]) else r["folder"] for r in st["runs"]]
    return sorted(runs, key=lambda r: -observables.Run(r).case["spacing"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="*")
    ap.add_argument("--study")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--limit", type=float, default=0.05)
    ap.add_argument("--shrink", type=float, default=0.9)
    ap.add_argument("--no-vtp", action="store_true", help="skip the detection check (the .vtp reading)")
    ap.add_argument("--detect", choices=["probe", "volume"], default="probe",
                    help="the front of the convergence and --check: the probe's (front.csv) or the volume-ahead one (.vtp)")
    a = ap.parse_args()
    folders = study_runs(a.study) if a.study else a.runs
    if len(folders) < 2:
        raise SystemExit("need two or more runs (coarse to fine)")
    runs = [observables.Run(f) for f in folders]
    runs.sort(key=lambda r: -r.case["spacing"])
    ok = True
    ref = observables.reference_table("martin_moyce_1952_front_n2_table.csv")
    sel = (ref[:, 0] >= T_RANGE[0]) & (ref[:, 0] <= T_RANGE[1])
    Tcmp = ref[sel, 0] - observables.GATE_OFFSET_T  # the simulated times of the offset comparison
    curves = []
    print("Martin & Moyce (1952) front, 1 <= T <= 3 (%d points); offset: simulated T + %.3f" %
          (sel.sum(), observables.GATE_OFFSET_T))
    print("| dx | h | dt | raw: mean | raw: mean abs | raw: max abs | offset: mean | offset: mean abs | offset: max abs |"
          " volume-ahead front, offset: mean abs | largest lead gap [dx] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        c = r.case
        T, Z = observables.dam_break_front(r, "probe")
        if a.detect == "volume":
            T, Z, _ = observables.front_volume_ahead(r, AREA)
        if T.max() < T_RANGE[1] - 1e-6:
            print(f"FAILED: {r.folder} ends at T = {T.max():.2f} < {T_RANGE[1]}")
            ok = False
        e0, _ = observables.front_relative_errors(T, Z, 0.0, T_RANGE)
        e1, _ = observables.front_relative_errors(T, Z, observables.GATE_OFFSET_T, T_RANGE)
        curves.append(np.interp(Tcmp, T, Z))
        extra = " | |"
        if not a.no_vtp:
            Tv, Zv, gap = observables.front_volume_ahead(r, AREA)
            ev, _ = observables.front_relative_errors(Tv, Zv, observables.GATE_OFFSET_T, T_RANGE)
            inside = (Tv >= T_RANGE[0] - 0.2) & (Tv <= T_RANGE[1])
            extra = f" | {np.abs(ev).mean() * 100:.2f}% | {gap[inside].max():.2f} |"
        print(f"| {c['spacing']:g} | {c['h']:g} | {c['dt']:g} | {e0.mean() * 100:+.2f}% | {np.abs(e0).mean() * 100:.2f}% |"
              f" {np.abs(e0).max() * 100:.1f}% | {e1.mean() * 100:+.2f}% | {np.abs(e1).mean() * 100:.2f}% |"
              f" {np.abs(e1).max() * 100:.1f}%" + extra)
        last_offset = np.abs(e1).mean()
    diffs = [curves[k] - curves[k + 1] for k in range(len(curves) - 1)]
    norms = [float(np.abs(d).mean()) for d in diffs]
    print()
    for k, d in enumerate(diffs):
        print(f"Z(dx {runs[k].case['spacing']:g}) - Z(dx {runs[k + 1].case['spacing']:g}): mean {d.mean():+.4f},"
              f" mean |.| {norms[k]:.4f} ({norms[k] / np.mean(curves[k + 1]) * 100:.2f}% of Z)")
    if len(diffs) >= 2:
        ratio = norms[-2] / norms[-1] if norms[-1] > 0 else math.inf
        refine = runs[-2].case["spacing"] / runs[-1].case["spacing"]
        p = math.log(ratio) / math.log(refine) if ratio > 0 else float("nan")
        print(f"observed order p = log(|d12| / |d23|) / log({refine:g}) = {p:.2f} (ratio {ratio:.2f})")
        if p > 0 and math.isfinite(p):
            Zx = curves[-1] + (curves[-1] - curves[-2]) / (refine ** p - 1)
            ex = (Zx - ref[sel, 1]) / ref[sel, 1]
            print(f"Richardson-extrapolated front, offset: mean {ex.mean() * 100:+.2f}%, mean |.| {np.abs(ex).mean() * 100:.2f}%")
        if a.check:
            shrinking = norms[-1] < a.shrink * norms[-2]
            print(f"{'ok' if shrinking else 'FAILED'}: successive differences shrink: {norms[-1]:.4f} < "
                  f"{a.shrink} x {norms[-2]:.4f}")
            ok &= shrinking
    if a.check:
        good = last_offset <= a.limit
        print(f"{'ok' if good else 'FAILED'}: finest run's mean |error| with the offset {last_offset * 100:.2f}% <= "
              f"{a.limit * 100:g}%")
        ok &= good
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
