#!/usr/bin/env python3
"""ctest driver for the ParaView workflow (see paraview/CMakeLists.txt).

    python3 paraview/run_test.py TEST --workdir DIR [--sph SPH]
        [--xvfb-run PATH] [--pvpython PATH] [--state FILE.pvsm]
        [--paraview PATH] [--import-cmd PATH] [--open-run] [--no-layout]

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
  gui          open --state in the real ParaView GUI under Xvfb, in a folder
               holding a fresh runs/<case>/ of its case, and check the
               screenshots with gui_check.py (particles, legend, time);
               with --open-run the GUI runs open_run.py on such a run
               instead; with --no-layout the state's layout is removed
               first and the check must FAIL (no render view) although the
               state loaded
  walls        render a synthetic run with wall particles (the `kind`
               array): walls grey and the colour range the fluid's, with
               and without a state; the same run without `kind`: no grey
  catalyst-png sph run --catalyst catalyst_png.py under Xvfb: the in-situ
               PNGs, checked with check_png.py
  catalyst-ranks
               the PNG script on 2 MPI ranks: the pictures of one rank
  catalyst-same-particles
               the particle files of a run with Catalyst bit for bit those
               of the run without
  catalyst-refusals
               each bad --catalyst refused before the run (exit 2, one
               line naming catalyst and the file, no folder)
  catalyst-live
               catalyst_live.py: the run goes on with no GUI; a client
               connecting as the GUI does receives the particles live
  units        every array of sph's files carries its unit (check_units.py,
               2D and 3D) and every state's legend shows it

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
GUI_CHECK = os.path.join(HERE, "gui_check.py")
OPEN_RUN = os.path.join(HERE, "open_run.py")
SIZE = ["480", "480"]


class TestFailure(Exception):
    pass


def log(msg):
    print(msg)
    sys.stdout.flush()


def run(cmd, expect_ok=True, env=None, timeout=120):
    """Run cmd in a session of its own: past the timeout the whole group
    (xvfb-run, Xvfb, mpirun, sph) is killed, not xvfb-run alone."""
    import signal
    log("$ " + " ".join(cmd))
    t0 = time.time()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         universal_newlines=True, env=env,
                         start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        log(out.rstrip())
        raise TestFailure("timed out after %d s: %s" % (timeout, " ".join(cmd)))
    log(out.rstrip() + ("\n" if out.strip() else "") +
        "(exit %d, %.1f s)" % (p.returncode, time.time() - t0))
    if expect_ok and p.returncode != 0:
        raise TestFailure("command failed with exit status %d: %s"
                          % (p.returncode, " ".join(cmd)))
    return p.returncode, out


X_FAILURES = ("Xvfb failed to start", "bad X server connection",
              "cannot open display", "Can't open display",
              # Under mpirun a rank's own message can be lost with its
              # abort: only VTK's logger's line reaches us (seen on
              # 2026-12-06 under load, 1 run in 6 of catalyst_ranks). A
              # deterministic abort still fails every try.
              "Loguru caught a signal: SIGABRT",
              # sph's own line when the display is not there (yet)
              "cannot open the X display")


def xvfb(e, cmd, server=None, env=None, timeout=120, before_retry=None):
    """Run cmd under xvfb-run on a random display number (xvfb-run -a
    starts at :99 and races other xvfb-runs of the machine for it).  An X
    server that fails to start or refuses the client (VTK then aborts with
    "bad X server connection", seen twice in a row in one CI run) is
    retried up to five times in all, each on another display after a
    growing pause (a loaded machine starts Xvfb late), and Xvfb's own
    messages (xvfb-run -e) are printed; anything else counts."""
    import random
    cmd = list(cmd)
    errors = os.path.join(e.work, "xvfb-errors.log")
    tries = 5
    for attempt in range(1, tries + 1):
        os.makedirs(e.work, exist_ok=True)
        open(errors, "w").close()     # xvfb-run -e appends
        full = [e.a.xvfb_run, "-a", "-n", str(random.randint(200, 899)),
                "-e", errors]
        if server:
            full += ["-s", server]
        code, out = run(full + cmd, expect_ok=False, env=env,
                        timeout=timeout)
        if code == 0 or not any(m in out for m in X_FAILURES):
            break
        with open(errors, errors="replace") as f:
            log("Xvfb said:\n" + (f.read().strip() or "(nothing)"))
        if attempt < tries:
            log("note: the X server failed; retrying on another display")
            time.sleep(2 * attempt)
            if before_retry:
                before_retry(cmd)
    return code, out


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
        """Run render.py headless, the documented way (under xvfb(): an X
        server that fails is retried; anything else counts)."""
        code, out = xvfb(self, [self.a.pvpython, "--disable-xdisplay-test",
                                RENDER] + args)
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


def t_ranks(e):
    """A run on 2 MPI ranks (a .pvtp and a piece per rank per snapshot):
    the on-the-fly view and the water2d state render it; resumed on one
    rank (a series of .pvtp, then .vtp), the state renders its last time."""
    e.need_tools()
    mpirun = shutil.which("mpirun")
    if not mpirun:
        raise TestFailure("mpirun not found (scripts/setup.sh installs openmpi-bin)")
    run_dir = os.path.join(e.work, "dam_break")
    case_file = os.path.join(ROOT, "cases", "dam_break.case")
    run([mpirun, "--oversubscribe", "--allow-run-as-root", "-n", "2", e.a.sph,
         "run", case_file, "--output", run_dir, "--end_time", "0.01",
         "--threads", "1"])
    pvtp = [f for f in os.listdir(run_dir) if f.endswith(".pvtp")]
    if len(pvtp) < 2:
        raise TestFailure("expected a .pvtp per snapshot, got %s" % pvtp)
    png = os.path.join(e.work, "default.png")
    e.render([run_dir, "--size"] + SIZE + ["--output", png])
    e.check(png, "--size", *SIZE, "--min-span", "0.5")
    state = os.path.join(HERE, "water2d.pvsm")
    first = os.path.join(e.work, "first.png")
    e.render([run_dir, "--state", state, "--time", "0", "--size"] + SIZE +
             ["--output", first])
    e.check(first, "--size", *SIZE, "--centroid-box", "0", "0", "0.5", "0.5")
    # Resumed on one rank: the series mixes .pvtp and .vtp snapshots.
    run([e.a.sph, "run", "--resume", run_dir, "--end_time", "0.02"])
    if not [f for f in os.listdir(run_dir) if f.endswith(".vtp") and f.count("_") == 2]:
        raise TestFailure("expected a one-rank .vtp after the resume, got %s" % sorted(os.listdir(run_dir)))
    last = os.path.join(e.work, "resumed.png")
    e.render([run_dir, "--state", state, "--time", "0.02", "--size"] + SIZE +
             ["--output", last])
    e.check(last, "--size", *SIZE, "--centroid-box", "0", "0", "0.5", "0.5")


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


def strip_layouts(state, out):
    """Write the state without its layouts: what the states were before,
    when the GUI loaded them but showed no view."""
    tree = ET.parse(state)
    sm = tree.getroot().find("ServerManagerState")
    for el in list(sm):
        if (el.tag == "Proxy" and el.get("type") == "ViewLayout") or \
                (el.tag == "ProxyCollection" and el.get("name") == "layouts"):
            sm.remove(el)
    tree.write(out)


def gui_min_pixels(case):
    """Particle pixels the GUI must show: a water case fills hundreds of
    discs, the few-particle cases a few small ones."""
    return 1000 if case in ("dam_break", "droplet", "block_drop",
                            "dam_break_3d") else 30


def t_gui(e):
    e.need_tools()
    for name, path in (("paraview", e.a.paraview),
                       ("import (ImageMagick)", e.a.import_cmd)):
        if not path or not os.path.exists(path):
            raise TestFailure("%s not found: run scripts/setup.sh" % name)
    state = os.path.abspath(e.a.state)
    case = state_case(state)
    # A folder standing in for the repository root: the state refers to
    # runs/<case>/<case>.pvd relative to the GUI's working folder.
    root = os.path.join(e.work, "root")
    run_dir = os.path.join(root, "runs", case)
    e.sph_run(case, run_dir, "--end_time", "0.002")   # t = 0 is shown
    cmd = [sys.executable, GUI_CHECK, "--cwd", root,
           "--paraview", e.a.paraview, "--import-cmd", e.a.import_cmd,
           "--min-pixels", str(gui_min_pixels(case)), "--timeout", "100",
           "--output", os.path.join(e.work, "screen.png")]
    env = None
    if e.a.open_run:
        # any run folder, any name: SPH_RUN names it, SPH_STATE the state
        other = os.path.join(root, "my_run")
        os.rename(run_dir, other)
        env = dict(os.environ, SPH_RUN=other, SPH_STATE=state,
                   SPH_PARAVIEW_DIR=HERE)
        cmd += ["--script", OPEN_RUN]
    elif e.a.no_layout:
        bare = os.path.join(e.work, "no_layout.pvsm")
        strip_layouts(state, bare)
        cmd += [bare, "--settle", "10"]
    else:
        cmd += [state]
    code, out = xvfb(e, cmd, server="-screen 0 1600x1000x24", env=env,
                     timeout=140)
    if e.a.no_layout:
        if code == 0:
            raise TestFailure("gui_check.py passed a state without a layout")
        if "no render view" not in out or "sources listed" not in out:
            raise TestFailure("expected the state to load (sources listed) "
                              "and no render view")
    elif code != 0:
        raise TestFailure("the GUI did not show the particles")


def t_walls(e):
    e.need_tools(sph=False)
    import make_synthetic_run
    # 2D: on the fly and with a state; 3D on the fly.  The wall particles'
    # pressure is 20x the fluid's: coloured by it, the fluid would use a
    # sliver of the colour map (--min-span fails), and no grey would show.
    # 3D: cut open (the walls hide the fluid), on the fly and with the 3D
    # state.
    cases = [("walls2d", 2, 0.02, []),
             ("walls2d", 2, 0.02, ["--state", "water2d.pvsm"]),
             ("walls3d", 3, 0.05, ["--clip"]),
             ("walls3d", 3, 0.05, ["--state", "dam_break_3d.pvsm"])]
    for k, (name, dim, dx, extra) in enumerate(cases):
        run_dir = os.path.join(e.work, name)
        if not os.path.isdir(run_dir):
            make_synthetic_run.generate(run_dir, name, steps=2, dim=dim,
                                        dx=dx, walls=True)
        png = os.path.join(e.work, "%s_%d.png" % (name, k))
        if extra[:1] == ["--state"]:
            extra = ["--state", os.path.join(HERE, extra[1])]
        e.render([run_dir, "--size"] + SIZE + ["--output", png] + extra)
        e.check(png, "--size", *SIZE, "--min-span", "0.5",
                "--min-grey", "3000")
    # Without `kind` the walls are particles like any other: coloured, the
    # colour range theirs, no grey.
    bare = os.path.join(e.work, "nokind")
    make_synthetic_run.generate(bare, "nokind", steps=2, walls=True,
                                kind=False)
    png = os.path.join(e.work, "nokind.png")
    e.render([bare, "--size"] + SIZE + ["--output", png])
    e.check(png, "--size", *SIZE, "--max-grey", "2000")
    e.check(png, "--min-grey", "3000", expect_ok=False)


# ---------------------------------------------------------------------------
# Catalyst (sph run --catalyst, docs/paraview.md) and units.

CATALYST_PNG = os.path.join(HERE, "catalyst_png.py")
CATALYST_LIVE = os.path.join(HERE, "catalyst_live.py")


def case_path(case):
    return os.path.join(ROOT, "cases", case + ".case")


def add_overwrite(cmd):
    """A run aborted with its X server left its output folder behind
    (marked as running): the retry replaces it."""
    if "--output" in cmd and "--overwrite" not in cmd:
        cmd.append("--overwrite")


def xvfb_sph(e, args, env=None, timeout=200):
    """sph under xvfb()."""
    return xvfb(e, [e.a.sph] + args, env=env, timeout=timeout,
                before_retry=add_overwrite)


def catalyst_pngs(run_dir, name, count):
    """The in-situ PNG script's folder in run_dir and its pictures, which
    must be NAME_00000.png ... (count of them)."""
    folder = os.path.join(run_dir, "catalyst")
    pngs = sorted(os.listdir(folder)) if os.path.isdir(folder) else []
    want = ["%s_%05d.png" % (name, k) for k in range(count)]
    if pngs != want:
        raise TestFailure("expected %s in %s, found %s" % (want, folder, pngs))
    return folder, pngs


def t_catalyst_png(e):
    """The in-situ PNG script under Xvfb: a picture at the start, every 100
    steps and at the end (0.02 s = 400 steps: 5), each passing check_png.py
    as render.py's pictures do. The colour-span check is the first
    picture's: the column at rest in hydrostatic balance, its pressure
    linear in depth over the whole colour range (at the end, 0.02 s, the
    column's acoustic release leaves a few hot particles in the corner at
    the top of the range, over too few pixels: 0.45 of the map with the
    clamped diffusion of 2026-12-07, 0.75 before; 0.47 at 480x480). At the
    script's default 800x800."""
    e.need_tools()
    run_dir = os.path.join(e.work, "dam_break")
    size = ["800", "800"]
    env = dict(os.environ, SPH_CATALYST_SIZE=" ".join(size))
    code, _ = xvfb_sph(e, ["run", case_path("dam_break"), "--output", run_dir,
                           "--end_time", "0.02", "--no-progress",
                           "--catalyst", CATALYST_PNG,
                           "--catalyst_every", "100"], env=env)
    if code != 0:
        raise TestFailure("sph run --catalyst failed (exit %d)" % code)
    folder, pngs = catalyst_pngs(run_dir, "dam_break", 5)
    e.check(os.path.join(folder, pngs[0]), "--size", *size, "--time-text",
            "--min-grey", "1000", "--min-span", "0.5",
            "--centroid-box", "0", "0", "0.5", "0.5")
    for name in pngs[1:-1]:
        e.check(os.path.join(folder, name), "--size", *size, "--time-text",
                "--min-grey", "1000", "--centroid-box", "0", "0", "0.5", "0.5")
    # The last one still shows a colour map, not one colour (0.45 measured).
    e.check(os.path.join(folder, pngs[-1]), "--size", *size, "--time-text",
            "--min-grey", "1000", "--min-span", "0.3",
            "--centroid-box", "0", "0", "0.5", "0.5")


def t_catalyst_ranks(e):
    """The in-situ PNG script on 2 MPI ranks (each hands Catalyst its own
    particles; ParaView composites the ranks' pictures): the same pictures
    as on one rank, checked as t_catalyst_png checks them, and pixel for
    pixel within the seam a rank boundary leaves (IceT keeps each rank's
    picture within the bounds of its points, so the discs at a piece's edge
    are cut: a line one pixel wide; at most 1% of the pixels differ,
    measured 0.2%; with each rank's own colour range, before the range was
    reduced over the ranks, 1.9% differed)."""
    e.need_tools()
    import shutil as sh
    mpirun = sh.which("mpirun")
    if not mpirun:
        raise TestFailure("mpirun not found: scripts/setup.sh installs openmpi-bin")
    size = ["800", "800"]
    env = dict(os.environ, SPH_CATALYST_SIZE=" ".join(size))
    common = ["--end_time", "0.01", "--no-progress", "--catalyst", CATALYST_PNG, "--catalyst_every", "100"]
    one = os.path.join(e.work, "one")
    code, _ = xvfb_sph(e, ["run", case_path("dam_break"), "--output", one] + common, env=env, timeout=60)
    if code != 0:
        raise TestFailure("sph run --catalyst on one rank failed (exit %d)" % code)
    two = os.path.join(e.work, "two")
    launcher = [mpirun, "--oversubscribe", "-n", "2"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        launcher.insert(1, "--allow-run-as-root")
    code, _ = xvfb(e, launcher + [e.a.sph, "run", case_path("dam_break"), "--output", two] + common,
                   env=env, timeout=60, before_retry=add_overwrite)
    if code != 0:
        raise TestFailure("sph run --catalyst on 2 ranks failed (exit %d)" % code)
    folder, pngs = catalyst_pngs(two, "dam_break", 3)
    # The plugin missing on one rank only (mpirun's MPMD form: rank 1 gets
    # another SPH_CATALYST_PLUGIN): every rank stops before the run, within
    # the timeout, exit 2, one error line, no folder. (It hung in the
    # collective calls of Catalyst's start before the ranks agreed first.)
    lonely = os.path.join(e.work, "lonely")
    args = [e.a.sph, "run", case_path("dam_break"), "--output", lonely] + common
    code, out = run(launcher[:-1] + ["1"] + args + [":", "-n", "1", "-x", "SPH_CATALYST_PLUGIN=/nonexistent.so"] + args,
                    expect_ok=False, env=env, timeout=60)
    errors = [l for l in out.splitlines() if l.startswith("sph: error:")]
    if code != 2 or len(errors) != 1 or "catalyst" not in errors[0] or os.path.exists(lonely):
        raise TestFailure("a plugin missing on one rank: expected exit 2, one error line naming catalyst "
                          "and no folder; got exit %d, %d error line(s)" % (code, len(errors)))
    import check_png
    for name in pngs:
        e.check(os.path.join(folder, name), "--size", *size, "--time-text",
                "--min-grey", "1000", "--centroid-box", "0", "0", "0.5", "0.5")
        a = check_png.read_png(os.path.join(one, "catalyst", name))
        b = check_png.read_png(os.path.join(folder, name))
        share = float((abs(a - b).sum(axis=2) > 30).mean())
        log("%s: %.4f of the pixels differ from the one-rank picture" % (name, share))
        if share > 0.01:
            raise TestFailure("%s on 2 ranks differs from one rank's in %.1f%% of its pixels"
                              % (name, 100 * share))


def vtp_arrays(path):
    """Points and every point array of a .vtp, as raw bytes by name."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    arrays = {"(points)": vtk_to_numpy(out.GetPoints().GetData()).tobytes()}
    pd = out.GetPointData()
    for k in range(pd.GetNumberOfArrays()):
        arr = pd.GetArray(k)
        arrays[arr.GetName()] = vtk_to_numpy(arr).tobytes()
    return arrays


def t_catalyst_same_particles(e):
    """A run with Catalyst (the PNG script, rendering in the process, every
    7 steps, out of step with the output) writes bit for bit the particle
    files of the same run without it: every point array and the points."""
    e.need_tools()
    plain = os.path.join(e.work, "plain")
    insitu = os.path.join(e.work, "insitu")
    args = ["--end_time", "0.01", "--output_every", "50", "--no-progress"]
    run([e.a.sph, "run", case_path("dam_break"), "--output", plain] + args)
    code, _ = xvfb_sph(e, ["run", case_path("dam_break"), "--output", insitu]
                       + args + ["--catalyst", CATALYST_PNG,
                                 "--catalyst_every", "7"])
    if code != 0:
        raise TestFailure("sph run --catalyst failed (exit %d)" % code)
    files = sorted(f for f in os.listdir(plain) if f.endswith(".vtp"))
    if len(files) < 3 or files != sorted(
            f for f in os.listdir(insitu) if f.endswith(".vtp")):
        raise TestFailure("the two runs wrote different particle files: %s"
                          % files)
    pngs = os.listdir(os.path.join(insitu, "catalyst"))
    if len(pngs) < 20:
        raise TestFailure("Catalyst made %d pictures, expected 30" % len(pngs))
    for f in files:
        a, b = vtp_arrays(os.path.join(plain, f)), vtp_arrays(
            os.path.join(insitu, f))
        if sorted(a) != sorted(b):
            raise TestFailure("%s: arrays %s and %s" % (f, sorted(a), sorted(b)))
        for name in a:
            if a[name] != b[name]:
                raise TestFailure("%s: array %s differs with Catalyst"
                                  % (f, name))
        log("%s: %d arrays bit for bit the same" % (f, len(a)))


def t_catalyst_refusals(e):
    """Each bad --catalyst is refused before the run: exit 2, one line on
    the output naming the key `catalyst` and the file, no output folder. A
    script that raises during the run is reported once (one warning with
    the step) and the run ends normally. And plain runs pay nothing: sph itself links neither Python nor
    ParaView's Catalyst (the plugin is loaded only for --catalyst)."""
    e.need_tools()
    code, out = run(["ldd", e.a.sph], expect_ok=False)
    linked = [l.split()[0] for l in out.splitlines()
              if "python" in l.lower() or "Catalyst" in l]
    if code != 0 or linked:
        raise TestFailure("sph links %s: plain runs would start them"
                          % (linked or "(ldd failed)"))
    w = e.work
    syntax = os.path.join(w, "syntax_error.py")
    with open(syntax, "w") as fh:
        fh.write("def RequestDataDescription(d):\n    pass\n"
                 "def DoCoProcessing(d)\n    pass\n")
    nofuncs = os.path.join(w, "no_functions.py")
    with open(nofuncs, "w") as fh:
        fh.write("from paraview.simple import *\nSphere()\n")
    case = os.path.join(w, "with_catalyst.case")
    with open(case_path("dam_break")) as fh, open(case, "w") as out:
        out.write(fh.read() + '\ncatalyst = "%s"\n' % CATALYST_LIVE)
    no_display = dict(os.environ)
    no_display.pop("DISPLAY", None)
    bad_plugin = dict(os.environ, SPH_CATALYST_PLUGIN=os.path.join(
        w, "libsph_catalyst_missing.so"))
    refusals = [
        ("missing script", ["--catalyst", os.path.join(w, "missing.py")],
         None, "missing.py"),
        ("not a file", ["--catalyst", w], None, w),
        ("syntax error", ["--catalyst", syntax], None, "syntax_error.py"),
        ("no Catalyst functions", ["--catalyst", nofuncs], None,
         "no_functions.py"),
        ("plugin not loadable", ["--catalyst", CATALYST_LIVE], bad_plugin,
         "libsph_catalyst_missing.so"),
        ("PNG script without DISPLAY", ["--catalyst", CATALYST_PNG],
         no_display, "catalyst_png.py"),
        ("catalyst_every 0", ["--catalyst", CATALYST_LIVE,
                              "--catalyst_every", "0"], None,
         "catalyst_every"),
    ]
    for k, (what, flags, env, file_word) in enumerate(refusals):
        out_dir = os.path.join(w, "run%d" % k)
        log("-- %s" % what)
        code, out = run([e.a.sph, "run", case_path("dam_break"), "--output",
                         out_dir, "--end_time", "0.001"] + flags,
                        expect_ok=False, env=env)
        expect_refusal(code, out, out_dir, ["catalyst", file_word])
    log("-- a script that raises during the run")
    raising = os.path.join(w, "raises_at_third_call.py")
    with open(raising, "w") as fh:
        fh.write("calls = [0]\n"
                 "def RequestDataDescription(d):\n"
                 "    d.GetInputDescriptionByName('input').AllFieldsOn()\n"
                 "def DoCoProcessing(d):\n"
                 "    calls[0] += 1\n"
                 "    if calls[0] == 3:\n"
                 "        raise ValueError('third call')\n")
    out_dir = os.path.join(w, "run_raising")
    code, out = run([e.a.sph, "run", case_path("dam_break"), "--output",
                     out_dir, "--end_time", "0.005", "--no-progress",
                     "--catalyst", raising, "--catalyst_every", "20"],
                    expect_ok=False, env=no_display)
    warnings = [l for l in out.splitlines() if l.startswith("sph: warning:")]
    if code != 0 or not os.path.isfile(os.path.join(out_dir, "dam_break.pvd")):
        raise TestFailure("a script failing during the run stopped it "
                          "(exit %d)" % code)
    if len(warnings) != 1 or not all(
            word in warnings[0] for word in ("catalyst", "raises_at_third_call.py",
                                             "step 40", "third call")):
        raise TestFailure("expected one warning naming catalyst, the script, "
                          "step 40 and the error, got %s" % warnings)
    log("-- catalyst in a case file")
    out_dir = os.path.join(w, "run_case_key")
    code, out = run([e.a.sph, "run", case, "--output", out_dir],
                    expect_ok=False)
    expect_refusal(code, out, out_dir, ["catalyst", "with_catalyst.case",
                                        "--catalyst"])


def expect_refusal(code, out, out_dir, words):
    lines = [l for l in out.splitlines() if l.strip()]
    if code != 2:
        raise TestFailure("expected exit status 2, got %d" % code)
    if len(lines) != 1 or not lines[0].startswith("sph: error: "):
        raise TestFailure("expected one 'sph: error:' line, got %d lines"
                          % len(lines))
    for w in words:
        if w not in lines[0]:
            raise TestFailure("the message does not name %r" % w)
    if os.path.exists(out_dir):
        raise TestFailure("the refused run made its folder %s" % out_dir)


def free_port():
    import socket
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def t_catalyst_live(e):
    """catalyst_live.py: (1) with no ParaView listening (no DISPLAY either)
    the run goes on and ends normally; (2) a client that connects as the
    GUI's Catalyst > Connect does (paraview.live) receives the particles
    live: the run's number of points, with its arrays."""
    e.need_tools()
    no_display = dict(os.environ, SPH_CATALYST_PORT=str(free_port()))
    no_display.pop("DISPLAY", None)
    alone = os.path.join(e.work, "alone")
    code, _ = run([e.a.sph, "run", case_path("dam_break"), "--output", alone,
                   "--end_time", "0.005", "--no-progress",
                   "--catalyst", CATALYST_LIVE, "--catalyst_every", "20"],
                  expect_ok=False, env=no_display)
    if code != 0 or not os.path.isfile(os.path.join(alone, "dam_break.pvd")):
        raise TestFailure("with no GUI listening the run did not finish "
                          "(exit %d)" % code)
    live_dir = os.path.join(e.work, "live")
    cmd = [e.a.pvpython, "--disable-xdisplay-test",
           os.path.join(HERE, "catalyst_live_check.py"), str(free_port()),
           "--", e.a.sph, "run", case_path("dam_break"), "--output", live_dir,
           "--end_time", "0.05", "--output_every", "2000", "--no-progress",
           "--catalyst", CATALYST_LIVE, "--catalyst_every", "20"]
    code, out = xvfb(e, cmd, timeout=170, before_retry=add_overwrite)
    summary = [l for l in out.splitlines() if l.startswith("live summary:")]
    if code != 0 or not summary:
        raise TestFailure("the live client got nothing (exit %d)" % code)
    first = sorted(f for f in os.listdir(live_dir) if f.endswith(".vtp"))[0]
    arrays = vtp_arrays(os.path.join(live_dir, first))
    n = len(arrays["(points)"]) // 24
    want = "live summary: max points %d, arrays %s," % (
        n, ", ".join(sorted(k for k in arrays if k != "(points)")))
    if not summary[0].startswith(want):
        raise TestFailure("expected %r, got %r" % (want, summary[0]))


def t_units(e):
    """Every point array of sph's files carries its unit, per dimension,
    as pvpython reads them (check_units.py: a 2D run with walls and
    continuity density, a 3D one with XSPH, a 2D one with surface
    tension), and every state's legend title shows the unit of its case's
    dimension."""
    e.need_tools()
    files = []
    for case in ("dam_break", "dam_break_3d", "droplet_surface_tension"):
        out = os.path.join(e.work, case)
        run([e.a.sph, "run", case_path(case), "--output", out,
             "--end_time", "0.0004", "--no-progress"])
        files += [os.path.join(out, f) for f in sorted(os.listdir(out))
                  if f.endswith(".vtp")][-1:]
    code, _ = xvfb(e, [e.a.pvpython, "--disable-xdisplay-test",
                       os.path.join(HERE, "check_units.py")] + files)
    if code != 0:
        raise TestFailure("check_units.py found arrays without their unit")
    import glob
    for state in sorted(glob.glob(os.path.join(HERE, "*.pvsm"))):
        title = legend_titles(state)
        case = state_case(state)
        from make_states import case_dimension
        dim = case_dimension(case)
        want = {"pressure": {2: "pressure [N/m]", 3: "pressure [Pa]"}[dim],
                "velocity": "speed [m/s]"}
        if not title or not any(t in want.values() for t in title):
            raise TestFailure("%s (%s, %dD): legend %s, expected one of %s"
                              % (os.path.basename(state), case, dim, title,
                                 sorted(want.values())))
        log("%s: legend %s" % (os.path.basename(state), title))


def legend_titles(state):
    """The Title values of the scalar bars of a .pvsm."""
    titles = []
    for proxy in ET.parse(state).getroot().iter("Proxy"):
        if proxy.get("type") != "ScalarBarWidgetRepresentation":
            continue
        for prop in proxy.iter("Property"):
            if prop.get("name") == "Title":
                titles += [el.get("value") for el in prop.iter("Element")]
    return titles


TESTS = {"snapshot": t_snapshot, "state": t_state,
         "default-view": t_default_view, "synthetic-3d": t_synthetic_3d,
         "errors": t_errors, "checker": t_checker, "gui": t_gui,
         "walls": t_walls, "catalyst-png": t_catalyst_png,
         "catalyst-ranks": t_catalyst_ranks,
         "catalyst-same-particles": t_catalyst_same_particles,
         "catalyst-refusals": t_catalyst_refusals,
         "catalyst-live": t_catalyst_live, "units": t_units,
         "ranks": t_ranks}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("test", choices=sorted(TESTS))
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--sph")
    ap.add_argument("--xvfb-run", default=shutil.which("xvfb-run"))
    ap.add_argument("--pvpython", default=shutil.which("pvpython"))
    ap.add_argument("--state")
    ap.add_argument("--paraview", default=shutil.which("paraview"))
    ap.add_argument("--import-cmd", default=shutil.which("import"))
    ap.add_argument("--open-run", action="store_true")
    ap.add_argument("--no-layout", action="store_true")
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
