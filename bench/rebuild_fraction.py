#!/usr/bin/env python3
"""Which translation units a change of one header rebuilds.

  bench/rebuild_fraction.py [--build build] [--under include/sph/terms] [--at-most 0.25]

Reads the build's compile_commands.json (configure with
-DCMAKE_EXPORT_COMPILE_COMMANDS=ON), asks the compiler for each unit's
headers (g++ -MM, no compiling), and prints for every header under --under
(default: every header of include/sph) how many of the units include it,
directly or not: the units `make` rebuilds when that header is touched.
Issue 18's aim: touching one term header rebuilds at most a quarter of them.
With --at-most F it exits 1, naming them, if a header under --under is in
more than the fraction F of the units; a declaring header (*_fwd.hpp: a
type's name only, which does not change when the type does) is listed but
not held to it (the test build.term_headers_rebuild_a_quarter).
"""
import argparse
import json
import os
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def headers_of(entry):
    args = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    if "ccache" in os.path.basename(args[0]):
        args = args[1:]
    keep, skip = [], False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a == "-o":
            skip = True
            continue
        if a == "-c" or a.startswith("-o"):
            continue
        keep.append(a)
    run = subprocess.run([args[0], *keep, "-MM"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         cwd=entry["directory"])
    if run.returncode != 0:
        sys.exit(f"rebuild_fraction: the compiler could not list the headers of {entry['file']}:\n{run.stderr}")
    out = run.stdout
    return {os.path.realpath(os.path.join(entry["directory"], p)) for p in out.replace("\\\n", " ").split()[1:]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--under", default=os.path.join(ROOT, "include", "sph"))
    ap.add_argument("--at-most", type=float, default=None, help="fail if a header is in more than this fraction")
    a = ap.parse_args()
    db = os.path.join(a.build, "compile_commands.json")
    if not os.path.exists(db):
        sys.exit(f"rebuild_fraction: {db} not found: configure with -DCMAKE_EXPORT_COMPILE_COMMANDS=ON")
    units = {e["file"]: headers_of(e) for e in json.load(open(db))}
    under = os.path.realpath(a.under)
    rows = []
    for d, _, files in os.walk(under):
        for f in files:
            path = os.path.realpath(os.path.join(d, f))
            rows.append((sum(path in h for h in units.values()), os.path.relpath(path, ROOT)))
    total = len(units)
    print(f"# {total} translation units; units that include each header (touching it rebuilds them)")
    for n, path in sorted(rows, key=lambda r: (-r[0], r[1])):
        print(f"{n:4d} {100 * n / total:5.1f}%  {path}")
    if a.at_most is not None:
        over = [(n, p) for n, p in rows if n > a.at_most * total and not p.endswith("_fwd.hpp")]
        for n, p in over:
            print(f"rebuild_fraction: {p} is in {n} of {total} units, more than {a.at_most:g} of them", file=sys.stderr)
        if not rows or total == 0:
            sys.exit("rebuild_fraction: no header or no unit found")
        sys.exit(1 if over else 0)


if __name__ == "__main__":
    main()
