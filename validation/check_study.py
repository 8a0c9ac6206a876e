#!/usr/bin/python3
"""Checks what `sph study` wrote (ctest study.ci_small):

  check_study.py STUDY_FOLDER

- study.csv has one row per run of study.json, every run finished, and each
  row's error is finite;
- the runs marked Pareto are non-dominated: no finished run of the same case
  is at most as slow and at most as wrong and better in one of the two; and
  every run off the front is dominated by one on it;
- each recommendation meets its tolerance, and no run that meets it is
  cheaper (less of the study's cost: wall or CPU seconds);
- the chart of each case (PNG and SVG), summary.png and report.md exist.
Prints one line per check and 'N passed, N failed'; exits 1 on a failure.
"""
import csv
import json
import math
import os
import sys

out = sys.argv[1]
passed = failed = 0


def check(ok, what):
    global passed, failed
    print(("ok      " if ok else "FAILED  ") + what)
    if ok:
        passed += 1
    else:
        failed += 1


with open(os.path.join(out, "study.json")) as f:
    study = json.load(f)
with open(os.path.join(out, "results.json")) as f:
    results = json.load(f)
with open(os.path.join(out, "study.csv")) as f:
    rows = list(csv.DictReader(f))

check(len(rows) == len(study["runs"]) and len(rows) > 0, f"study.csv has {len(rows)} rows for {len(study['runs'])} runs")
for r in rows:
    e = float(r["error"]) if r["error"] else math.nan
    check(r["status"] == "finished" and math.isfinite(e) and e >= 0 and float(r["wall_s"]) > 0
          and float(r["N"]) > 0 and float(r["peak_memory_mb"]) > 0,
          f"{r['folder']}: {r['status']}, {r['metric']} = {r['error']}, wall {r['wall_s']} s, "
          f"peak {r['peak_memory_mb']} MB")

for case in [c["name"] for c in study["cases"]]:
    mine = [r for r in rows if r["case"] == case and r["status"] == "finished"]
    pts = {r["folder"]: (float(r[results["cost"]]), float(r["error"])) for r in mine}

    def dominated(p):
        return any(q[0] <= p[0] and q[1] <= p[1] and (q[0] < p[0] or q[1] < p[1]) for q in pts.values())

    front = [r["folder"] for r in mine if r["pareto"] == "True"]
    check(front == results["cases"][case]["pareto"] and len(front) > 0, f"{case}: Pareto front {front}")
    check(all(not dominated(pts[f]) for f in front), f"{case}: no run dominates a run on the front")
    check(all(dominated(p) for f, p in pts.items() if f not in front), f"{case}: every run off the front is dominated")
    for t, folder in results["cases"][case]["recommendations"].items():
        meets = [p for p in pts.values() if p[1] <= float(t)]
        if folder is None:
            check(not meets, f"{case}, tolerance {t}: no recommendation, and no run meets it")
            continue
        w, e = pts[folder]
        check(e <= float(t), f"{case}, tolerance {t}: {folder} has error {e:.4g} <= {t}")
        check(all(p[0] >= w for p in meets), f"{case}, tolerance {t}: no run that meets it is cheaper than {w:.2f} s ({results['cost']})")
    for ext in ("png", "svg"):
        check(os.path.getsize(os.path.join(out, f"{case}.{ext}")) > 1000, f"{case}.{ext} written")
check(os.path.exists(os.path.join(out, "summary.png")), "summary.png written")
with open(os.path.join(out, "report.md")) as f:
    report = f.read()
check(all(f"## {c['name']}" in report for c in study["cases"]), "report.md has a section per case")

print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
