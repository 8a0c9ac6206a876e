#!/usr/bin/env python3
"""ctest driver for the ParaView workflow (see paraview/CMakeLists.txt).

    python3 paraview/run_test.py TEST --workdir DIR [--sph SPH]
        [--xvfb-run PATH] [--pvpython PATH] [--state FILE.pvsm]

TEST is one of:
  snapshot     run dam_break for 0.01 s, render its first and last output
               with water2d.pvsm and check both PNGs (size, not blank,
               centroid of the t = 0 particles in the lower-left quarter,
               colours spanning the colour map at the last step)
  state        run the case of --state (its sph.case annotation) and render
               its last step with that state
  default-view render without a state: every step (--all), another field,
               a time, --mp4 (or its clear error without ffmpeg)
  synthetic-3d render a synthetic 3D series: the 3D default camera
  errors       the clear errors of render.py (missing folder, no .pvd,
               missing array, bad state, no ParaView) and its re-run under
               xvfb-run when started by a plain python3 without a display
  checker      check_png.py rejects a blank image and a one-colour render

Exit status 0 when the test passes.
"""
import argparse
import os
import shutil
import subprocess
import sys
sys.dont_write_bytecode = True   # keep the source tree clean
import time
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
RENDER = os.path.join(HERE, "render.py")
SIZE = ["480", "480"]


class TestFailure(Exception):
    pass


def log(msg):
    print(msg)
    sys.stdout.flush()


def run(cmd, expect_ok=True, env=None, timeout=120):
    log("$ " + " ".join(cmd))
    t0 = time.time()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, env=env, timeout=timeout)
    out = r.stdout
    log(out.rstrip() + ("\n" if out.strip() else "") +
        "(exit %d, %.1f s)" % (r.returncode, time.time() - t0))
    if expect_ok and r.returncode != 0:
        raise TestFailure("command failed with exit status %d: %s"
                          % (r.returncode, " ".join(cmd)))
    return r.returncode, out


class Env:
    def __init__(self, a):
        self.a = a
        self.work = os.path.abspath(a.workdir)

    def need_tools(self, sph=True):
        missing = []
        for name, path in (("xvfb-run", self.a.xvfb_run),
                           ("pvpython", self.a.pvpython)):
            if not path or path.endswith("NOTFOUND") or not os.path.exists(path):
                missing.append(name)
        if missing:
            raise TestFailure(
                "%s not found: install them (scripts/setup.sh installs "
                "paraview python3-paraview xvfb xauth) and reconfigure"
                % " and ".join(missing))
        if sph and (not self.a.sph or not os.path.exists(self.a.sph)):
            raise TestFailure("sph executable not found: %s" % self.a.sph)

    def render(self, args, expect_ok=True):
        """Run render.py headless, the documented way.  An Xvfb that fails
        to start (a display-number race with another xvfb-run) is retried
        once; anything else counts."""
        cmd = [self.a.xvfb_run, "-a", self.a.pvpython,
               "--disable-xdisplay-test", RENDER] + args
        for attempt in (1, 2):
            code, out = run(cmd, expect_ok=False)
            if "Xvfb failed to start" in out and attempt == 1:
                log("note: Xvfb failed to start; retrying once")
                time.sleep(1)
                continue
            break
        if expect_ok and code != 0:
            raise TestFailure("render.py failed (exit %d)" % code)
        return code, out

    def sph_run(self, case, out, *extra):
        case_file = os.path.join(ROOT, "cases", case + ".case")
        if not os.path.isfile(case_file):
            raise TestFailure("no case file %s" % case_file)
        run([self.a.sph, "run", case_file, "--output", out] + list(extra))
        pvds = [f for f in os.listdir(out) if f.endswith(".pvd")]
        if len(pvds) != 1:
            raise TestFailure("sph wrote %d .pvd files to %s" % (len(pvds), out))
        return os.path.join(out, pvds[0])

    def check(self, png, *args, expect_ok=True):
        import check_png
        log("$ check_png.py %s %s" % (png, " ".join(args)))
        code = check_png.main([png] + list(args))
        if expect_ok and code != 0:
            raise TestFailure("check_png.py rejected %s" % png)
        if not expect_ok and code == 0:
            raise TestFailure("check_png.py accepted %s but should not" % png)


def t_snapshot(e):
    e.need_tools()
    state = e.a.state or os.path.join(HERE, "water2d.pvsm")
    run_dir = os.path.join(e.work, "dam_break")
    e.sph_run("dam_break", run_dir, "--end_time", "0.01")
    first = os.path.join(e.work, "first.png")
    last = os.path.join(e.work, "last.png")
    e.render([run_dir, "--state", state, "--time", "0", "--size"] + SIZE +
             ["--output", first])
    e.check(first, "--size", *SIZE, "--centroid-box", "0", "0", "0.5", "0.5")
    e.render([run_dir, "--state", state, "--size"] + SIZE +
             ["--output", last])
    e.check(last, "--size", *SIZE, "--min-span", "0.5",
            "--centroid-box", "0", "0", "0.5", "0.5")


def state_case(state):
    root = ET.parse(state).getroot()
    for ann in root.iter("Annotation"):
        if ann.get("key") == "sph.case":
            return ann.get("value")
    return os.path.splitext(os.path.basename(state))[0]


def t_state(e):
    e.need_tools()
    state = os.path.abspath(e.a.state)
    case = state_case(state)
    log("state %s is for case %s" % (os.path.basename(state), case))
    run_dir = os.path.join(e.work, case)
    e.sph_run(case, run_dir, "--end_time", "0.01")
    png = os.path.join(e.work, os.path.basename(state)[:-5] + ".png")
    e.render([run_dir, "--state", state, "--size"] + SIZE +
             ["--output", png])
    e.check(png, "--size", *SIZE, "--min-pixels", "10")


def t_default_view(e):
    e.need_tools()
    run_dir = os.path.join(e.work, "dam_break")
    pvd = e.sph_run("dam_break", run_dir, "--end_time", "0.01",
                    "--output_every", "25")
    n = len(ET.parse(pvd).getroot().findall(".//DataSet"))
    if n < 3:
        raise TestFailure("expected several outputs, got %d" % n)
    frames = os.path.join(e.work, "frames")
    e.render([run_dir, "--all", "--size", "320", "240", "--output", frames])
    pngs = sorted(f for f in os.listdir(frames) if f.endswith(".png"))
    log("frames: %s" % ", ".join(pngs))
    if len(pngs) != n:
        raise TestFailure("%d frames for %d outputs" % (len(pngs), n))
    for f in (pngs[0], pngs[-1]):
        e.check(os.path.join(frames, f), "--size", "320", "240")
    e.check(os.path.join(frames, pngs[0]), "--centroid-box", "0", "0",
            "0.5", "0.5")
    vel = os.path.join(e.work, "velocity.png")
    e.render([pvd, "--field", "velocity", "--time", "0.005", "--size"] +
             SIZE + ["--output", vel])
    e.check(vel, "--size", *SIZE)
    mp4 = os.path.join(e.work, "movie.mp4")
    # ffmpeg is optional: with it an mp4 must appear, without it a clear
    # error before anything is rendered.
    code, out = e.render([run_dir, "--mp4", mp4, "--size", "320", "240",
                          "--output", os.path.join(e.work, "mp4frames")],
                         expect_ok=False)
    if shutil.which("ffmpeg"):
        if code != 0 or not os.path.getsize(mp4):
            raise TestFailure("--mp4 with ffmpeg installed wrote no mp4")
    elif code == 0 or "needs ffmpeg" not in out:
        raise TestFailure("--mp4 without ffmpeg: expected a clear error")


def t_synthetic_3d(e):
    e.need_tools(sph=False)
    sys.path.insert(0, HERE)
    import make_synthetic_run
    run_dir = os.path.join(e.work, "cube")
    make_synthetic_run.generate(run_dir, "cube", steps=2, dim=3, dx=0.05)
    png = os.path.join(e.work, "cube.png")
    e.render([run_dir, "--size"] + SIZE + ["--output", png])
    e.check(png, "--size", *SIZE, "--min-span", "0.5")


def expect_error(e, cmd, words, env=None):
    code, out = run(cmd, expect_ok=False, env=env)
    if code == 0:
        raise TestFailure("expected a non-zero exit: %s" % " ".join(cmd))
    for w in words:
        if w not in out:
            raise TestFailure("expected %r in the error message" % w)


def t_errors(e):
    e.need_tools(sph=False)
    import make_synthetic_run
    py = sys.executable
    good = os.path.join(e.work, "good")
    make_synthetic_run.generate(good, "good", steps=2)
    empty = os.path.join(e.work, "empty")
    os.makedirs(empty)
    bad_state = os.path.join(e.work, "bad.pvsm")
    with open(bad_state, "w") as fh:
        fh.write("<ParaView><ServerManagerState/></ParaView>\n")
    # These are found before ParaView is started.
    expect_error(e, [py, RENDER, os.path.join(e.work, "nowhere")],
                 ["no such run folder"])
    expect_error(e, [py, RENDER, empty], ["no .pvd file in"])
    expect_error(e, [py, RENDER, good, "--field", "vorticity"],
                 ["no point array 'vorticity'", "density", "pressure",
                  "velocity"])
    expect_error(e, [py, RENDER, good, "--state",
                     os.path.join(e.work, "none.pvsm")], ["no such state"])
    # No ParaView: a python without Debian's modules and no xvfb-run or
    # pvpython on PATH to fall back on.
    env = dict(os.environ, PATH=empty, DISPLAY=":99")
    expect_error(e, [py, "-S", RENDER, good],
                 ["ParaView", "xvfb-run -a pvpython --disable-xdisplay-test"],
                 env=env)
    env = dict(os.environ, PATH=empty)
    env.pop("DISPLAY", None)
    expect_error(e, [py, "-S", RENDER, good],
                 ["no X display", "xvfb-run -a pvpython"], env=env)
    # A state without a PVD reader, found once ParaView runs.
    code, out = e.render([good, "--state", bad_state], expect_ok=False)
    if code == 0 or "no PVD reader" not in out:
        raise TestFailure("bad state: expected a clear error")
    # A plain python3 without a display re-runs itself under xvfb-run.
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env["PATH"] = os.pathsep.join([os.path.dirname(e.a.xvfb_run),
                                   os.path.dirname(e.a.pvpython),
                                   env.get("PATH", "")])
    png = os.path.join(e.work, "reexec.png")
    code, out = run([py, RENDER, good, "--size", "200", "200", "--output",
                     png], expect_ok=False, env=env)
    if code != 0 or not os.path.isfile(png):
        raise TestFailure("plain python3 without a display: no image")
    e.check(png, "--size", "200", "200")


def t_checker(e):
    e.need_tools(sph=False)
    import make_synthetic_run
    from vtkmodules.vtkImagingSources import vtkImageCanvasSource2D
    from vtkmodules.vtkIOImage import vtkPNGWriter
    blank = os.path.join(e.work, "blank.png")
    c = vtkImageCanvasSource2D()
    c.SetScalarTypeToUnsignedChar()
    c.SetNumberOfScalarComponents(3)
    c.SetExtent(0, 99, 0, 99, 0, 0)
    c.SetDrawColor(255, 255, 255)
    c.FillBox(0, 99, 0, 99)
    w = vtkPNGWriter()
    w.SetFileName(blank)
    w.SetInputConnection(c.GetOutputPort())
    w.Write()
    e.check(blank, expect_ok=False)
    e.check(blank, "--size", "100", "120", "--min-pixels", "0",
            expect_ok=False)
    good = os.path.join(e.work, "good")
    make_synthetic_run.generate(good, "good", steps=2)
    flat = os.path.join(e.work, "flat.png")
    e.render([good, "--range", "1e6", "2e6", "--time", "0", "--size"] +
             SIZE + ["--output", flat])
    e.check(flat, "--size", *SIZE)                       # not blank ...
    e.check(flat, "--min-span", "0.5", expect_ok=False)  # ... but one colour
    e.check(flat, "--centroid-box", "0.5", "0", "1", "1", expect_ok=False)


TESTS = {"snapshot": t_snapshot, "state": t_state,
         "default-view": t_default_view, "synthetic-3d": t_synthetic_3d,
         "errors": t_errors, "checker": t_checker}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("test", choices=sorted(TESTS))
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--sph")
    ap.add_argument("--xvfb-run", default=shutil.which("xvfb-run"))
    ap.add_argument("--pvpython", default=shutil.which("pvpython"))
    ap.add_argument("--state")
    a = ap.parse_args()
    sys.path.insert(0, HERE)
    e = Env(a)
    shutil.rmtree(e.work, ignore_errors=True)
    os.makedirs(e.work)
    t0 = time.time()
    try:
        TESTS[a.test](e)
    except (TestFailure, subprocess.TimeoutExpired) as err:
        log("FAILED %s: %s (%.1f s)" % (a.test, err, time.time() - t0))
        return 1
    log("PASSED %s (%.1f s)" % (a.test, time.time() - t0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
