"""Open any sph run in the ParaView GUI with a state file of this folder.

    SPH_RUN=runs/droplet paraview --script=paraview/open_run.py   # from the repo root
    SPH_RUN=/tmp/out SPH_STATE=paraview/water2d.pvsm paraview --script=paraview/open_run.py

SPH_RUN is the run folder (or its .pvd); SPH_STATE the state file (default:
paraview/<case>.pvsm when the run's .pvd is <case>.pvd and that state
exists, else paraview/water2d.pvsm).  The state's reader is pointed at the
run's .pvd whatever its name, the camera frames the run's domain and the
particles are sized to its spacing, as render.py does.  The GUI's own
File > Load State does the same for runs whose .pvd has the state's name.
"""
import os
import sys
sys.dont_write_bytecode = True   # keep the source tree clean



def _here():
    """This folder: the GUI runs --script files without __file__, so fall
    back on SPH_PARAVIEW_DIR or ./paraview (the repository root's)."""
    if "__file__" in globals():
        return os.path.dirname(os.path.abspath(__file__))
    for d in (os.environ.get("SPH_PARAVIEW_DIR"), "paraview", "."):
        if d and os.path.isfile(os.path.join(d, "render.py")):
            return os.path.abspath(d)
    raise SystemExit("open_run.py: run it from the repository root or set "
                     "SPH_PARAVIEW_DIR to the paraview/ folder")


HERE = _here()
sys.path.insert(0, HERE)
import render  # noqa: E402
import paraview.simple as pv  # noqa: E402


def open_run():
    run = os.environ.get("SPH_RUN")
    if not run:
        raise render.RenderError("set SPH_RUN to a run folder, e.g. "
                                 "SPH_RUN=runs/dam_break paraview "
                                 "--script=paraview/open_run.py")
    pvd = render.find_pvd(run)
    steps = render.read_pvd(pvd)
    name = os.path.splitext(os.path.basename(pvd))[0]
    state = os.environ.get("SPH_STATE")
    if not state:
        state = os.path.join(HERE, name + ".pvsm")
        if not os.path.isfile(state):
            state = os.path.join(HERE, "water2d.pvsm")
    render.pv = pv
    reader, display, view = render.load_state(os.path.abspath(state), pvd)
    if pv.GetLayout(view) is None:
        # A state without a layout (older ones, or from elsewhere): the GUI
        # would show no view at all.
        pv.AssignViewToLayout(view=view, layout=pv.CreateLayout("sph"),
                              hint=0)
    info = render.RunInfo(steps)
    size = list(view.ViewSize) if view.ViewSize[0] > 0 else [800, 800]
    render.refit_from_state(view, display, info, size, None)
    pv.GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
    pv.Render(view)
    print("open_run.py: %s with %s" % (pvd, state))


try:
    open_run()
except render.RenderError as e:
    print("open_run.py: error: %s" % e)
