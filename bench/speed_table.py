#!/usr/bin/env python3
"""The speed table: sph's full water physics (and the seed scheme) against
the yardstick, per CPU second, with memory. `bench/run.sh` runs it.

Scenarios (each `sph run` of a shipped case with its spacing, h and dt
scaled together, so neighbours per particle and c0 dt / h stay the case's):
  water 2D  cases/dam_break.case (Wendland, continuity density + delta-SPH,
            Tait, Monaghan 0.02, dummy walls, leap-frog), h = 1.5 dx
  seed 2D   cases/dam_break_seed.case (the seed scheme), h = 1.333 dx
  water 3D  cases/dam_break_3d.case's tank and column with the same water
            physics as water 2D (dummy walls, continuity + delta-SPH, Tait
            c0 = 40, Monaghan 0.02), h = 1.3 dx
  DSPH-like 2D  water 2D with DualSPHysics' choices for its 2D dam-break
            validation case: dynamic walls (DBC), h = sqrt(2) dx
            (--scenarios dsph2d; not in the default set)
The yardstick (build/sph-yardstick, or build/sph-yardstick-3d for 3D) runs
interleaved with them at the same N and h/dx.

CPU seconds are the user + system time of the process (os.wait4) for S
steps minus that of a 1-step run of the same set-up, so set-up, reading and
writing are left out: particle-steps per CPU second = N (S - 1) / (cpu_S -
cpu_1), over all particles (fluid and wall). With 1 thread the process is
pinned to one core (taskset -c 0). Wall-clock particle-steps per second are
printed too. Medians over the repeats; one repeat of every row in turn.

Memory: the peak resident set (ru_maxrss) of the S-step run; "B/p" is its
growth per added particle between the two sizes of a scenario,
(RSS_2 - RSS_1) / (N_2 - N_1), which leaves out the program's fixed part.

--old-build DIR: the sph of an earlier build (DIR/sph) runs every row too,
interleaved, as extra rows marked "old"; "ratio" then also reads against the
same yardstick, so before/after figures of a change come from one run.

Figures are printed, never asserted; `uptime` is printed before and after.
"""
import argparse
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(cmd, env=None, pin=False):
    """Run cmd; return (stdout+stderr, cpu seconds, peak RSS in bytes)."""
    if pin and shutil.which("taskset"):
        cmd = ["taskset", "-c", "0"] + cmd
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    out = proc.stdout.read()
    _, status, ru = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit(f"speed_table: {' '.join(cmd)} failed (exit {proc.returncode}):\n{out[-2000:]}")
    return out, ru.ru_utime + ru.ru_stime, ru.ru_maxrss * 1024


class Scenario:
    def __init__(self, name, dim, case, hdx, extra, dt_of, spacing_of, yardstick_hdx=None):
        self.name, self.dim, self.case, self.hdx, self.extra = name, dim, case, hdx, extra
        self.dt_of, self.spacing_of = dt_of, spacing_of
        self.yardstick_hdx = yardstick_hdx or hdx

    def command(self, exe, n, steps, threads, folder):
        s = self.spacing_of(n)
        h = self.hdx * s
        dt = self.dt_of(h)
        return [exe, "run", os.path.join(ROOT, "cases", self.case), *self.extra, "--spacing", repr(s), "--h", repr(h),
                "--dt", repr(dt), "--end_time", repr(steps * dt), "--output_interval", repr(steps * dt),
                "--threads", str(threads), "--output", folder, "--overwrite"], dt


# Fluid columns: 2D 0.25 x 0.5 m (dam_break.case, dam_break_seed.case);
# 3D 0.3 x 0.25 x 0.5 m (dam_break_3d.case). Spacing for n fluid particles.
def spacing2d(n):
    return math.sqrt(0.25 * 0.5 / n)


def spacing3d(n):
    return (0.3 * 0.25 * 0.5 / n) ** (1 / 3)


WATER_3D = ["--boundary", "dummy", "--density", "continuity", "--delta", "0.1", "--eos", "tait", "--c0", "40",
            "--gamma", "7", "--alpha", "0.02", "--xsph", "0", "--negative_pressure", "clamp", "--hydrostatic_start",
            "--cfl", "0", "--block_min", "[0, 0.125, 0]", "--block_max", "[0.3, 0.375, 0.5]"]

SCENARIOS = {
    # dam_break.case: c0 = 44, dt = 5e-5 at h = 0.015 (c0 dt / h = 0.147)
    "water2d": Scenario("water 2D", 2, "dam_break.case", 1.5, [], lambda h: 5e-5 * h / 0.015, spacing2d),
    # dam_break_seed.case: h = 0.01 is the seed's support radius (about 4
    # neighbours), dt = 1e-4, spacing 0.0075. The yardstick runs at its own
    # h = 1.3 dx (about 19 neighbours), as in the README's table whose ratio
    # 5.09 (10 011 particles, 1 thread) issue 19 names as the seed's aim.
    "seed2d": Scenario("seed 2D", 2, "dam_break_seed.case", 0.01 / 0.0075, [], lambda h: 1e-4 * h / 0.01,
                       spacing2d, yardstick_hdx=1.3),
    "water3d": Scenario("water 3D", 3, "dam_break_3d.case", 1.3, WATER_3D, lambda h: 0.15 * h / 40, spacing3d),
    # The water dam break with DualSPHysics' own choices for its 2D dam-break
    # validation case (CaseDambreakVal2D, as issue 19 quotes them): dynamic
    # boundary particles (DBC), h = sqrt(2) dx, Wendland, Monaghan 0.02,
    # Fourtakas density diffusion 0.1; sph's leap-frog and double precision.
    # Issue 19 measured DualSPHysics 5.4 CPU on that case at 1.52 M
    # particle-steps per CPU second on this machine (21 001 particles).
    "dsph2d": Scenario("DSPH-like 2D", 2, "dam_break.case", 2 ** 0.5, ["--boundary", "dynamic"],
                       lambda h: 5e-5 * h / 0.015, spacing2d),
}


def parse_run(out):
    n = int(re.search(r"particles\s+(\d+)", out).group(1))
    wall = re.search(r"particles\s+\d+ \((\d+) wall\)", out)
    nb = float(re.search(r"neighbours\s+([\d.]+) per particle", out).group(1))
    return n, int(wall.group(1)) if wall else 0, nb


def yardstick_cmd(build, dim, n, steps, hdx):
    if dim == 2:
        return [os.path.join(build, "sph-yardstick"), str(max(2, round(math.sqrt(n / 2)))), str(steps), repr(hdx)]
    return [os.path.join(build, "sph-yardstick-3d"), str(max(2, round((n / 2) ** (1 / 3)))), str(steps), repr(hdx)]


def parse_yardstick(out):
    m = re.search(r"N=(\d+) threads=\d+ neighbours=([\d.]+) particle-steps/s=([\d.e+]+)", out)
    return int(m.group(1)), float(m.group(2)), float(m.group(3))


def rate(work, seconds):
    """work / seconds, or NaN when the difference of two timings is lost in their granularity."""
    return work / seconds if seconds > 0.01 else float("nan")


def fmt(x):
    if math.isnan(x):
        return "too short"
    return f"{x / 1e6:.3f} M" if x >= 1e5 else f"{x / 1e3:.1f} k"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--scenarios", default="water2d,seed2d,water3d")
    ap.add_argument("--n2d", default="20000,200000",
                    help="fluid particles of the 2D scenarios (two or more sizes, e.g. 1e4,1e5,1e6,1e7 for the "
                         "linear-cost table; B/p is taken between the first and the last)")
    ap.add_argument("--n3d", default="20000,100000", help="fluid particles of the 3D scenario (as --n2d)")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=0, help="steps per run (default: about 4e6 particle-steps)")
    ap.add_argument("--old-build", help="an earlier build folder whose sph runs every row too, interleaved")
    ap.add_argument("--sph_flags", default="",
                    help="more flags for every sph run, e.g. \"--neighbour_skin 0.1\" (one string, split at spaces)")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless every figure of every row is finite and positive (the smoke test)")
    a = ap.parse_args()
    sph = os.path.join(a.build, "sph")
    programs = {"": sph}  # row tag -> sph executable
    if a.old_build:
        programs[" old"] = os.path.join(a.old_build, "sph")
    for exe in (*programs.values(), os.path.join(a.build, "sph-yardstick"), os.path.join(a.build, "sph-yardstick-3d")):
        if not os.access(exe, os.X_OK):
            sys.exit(f"speed_table: {exe} not found: build it first (cmake --build build)")
    names = a.scenarios.split(",")
    for s in SCENARIOS.values():
        s.extra = s.extra + a.sph_flags.split()
    for s in names:
        if s not in SCENARIOS:
            sys.exit(f"speed_table: --scenarios: unknown '{s}' (allowed: {', '.join(SCENARIOS)})")
    threads = [int(t) for t in a.threads.split(",")]
    rows = []  # (scenario, n_fluid, threads)
    for s in names:
        sizes = a.n3d if SCENARIOS[s].dim == 3 else a.n2d
        for n in [int(float(v)) for v in sizes.split(",")]:
            for t in threads:
                for tag in programs:
                    rows.append((s, n, t, tag))
    print("# uptime before:", subprocess.run(["uptime"], stdout=subprocess.PIPE, text=True).stdout.strip())
    print(f"# {a.repeats} interleaved repeats; medians; p-s = particle-steps; CPU = user + system seconds "
          "of S steps minus a 1-step run")
    results = {r: {"cpu": [], "wall": [], "ycpu": [], "rss": []} for r in rows}
    info = {}
    with tempfile.TemporaryDirectory() as tmp:
        folder = os.path.join(tmp, "run")
        for rep in range(a.repeats):
            for r in rows:
                s, n, t, tag = r
                sc = SCENARIOS[s]
                steps = a.steps or max(10, min(400, round(4e6 / n)))
                env = dict(os.environ, OMP_NUM_THREADS=str(t))
                cmd1, dt = sc.command(programs[tag], n, 1, t, folder)
                out1, cpu1, _ = timed(cmd1, env, pin=(t == 1))
                cmd, dt = sc.command(programs[tag], n, steps, t, folder)
                out, cpu, rss = timed(cmd, env, pin=(t == 1))
                total, wall, nb = parse_run(out)
                stepping = float(re.search(r"stepping ([\d.e+-]+) s", out).group(1))
                stepping1 = float(re.search(r"stepping ([\d.e+-]+) s", out1).group(1))
                results[r]["cpu"].append(rate(total * (steps - 1), cpu - cpu1))
                results[r]["wall"].append(rate(total * (steps - 1), stepping - stepping1))
                results[r]["rss"].append(rss)
                # The yardstick: S + 5 steps (it times the steps after the fifth) minus a 6-step run.
                ycmd = yardstick_cmd(a.build, sc.dim, total, steps + 5, sc.yardstick_hdx)
                yout1, ycpu1, _ = timed(yardstick_cmd(a.build, sc.dim, total, 6, sc.yardstick_hdx), env, pin=(t == 1))
                yout, ycpu, _ = timed(ycmd, env, pin=(t == 1))
                yn, ynb, _ = parse_yardstick(yout)
                results[r]["ycpu"].append(rate(yn * (steps - 1), ycpu - ycpu1))
                info[r] = (total, wall, nb, steps, dt, yn, ynb)
    print(f"{'scenario':13s} {'D':>1s} {'N':>7s} {'wall':>6s} {'nbrs':>5s} {'thr':>3s} {'p-s/CPU s':>10s} "
          f"{'p-s/s':>10s} {'CPU s/sim s':>11s} {'ns/p-s':>6s} {'ns/pair':>7s} {'RSS MB':>7s} {'B/p':>5s} {'yardstick':>10s} "
          f"{'y N':>7s} {'y nbrs':>6s} {'y ns/pair':>9s} {'ratio':>6s} {'range':>9s}")
    bad = []
    for r in rows:
        s, n, t, tag = r
        total, wall, nb, steps, dt, yn, ynb = info[r]
        cpu = statistics.median(results[r]["cpu"])
        wallps = statistics.median(results[r]["wall"])
        ycpu = statistics.median(results[r]["ycpu"])
        rss = statistics.median(results[r]["rss"])
        # B/p: growth of the peak RSS between this scenario's two sizes (same threads).
        pair = [q for q in rows if q[0] == s and q[2] == t and q[3] == tag]
        bpp = "-"
        if len(pair) >= 2 and r == pair[-1]:
            lo, hi = pair[0], pair[-1]
            dn = info[hi][0] - info[lo][0]
            if dn > 0:
                bpp = f"{(statistics.median(results[hi]['rss']) - statistics.median(results[lo]['rss'])) / dn:.0f}"
        # Each repeat's own ratio (its sph and yardstick runs were neighbours
        # in time): their range shows how far the host's load moved it.
        each = [c / y for c, y in zip(results[r]["cpu"], results[r]["ycpu"]) if math.isfinite(c / y)]
        spread = f"{min(each):.2f}-{max(each):.2f}" if each else "-"
        cpu_per_sim = total / cpu / dt
        # CPU nanoseconds per listed neighbour (per pair seen from one side).
        ns_pair = 1e9 / (cpu * nb) if nb > 0 else float("nan")
        y_ns_pair = 1e9 / (ycpu * ynb) if ynb > 0 else float("nan")
        print(f"{SCENARIOS[s].name + tag:13s} {SCENARIOS[s].dim:1d} {total:7d} {wall:6d} {nb:5.1f} {t:3d} {fmt(cpu):>10s} "
              f"{fmt(wallps):>10s} {cpu_per_sim:11.1f} {1e9 / cpu:6.0f} {ns_pair:7.1f} {rss / 1e6:7.1f} {bpp:>5s} {fmt(ycpu):>10s} "
              f"{yn:7d} {ynb:6.1f} {y_ns_pair:9.1f} {cpu / ycpu:6.2f} {spread:>9s}")
        figures = [cpu, wallps, ycpu, rss, nb, ynb, cpu_per_sim]
        if not each or not all(math.isfinite(f) and f > 0 for f in figures):
            bad.append(f"{SCENARIOS[s].name}{tag} N={total} threads={t}")
    print("# ratio = sph p-s per CPU s / yardstick p-s per CPU s (the same thread count, interleaved), of the"
          " medians; range: the lowest and highest of the repeats' own ratios")
    print("# nbrs: sph's mean neighbours per particle (a wall particle lists only fluid neighbours);"
          " y nbrs: the yardstick's; ns/p-s: CPU ns per particle-step (flat in N when the cost grows"
          " linearly); ns/pair: CPU ns per particle-step and listed neighbour")
    print("# B/p: growth of the peak RSS per added particle between the scenario's two sizes")
    print("# uptime after:", subprocess.run(["uptime"], stdout=subprocess.PIPE, text=True).stdout.strip())
    if a.check and bad:
        sys.exit("speed_table: rows without a figure (runs too short to time?): " + "; ".join(bad))


if __name__ == "__main__":
    main()
