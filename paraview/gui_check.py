#!/usr/bin/env python3
"""Open a state (or a script) in the real ParaView GUI and check, from X
screenshots, that it shows the particles: coloured, with a colour legend and
the time.

    /usr/bin/python3 paraview/gui_check.py STATE.pvsm [--cwd DIR] [options]
    SPH_RUN=runs/x /usr/bin/python3 paraview/gui_check.py --script paraview/open_run.py

Without an X display it re-runs itself under
`xvfb-run -a -s "-screen 0 1600x1000x24"`.  It starts `paraview
--state=STATE` (or `--script=SCRIPT`) in DIR (default: the current folder;
the states refer to runs/<case>/<case>.pvd relative to it), with a private,
fresh ParaView settings folder in which the welcome dialog is off (it is
modal and would stop the state loading).  Then, once a second until
--timeout, it takes a screenshot (`import -window root`, ImageMagick) and
looks for the render view: the largest pure-white region of the screen (the
view's background; the GUI's own panels are grey, an empty layout is
251-grey).  The view is cut out and checked with check_png.py: particle
pixels in the plot area, the legend (a colour bar whose colours the
particles match) and the time annotation.  The first screenshot that passes
ends the check; the last one is saved (--output) either way.

A state without a layout, or any other blank GUI, fails: "no render view".
The report says whether the pipeline browser lists the state's sources (its
green source icons), which tells a state that loaded without a view from a
GUI that did not get that far.

Exit status 0 when a screenshot passed, 1 otherwise.
"""
import argparse
import os
import shutil
import subprocess
import sys
sys.dont_write_bytecode = True   # keep the source tree clean
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
SCREEN = "1600x1000x24"
REEXEC_ENV = "SPH_GUI_CHECK_REEXEC"
MIN_VIEW_AREA = 100000    # pixels: the view is ~840x520 in a 1600x1000 screen
LOADED_ICONS = 150        # pipeline browser: a few source icons (idle GUI: 0)
BLOCK = 4                 # view search on 4x4 pixel blocks


def log(msg):
    print("gui_check.py: " + msg)
    sys.stdout.flush()


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("state", nargs="?", help="state file to open")
    ap.add_argument("--script", help="a --script for the GUI instead of a "
                    "state (e.g. paraview/open_run.py with SPH_RUN set)")
    ap.add_argument("--cwd", default=".", help="folder to start the GUI in")
    ap.add_argument("--timeout", type=float, default=60.0,
                    help="seconds to wait for a passing screenshot")
    ap.add_argument("--min-pixels", type=int, default=50,
                    help="particle pixels needed in the view")
    ap.add_argument("--min-span", type=float, default=0.0,
                    help="fraction of the colour map the particles span")
    ap.add_argument("--settle", type=float, default=None,
                    help="give up this many seconds after the pipeline "
                         "browser first lists sources (a state that loaded "
                         "but shows nothing need not wait for --timeout)")
    ap.add_argument("--output", help="save the last screenshot here "
                    "(and the render view cut out of it as NAME_view.png)")
    ap.add_argument("--paraview", default=shutil.which("paraview"))
    ap.add_argument("--import-cmd", default=shutil.which("import"),
                    help="ImageMagick's import (screenshots)")
    a = ap.parse_args(argv)
    if bool(a.state) == bool(a.script):
        ap.error("give a state file or --script, not both")
    return a


def ensure_display(argv):
    if os.environ.get("DISPLAY"):
        return
    xvfb = shutil.which("xvfb-run")
    if not xvfb or os.environ.get(REEXEC_ENV):
        sys.exit("gui_check.py: no X display and no xvfb-run")
    env = dict(os.environ, **{REEXEC_ENV: "1"})
    cmd = [xvfb, "-a", "-s", "-screen 0 " + SCREEN, sys.executable,
           os.path.abspath(__file__)] + argv
    os.execvpe(xvfb, cmd, env)


def paraview_version():
    try:
        from paraview import __version__
        return __version__
    except ImportError:
        out = subprocess.run(["pvpython", "--version"], stdout=subprocess.PIPE,
                             universal_newlines=True).stdout
        return out.split()[-1] if out.strip() else "5.11.0"


def settings_dir(tmp):
    """XDG_CONFIG_HOME with ParaView's Qt settings: no welcome dialog (it is
    modal and blocks the state loading until someone closes it)."""
    d = os.path.join(tmp, "config", "ParaView")
    os.makedirs(d)
    with open(os.path.join(d, "ParaView%s.ini" % paraview_version()),
              "w") as fh:
        fh.write("[General]\nGeneralSettings.ShowWelcomeDialog=false\n")
    return os.path.dirname(d)


def find_view(img):
    """(x0, y0, x1, y1) of the largest 4-connected pure-white region, in
    pixels, or None when it is smaller than MIN_VIEW_AREA."""
    import numpy as np
    H, W = img.shape[:2]
    h, w = H // BLOCK, W // BLOCK
    white = (img[:h * BLOCK, :w * BLOCK] == 255).all(axis=2)
    cells = white.reshape(h, BLOCK, w, BLOCK).all(axis=(1, 3))
    seen = np.zeros_like(cells)
    best, best_box = 0, None
    for sy, sx in zip(*np.nonzero(cells)):
        if seen[sy, sx]:
            continue
        seen[sy, sx] = True
        stack, n = [(sy, sx)], 0
        y0, y1, x0, x1 = sy, sy, sx, sx
        while stack:
            y, x = stack.pop()
            n += 1
            y0, y1, x0, x1 = min(y0, y), max(y1, y), min(x0, x), max(x1, x)
            for ny, nx in ((y + 1, x), (y - 1, x), (y, x + 1), (y, x - 1)):
                if 0 <= ny < h and 0 <= nx < w and cells[ny, nx] and \
                        not seen[ny, nx]:
                    seen[ny, nx] = True
                    stack.append((ny, nx))
        if n > best:
            best, best_box = n, (x0, y0, x1 + 1, y1 + 1)
    if best * BLOCK * BLOCK < MIN_VIEW_AREA:
        return None
    return tuple(BLOCK * v for v in best_box)


def pipeline_icons(img):
    """Saturated pixels in the upper left of the screen, where the pipeline
    browser shows a green icon per source (diagnostic only)."""
    H, W = img.shape[:2]
    reg = img[int(0.1 * H):int(0.4 * H), :int(0.2 * W)]
    return int(((reg.max(axis=2) - reg.min(axis=2)) >= 60).sum())


def write_png(img, path):
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.util.numpy_support import numpy_to_vtk
    import numpy as np
    H, W = img.shape[:2]
    data = vtkImageData()
    data.SetDimensions(W, H, 1)
    flat = np.ascontiguousarray(img[::-1].reshape(-1, 3).astype(np.uint8))
    arr = numpy_to_vtk(flat, deep=1)
    data.GetPointData().SetScalars(arr)
    w = vtkPNGWriter()
    w.SetFileName(path)
    w.SetInputData(data)
    w.Write()


def check_shot(shot, crop_path, a):
    """(passed, loaded, messages) for one screenshot; loaded: the pipeline
    browser lists sources."""
    import check_png
    img = check_png.read_png(shot)
    icons = pipeline_icons(img)
    loaded = icons >= LOADED_ICONS
    box = find_view(img)
    if box is None:
        return False, loaded, [
            "no render view (no white region of %d pixels); pipeline "
            "browser icons: %d pixels (%s)" % (
                MIN_VIEW_AREA, icons,
                "sources listed" if loaded else "no sources listed")]
    x0, y0, x1, y1 = box
    write_png(img[y0:y1, x0:x1], crop_path)
    msgs = ["render view at x %d..%d, y %d..%d (%dx%d); pipeline browser "
            "icons: %d pixels" % (x0, x1, y0, y1, x1 - x0, y1 - y0, icons)]
    args = [crop_path, "--min-pixels", str(a.min_pixels), "--min-span",
            str(a.min_span), "--time-text"]
    from io import StringIO
    out, old = StringIO(), sys.stdout
    sys.stdout = out
    try:
        code = check_png.main(args)
    finally:
        sys.stdout = old
    msgs += out.getvalue().rstrip().splitlines()
    return code == 0, loaded, msgs


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    a = parse_args(argv)
    for name, path in (("paraview", a.paraview), ("import", a.import_cmd)):
        if not path or not os.path.exists(path):
            sys.exit("gui_check.py: %s not found (scripts/setup.sh installs "
                     "paraview and imagemagick)" % name)
    ensure_display(argv)
    tmp = tempfile.mkdtemp(prefix="sph_gui_")
    env = dict(os.environ, XDG_CONFIG_HOME=settings_dir(tmp))
    if a.state:
        cmd = [a.paraview, "--state=" + os.path.abspath(a.state)]
    else:
        cmd = [a.paraview, "--script=" + os.path.abspath(a.script)]
    log("$ (cd %s; %s)" % (a.cwd, " ".join(cmd)))
    gui_log = open(os.path.join(tmp, "paraview.log"), "w")
    gui = subprocess.Popen(cmd, cwd=a.cwd, env=env, stdout=gui_log,
                           stderr=subprocess.STDOUT)
    shot = os.path.join(tmp, "screen.png")
    crop = os.path.join(tmp, "view.png")
    t0 = time.time()
    t_loaded = None
    passed, msgs = False, ["no screenshot taken"]
    try:
        while time.time() - t0 < a.timeout:
            if a.settle is not None and t_loaded is not None and \
                    time.time() - t_loaded > a.settle:
                msgs.append("gave up %g s after the sources were listed"
                            % a.settle)
                break
            time.sleep(1.0)
            if gui.poll() is not None:
                msgs = ["paraview exited with status %d" % gui.returncode]
                break
            r = subprocess.run([a.import_cmd, "-window", "root", shot],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
            if r.returncode != 0 or not os.path.isfile(shot):
                msgs = ["import failed: %s" % r.stdout.decode().strip()]
                continue
            passed, loaded, msgs = check_shot(shot, crop, a)
            if loaded and t_loaded is None:
                t_loaded = time.time()
                log("sources listed after %.1f s" % (t_loaded - t0))
            if passed:
                break
        log("after %.1f s: %s" % (time.time() - t0,
                                  "PASSED" if passed else "not passed"))
        for m in msgs:
            print("    " + m)
        if a.output and os.path.isfile(shot):
            shutil.copy(shot, a.output)
            if os.path.isfile(crop):
                shutil.copy(crop, os.path.splitext(a.output)[0] + "_view.png")
            log("screenshot: %s" % a.output)
    finally:
        # Our own child only; SIGKILL: there is nothing to save, and on
        # SIGTERM ParaView prints a long stack trace.
        if gui.poll() is None:
            gui.kill()
            gui.wait()
        gui_log.close()
        if not passed:
            with open(os.path.join(tmp, "paraview.log")) as fh:
                lines = [l for l in fh.read().splitlines() if l.strip()]
            if lines:
                log("paraview's output (last lines):")
                for l in lines[-15:]:
                    print("    " + l)
        shutil.rmtree(tmp, ignore_errors=True)
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
