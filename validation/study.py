#!/usr/bin/python3
"""The analysis of `sph study` (src/study.cpp runs the runs, then this):

  study.py STUDY_FOLDER [--cost wall|cpu]

reads STUDY_FOLDER/study.json (the cases, methods, resolutions and run
folders the study ran), measures every run's error from its own .vtp files
with observables.py, takes its costs from its run.json, and writes into
STUDY_FOLDER:

  study.csv        one row per run: case, method, resolution, status, every
                   varied key (its resolved value), N (fluid particles), dx,
                   the error metric and its value, every error measure of the
                   observable, costs (wall and CPU seconds, steps,
                   particle-steps/s, mean neighbours, peak memory, threads),
                   whether the run is on the Pareto front of its case
  CASE.png, .svg   error against wall time (log-log) for a case: one marker and
                   colour per method, its resolutions joined by a line, the
                   Pareto front (runs no other run beats in both) dashed, each
                   tolerance a horizontal line, the recommendation ringed
  summary.png/svg  the cases side by side
  report.md        for each case and tolerance the cheapest run (least wall
                   time) whose error meets it, with the pictures

The cost is wall-clock seconds unless the study file says cost = "cpu" (or
--cost cpu re-measures a study folder that way): on a machine shared with
other work, CPU seconds are the steadier measure.
  results.json     the Pareto fronts and recommendations (check_study.py reads it)

Error metrics (each observable's first one is charted and recommended on):
  dam_break    front_mean_abs_error: mean |Z - Z_MM| / Z_MM of the surge front
               Z = x/a at Martin & Moyce's times 1 <= T <= 3 (T = t sqrt(2g/a));
               also the max, the signed mean, and the residual height error
  hydrostatic  mean_error: mean |p - p_exact| / (rho0 g H) over the fluid at
               the last snapshot, p_exact the compressible column; also the
               worst layer deeper than a support below the surface
  toy_star     l2_error: relative L2 of the density of the particles inside
               0.9 R against the analytic polytrope, at the last snapshot;
               also the mean and worst relative error inside 0.5 R

Matplotlib with the Agg backend (no display), Debian's /usr/bin/python3.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import observables  # noqa: E402


def dam_break(run):
    return observables.dam_break_errors(run)


def hydrostatic(run):
    c = run.case
    return observables.hydrostatic_errors(run, c["block_max"][-1] - c["block_min"][-1])


def toy_star(run):
    return observables.toy_star_errors(run)


# observable -> (measure, charted metric, what the metric is)
OBSERVABLES = {
    "dam_break": (dam_break, "front_mean_abs_error",
                  "mean |Z - Z_MM| / Z_MM of the surge front against Martin & Moyce (1952), 1 <= T <= 3"),
    "hydrostatic": (hydrostatic, "mean_error",
                    "mean |p - p_exact| / (rho0 g H) over the fluid at the last snapshot (compressible column)"),
    "toy_star": (toy_star, "l2_error",
                 "relative L2 density error inside 0.9 R against the analytic polytrope (Monaghan & Price 2004)"),
}

COSTS = ["wall_s", "cpu_s", "steps", "particle_steps_per_s", "mean_neighbours", "peak_memory_mb", "threads"]


def measure(folder, observable):
    """(status, record, errors) of one run folder."""
    path = os.path.join(folder, "run.json")
    if not os.path.exists(path):
        return "missing", None, {}
    with open(path) as f:
        record = json.load(f)
    if record["status"] != "finished":
        return record["status"], record, {}
    try:
        return "finished", record, OBSERVABLES[observable][0](observables.Run(folder))
    except Exception as e:  # a run whose files cannot be measured is a row that says so
        return f"not measured: {e}", record, {}


def costs(record):
    s = record["summary"]
    used = record["threads"]["used"]
    return {
        "wall_s": s["wall_seconds"],
        "cpu_s": s.get("cpu_seconds", float("nan")),
        "steps": s["steps"],
        "particle_steps_per_s": s["particle_steps_per_second"],
        "mean_neighbours": s["neighbours_per_particle"],
        "peak_memory_mb": s.get("peak_memory_bytes", float("nan")) / 2 ** 20,
        "threads": max(used) if used else "",
    }


def pareto(points):
    """Indices of the points (cost, error) that no other point beats in both
    (<= in both, < in one)."""
    front = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for j, (c2, e2) in enumerate(points) if j != i):
            front.append(i)
    return front


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def fmt(v):
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, (list, dict)):
        return json.dumps(v)
    return str(v)


def setting(row, varied):
    return ", ".join(f"{k} = {fmt(row[k])}" for k in varied if row.get(k, "") != "")


COST_LABEL = {"wall_s": "wall time [s]", "cpu_s": "CPU time [s]"}


def plot_case(ax, case, rows, methods, tolerances, recommended, cost):
    markers = "osD^vP*Xh<>"
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    ok = [r for r in rows if finite(r["error"])]
    for k, m in enumerate(methods):
        mine = [r for r in ok if r["method"] == m]
        if not mine:
            continue
        ax.plot([r[cost] for r in mine], [r["error"] for r in mine], marker=markers[k % len(markers)],
                color=colours[k % len(colours)], label=m, linewidth=1.2, markersize=6)
        for r in mine:
            ax.annotate(r["resolution"], (r[cost], r["error"]), textcoords="offset points", xytext=(4, 4),
                        fontsize=6, color=colours[k % len(colours)])
    front = sorted((r for r in ok if r["pareto"]), key=lambda r: r[cost])
    if front:
        ax.step([r[cost] for r in front], [r["error"] for r in front], where="post", color="black",
                linestyle="--", linewidth=1, marker="s", markersize=11, markerfacecolor="none",
                label="Pareto front")
    for t in tolerances:
        ax.axhline(t, color="grey", linestyle=":", linewidth=1.2)
        ax.annotate(f"tolerance {t:g}", (0.01, t), xycoords=("axes fraction", "data"), ha="left", va="bottom",
                    fontsize=8, color="dimgrey")
    ringed = False
    for t, r in recommended.items():
        if r is not None:
            ax.plot([r[cost]], [r["error"]], marker="o", markersize=14, markerfacecolor="none",
                    markeredgecolor="red", linestyle="none", label=None if ringed else "recommended")
            ringed = True
    blown = [r for r in rows if r["status"] == "blew_up"]
    if blown:
        ax.text(0.01, 0.01, "blew up: " + ", ".join(f"{r['method']}/{r['resolution']}" for r in blown),
                transform=ax.transAxes, fontsize=7, color="red", va="bottom")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(COST_LABEL[cost])
    ax.set_ylabel(rows[0]["metric"] if rows else "error")
    ax.set_title(case)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")


def main():
    args = sys.argv[1:]
    cost_arg = None
    if len(args) == 3 and args[1] == "--cost" and args[2] in ("wall", "cpu"):
        cost_arg = args[2]
        args = args[:1]
    if len(args) != 1:
        raise SystemExit(__doc__)
    out = args[0]
    with open(os.path.join(out, "study.json")) as f:
        study = json.load(f)
    cost = {"wall": "wall_s", "cpu": "cpu_s"}[cost_arg or study.get("cost", "wall")]
    tolerances = study["tolerances"]
    observable = {c["name"]: c["observable"] for c in study["cases"]}
    # The charted metric of each case: the study file's third element, else the observable's first.
    case_metric = {c["name"]: c.get("metric") or OBSERVABLES[c["observable"]][1] for c in study["cases"]}
    varied = []
    for v in study["methods"] + study["resolutions"]:
        for k in v["overrides"]:
            if k not in varied:
                varied.append(k)

    rows = []
    error_keys = []
    for run in study["runs"]:
        folder = os.path.join(out, run["folder"])
        status, record, errors = measure(folder, observable[run["case"]])
        metric = case_metric[run["case"]]
        row = {"case": run["case"], "method": run["method"], "resolution": run["resolution"], "status": status}
        case = record["case"] if record else {}
        for k in varied:
            row[k] = case.get(k, "")
        row["N"] = record["summary"]["fluid_particles"] if record else ""
        row["dx"] = case.get("spacing", "")
        row["metric"] = metric
        if errors and metric not in errors:
            raise SystemExit(f"study.py: case {run['case']}: no error metric '{metric}': "
                             f"the {observable[run['case']]} observable has {', '.join(errors)}")
        row["error"] = errors.get(metric, float("nan"))
        for k, v in errors.items():
            if k not in error_keys:
                error_keys.append(k)
            row[k] = v
        row.update(costs(record) if record else {k: "" for k in COSTS})
        row["folder"] = run["folder"]
        rows.append(row)

    # Pareto fronts and recommendations, per case.
    results = {"tolerances": tolerances, "cost": cost, "cases": {}}
    recommended_rows = {}
    for case in [c["name"] for c in study["cases"]]:
        mine = [r for r in rows if r["case"] == case]
        ok = [r for r in mine if r["status"] == "finished" and finite(r["error"]) and finite(r[cost])]
        for r in mine:
            r["pareto"] = False
        for i in pareto([(r[cost], r["error"]) for r in ok]):
            ok[i]["pareto"] = True
        rec = {}
        for t in tolerances:
            meets = [r for r in ok if r["error"] <= t]
            rec[t] = min(meets, key=lambda r: r[cost]) if meets else None
        recommended_rows[case] = rec
        results["cases"][case] = {
            "metric": case_metric[case],
            "pareto": [r["folder"] for r in ok if r["pareto"]],
            "recommendations": {f"{t:g}": (rec[t]["folder"] if rec[t] else None) for t in tolerances},
        }

    columns = (["case", "method", "resolution", "status"] + varied + ["N", "dx", "metric", "error"] + error_keys +
               COSTS + ["pareto", "folder"])
    with open(os.path.join(out, "study.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([fmt(r.get(k, "")) for k in columns])
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(results, f, indent=2)

    methods = [m["name"] for m in study["methods"]]
    cases = [c["name"] for c in study["cases"]]
    for case in cases:
        fig, ax = plt.subplots(figsize=(7, 5))
        plot_case(ax, case, [r for r in rows if r["case"] == case], methods, tolerances, recommended_rows[case], cost)
        fig.tight_layout()
        for ext in ("png", "svg"):
            fig.savefig(os.path.join(out, f"{case}.{ext}"), dpi=110)
        plt.close(fig)
    fig, axes = plt.subplots(1, len(cases), figsize=(6 * len(cases), 4.5), squeeze=False)
    for ax, case in zip(axes[0], cases):
        plot_case(ax, case, [r for r in rows if r["case"] == case], methods, tolerances, recommended_rows[case], cost)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, f"summary.{ext}"), dpi=90)
    plt.close(fig)

    # report.md
    lines = [f"# Study {study['study']}", "", f"Made by `{study['command']}`.", "",
             f"Cost: {COST_LABEL[cost]} of each run, measured on the machine that ran the study; each run's "
             "folder keeps its run.json. \"Cheapest\" below means the least of that cost.", ""]
    for case in cases:
        obs = observable[case]
        mine = [r for r in rows if r["case"] == case]
        about = OBSERVABLES[obs][2] if case_metric[case] == OBSERVABLES[obs][1] else "see validation/observables.py"
        lines += [f"## {case}", "", f"Error: `{case_metric[case]}`, {about}.", "",
                  f"![{case}]({case}.png)", ""]
        for t in tolerances:
            r = recommended_rows[case][t]
            if r is None:
                ok = [x for x in mine if finite(x["error"])]
                best = min(ok, key=lambda x: x["error"]) if ok else None
                lines.append(f"- tolerance {t:g}: **no run meets it**" +
                             (f"; the smallest error is {best['error']:.4g} ({best['method']}, {best['resolution']}: "
                              f"{setting(best, varied)}, {best[cost]:.1f} s)" if best else ""))
            else:
                lines.append(f"- tolerance {t:g}: **{r['method']}, {r['resolution']}** ({setting(r, varied)}): "
                             f"error {r['error']:.4g}, {r['wall_s']:.1f} s wall, {r['cpu_s']:.1f} s CPU, "
                             f"N = {r['N']}, {r['steps']} steps, "
                             f"{r['threads']} thread(s)")
        lines += ["", "| method | resolution | N | dx | error | wall [s] | CPU [s] | particle-steps/s | neighbours | "
                  "peak MB | Pareto | status |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in sorted(mine, key=lambda x: (x[cost] if finite(x[cost]) else math.inf)):
            lines.append(f"| {r['method']} | {r['resolution']} | {r['N']} | {fmt(r['dx'])} | {fmt(r['error'])} | "
                         f"{fmt(r['wall_s'])} | {fmt(r['cpu_s'])} | {fmt(r['particle_steps_per_s'])} | "
                         f"{fmt(r['mean_neighbours'])} | "
                         f"{fmt(r['peak_memory_mb'])} | {'yes' if r['pareto'] else ''} | {r['status']} |")
        lines.append("")
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write("\n".join(lines))

    print(f"study {study['study']}: {len(rows)} runs measured; {out}/study.csv, report.md, "
          + ", ".join(f"{c}.png" for c in cases) + ", summary.png")
    for case in cases:
        for t in tolerances:
            r = recommended_rows[case][t]
            print(f"  {case}, tolerance {t:g}: " +
                  (f"{r['method']}, {r['resolution']} ({setting(r, varied)}): error {r['error']:.4g}, "
                   f"{r[cost]:.1f} s ({cost})" if r else "no run meets it"))


if __name__ == "__main__":
    main()
