#!/usr/bin/env pvpython
"""(Re)generate the ParaView state files in paraview/ with this ParaView.

    xvfb-run -a pvpython --disable-xdisplay-test paraview/make_states.py \\
        --sph build/sph [--only water2d dam_break ...]

For every state below it runs the case briefly with `sph` into a scratch
folder, builds the same view as render.py's default one (point Gaussians of
radius particle_spacing/2 coloured by the field, legend, time, domain outline,
top view in 2D), points the reader at runs/<case>/<case>.pvd (where
`sph run cases/<case>.case` writes by default, relative to the repository
root) and saves paraview/<state>.pvsm.  Without --sph a synthetic dam-break
series (make_synthetic_run.py) stands in for every case.

The view remembers the domain box, the dimension and the radius factor as
proxy annotations (sph.*): render.py uses them to frame other runs and other
image sizes, and the tests use sph.case to know which case a state is for.
"""
import argparse
import os
import shutil
import subprocess
import sys
sys.dont_write_bytecode = True   # keep the source tree clean
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import render  # noqa: E402

# state name -> (case, field, colour preset, clip).  Water cases show
# pressure; the few-particle cases show the speed (their pressure is zero
# until two particles meet).  clip: the 3D view cut through the middle of
# the domain (render.add_clip), to show the inside of the fluid.
STATES = {
    "water2d": ("dam_break", "pressure", "Turbo", False),
    "dam_break": ("dam_break", "pressure", "Turbo", False),
    "droplet": ("droplet", "pressure", "Turbo", False),
    "block_drop": ("block_drop", "pressure", "Turbo", False),
    "one_particle": ("one_particle", "velocity", "Turbo", False),
    "two_particles": ("two_particles", "velocity", "Turbo", False),
    "three_particles": ("three_particles", "velocity", "Turbo", False),
    "four_particles": ("four_particles", "velocity", "Turbo", False),
    "dam_break_3d": ("dam_break_3d", "pressure", "Turbo", True),
    "spheric2_dam_break_box": ("spheric2_dam_break_box", "pressure", "Turbo", True),
}
# The view size the states are made for: about the GUI's render view on a
# 1600x1000 screen (the GUI resizes the view; the camera keeps the domain's
# height, and explicit points keep their 4-pixel minimum radius).
STATE_VIEW_SIZE = (840, 520)


def make_run(case, scratch, sph):
    out = os.path.join(scratch, "runs", case)
    if sph:
        case_file = os.path.join(ROOT, "cases", case + ".case")
        if not os.path.isfile(case_file):
            return None
        cmd = [sph, "run", case_file, "--output", out, "--end_time", "0.002", "--overwrite",
               "--no-progress"]
        r = subprocess.run(cmd, stdout=subprocess.DEVNULL)
        if r.returncode != 0:
            sys.exit("make_states.py: %s failed" % " ".join(cmd))
    else:
        import make_synthetic_run
        make_synthetic_run.generate(out, case, steps=2,
                                    dim=case_dimension(case))
    return render.find_pvd(out)


def case_dimension(case):
    """`dimension` of cases/<case>.case (2 when absent)."""
    path = os.path.join(ROOT, "cases", case + ".case")
    if os.path.isfile(path):
        with open(path) as fh:
            for line in fh:
                key, _, value = line.split("#")[0].partition("=")
                if key.strip() == "dimension":
                    return int(value)
    return 2


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sph", help="the sph executable (default: synthetic "
                    "data instead of real runs)")
    ap.add_argument("--only", nargs="+", metavar="STATE", choices=STATES,
                    help="states to make (default: all)")
    ap.add_argument("--out", default=HERE, help="folder for the .pvsm files")
    a = ap.parse_args()
    a.out = os.path.abspath(a.out)
    if a.sph:
        a.sph = os.path.abspath(a.sph)

    import paraview.simple as pv
    render.pv = pv
    pv._DisableFirstRenderCameraReset()
    scratch = tempfile.mkdtemp(prefix="sph_states_")
    try:
        for name in a.only or list(STATES):
            case, field, preset, clip = STATES[name]
            pvd = make_run(case, scratch, a.sph)
            # The state refers to runs/<case>/<case>.pvd relative to the
            # repository root, where `sph run` writes by default, so that
            # `paraview --state=paraview/<case>.pvsm` works from there; and
            # LoadState(data_directory=...) matches it by file name.
            os.chdir(scratch)
            rel = os.path.join("runs", case, case + ".pvd")
            if pvd is None:
                print("skip %s: no cases/%s.case" % (name, case))
                continue
            steps = render.read_pvd(pvd)
            arrays = render.vtp_point_arrays(steps[0][1])
            info = render.RunInfo(steps)
            pv.ResetSession()
            pv._DisableFirstRenderCameraReset()
            pv.LoadPalette("WhiteBackground")
            # split: every state separates wall particles (the `kind`
            # array) from the fluid, and still shows runs without `kind`.
            reader, display, view = render.build_default(
                rel, info, field, "Magnitude", arrays[field], preset,
                STATE_VIEW_SIZE, "z", split=True, clip=clip,
                unit=render.vtp_point_units(steps[0][1]).get(field))
            view.SMProxy.SetAnnotation(render.VIEW_ANNOTATION + "case", case)
            scene = pv.GetAnimationScene()
            scene.UpdateAnimationUsingDataTimeSteps()
            scene.AnimationTime = steps[0][0]
            # Colour range: that of the scratch run's steps (a readable one
            # for a constant field: ParaView would make speed 0 at rest a
            # range 0 .. 1e-38); the GUI grows it as the run plays.
            lo, hi = render.readable_range(*render.data_range(
                render.particle_source(reader), field, "Magnitude",
                [t for t, _ in steps]))
            reader.UpdatePipeline(steps[0][0])
            lut = pv.GetColorTransferFunction(field)
            lut.RescaleTransferFunction(lo, hi)
            pv.GetOpacityTransferFunction(field).RescaleTransferFunction(lo, hi)
            lut.AutomaticRescaleRangeMode = "Grow and update every timestep"
            reader.SMProxy.SetAnnotation(render.VIEW_ANNOTATION + "case",
                                         case)
            out = os.path.join(a.out, name + ".pvsm")
            pv.SaveState(out)
            print("wrote %s (%s, coloured by %s)" % (out, case, field))
            for v in list(pv.GetViews()):
                pv.Delete(v)
    finally:
        os.chdir(ROOT)
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
