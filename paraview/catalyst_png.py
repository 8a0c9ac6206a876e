"""In-situ pictures of a running sph simulation: a ParaView Catalyst
pipeline script (legacy "Catalyst 1": RequestDataDescription and
DoCoProcessing) for `sph run --catalyst`.

    xvfb-run -a build/sph run cases/dam_break.case \\
        --catalyst paraview/catalyst_png.py --catalyst_every 20

Each time sph hands over the particles (at the start, every catalyst_every
steps and at the end) it writes RUN/catalyst/NAME_00000.png, _00001.png, ...
(RUN: the run's folder, NAME: the run's name): the view render.py draws for
a run folder, built here from the particles in memory (point Gaussians of
radius particle_spacing/2 coloured by pressure with the Turbo map, a
legend with the unit, "pressure [Pa]", the time, the domain outline, wall
particles grey, the colour range the fluid's at that step). The particles
are the vtkPolyData that the .vtp files hold, arrays and names alike.

Settings, from the environment of `sph run`:
    SPH_CATALYST_FIELD   point array to colour by (default pressure; vectors
                         by magnitude)
    SPH_CATALYST_SIZE    image size "W H" (default "800 800")
    SPH_CATALYST_RANGE   a fixed colour range "MIN MAX" (default: the fluid's
                         range at each picture)

Debian's ParaView 5.11 renders through X only: without an X display
(DISPLAY unset) the script refuses to load, so sph stops before the run
with one line saying so; under `xvfb-run -a` it renders off screen.
"""
import os
import sys
sys.dont_write_bytecode = True   # keep the source tree clean



def _check_display():
    """Refuse to load without a reachable X display: VTK would abort the
    whole simulation when it opens its window."""
    display = os.environ.get("DISPLAY")
    if not display:
        raise SystemExit(
            "needs an X display to render (Debian's ParaView 5.11 renders "
            "through X only) and DISPLAY is not set: run sph under "
            "`xvfb-run -a`")
    import ctypes
    import ctypes.util
    try:
        xlib = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
    except OSError as e:
        raise SystemExit("needs libX11 to render: %s" % e)
    xlib.XOpenDisplay.restype = ctypes.c_void_p
    xlib.XOpenDisplay.argtypes = [ctypes.c_char_p]
    xlib.XCloseDisplay.argtypes = [ctypes.c_void_p]
    handle = xlib.XOpenDisplay(None)
    if not handle:
        raise SystemExit("cannot open the X display DISPLAY=%s (no X server "
                         "there?): run sph under `xvfb-run -a`" % display)
    xlib.XCloseDisplay(handle)


_check_display()

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import render  # noqa: E402  (the view render.py draws)
import paraview.simple as pv  # noqa: E402

render.pv = pv
pv._DisableFirstRenderCameraReset()

FIELD = os.environ.get("SPH_CATALYST_FIELD", render.DEFAULT_FIELD)
SIZE = [int(v) for v in os.environ.get("SPH_CATALYST_SIZE", "800 800").split()]
RANGE = [float(v) for v in os.environ.get("SPH_CATALYST_RANGE", "").split()]
if len(SIZE) != 2 or min(SIZE) < 64:
    raise SystemExit("SPH_CATALYST_SIZE must be two numbers >= 64, W H")
if RANGE and (len(RANGE) != 2 or not RANGE[0] < RANGE[1]):
    raise SystemExit("SPH_CATALYST_RANGE must be two numbers MIN < MAX")

# The pipeline, built on the first call from the first particles.
_pipeline = {}


def RequestDataDescription(datadescription):
    """Every call sph makes is rendered: all arrays and the points."""
    grid = datadescription.GetInputDescriptionByName("input")
    grid.AllFieldsOn()
    grid.GenerateMeshOn()


def _user_value(datadescription, name):
    arr = datadescription.GetUserData().GetAbstractArray(name)
    return arr.GetValue(0)


def _build(grid, datadescription):
    pd = grid.GetPointData()
    if pd.GetArray(FIELD) is None:
        names = sorted(pd.GetArrayName(k) for k in range(pd.GetNumberOfArrays()))
        raise RuntimeError("no point array '%s' (SPH_CATALYST_FIELD); the "
                           "particles have %s" % (FIELD, ", ".join(names)))
    arr = pd.GetArray(FIELD)
    ncomp = arr.GetNumberOfComponents()
    unit = arr.GetInformation().Get(arr.UNITS_LABEL())
    # On several ranks the domain, when the particles do not carry it (no
    # walls), is the box around every rank's particles: one camera for all.
    fields, local = render.polydata_field_data(grid)
    override = None
    if _ranks() is not None and "domain_bounds" not in fields and \
            "domain_min" not in fields:
        inf = float("inf")
        override = _all_ranks(local or (inf, -inf) * 3)
    info = render.RunInfo(None, bounds_override=override, polydata=grid)
    pv.LoadPalette("WhiteBackground")
    producer = pv.PVTrivialProducer(registrationName="input")
    producer.GetClientSideObject().SetOutput(grid, datadescription.GetTime())
    view = pv.CreateView("RenderView")
    render.style_view(view, info.dimension, SIZE)
    particles, walls = producer, None
    if pd.GetArray(render.KIND_ARRAY) is not None:
        particles, walls = render.split_kind(producer)
    radius = info.radius(SIZE)
    display = render.show_particles(particles, view, info.dimension, radius)
    lut = render.color_by(display, view, FIELD, "Magnitude", ncomp,
                          render.DEFAULT_COLORMAP, SIZE, unit)
    if walls is not None:
        wdisp = render.show_particles(walls, view, info.dimension, radius)
        wdisp.ColorArrayName = ["POINTS", ""]
        wdisp.AmbientColor = wdisp.DiffuseColor = list(render.WALL_COLOR)
    label = pv.Text(registrationName="time")
    ldisp = pv.Show(label, view)
    ldisp.WindowLocation = "Upper Left Corner"
    ldisp.FontSize = render.Layout(*SIZE).title_font
    ldisp.Color = [0.0, 0.0, 0.0]
    render.domain_outline(view, info.bounds)
    render.fit_camera(view, render.padded(info.bounds, radius, info.dimension),
                      info.dimension, SIZE, "z")
    folder = os.path.join(_user_value(datadescription, "run_folder"), "catalyst")
    os.makedirs(folder, exist_ok=True)
    _pipeline.update(producer=producer, particles=particles, view=view,
                     lut=lut, label=label, frame=0,
                     prefix=os.path.join(folder, _user_value(
                         datadescription, "run_name")))


def _ranks():
    """VTK's global controller when sph runs on several MPI ranks (each
    rank's particles are its own piece), else None."""
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    ranks = vtkMultiProcessController.GetGlobalController()
    if ranks is None or ranks.GetNumberOfProcesses() < 2:
        return None
    return ranks


def _all_ranks(lo_hi):
    """(lo, hi) pairs, flat (lo0, hi0, lo1, hi1, ...), reduced over every
    MPI rank of the run: the lowest lo and the highest hi of each pair."""
    ranks = _ranks()
    if ranks is None:
        return tuple(lo_hi)
    from vtkmodules.vtkParallelCore import vtkCommunicator
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    mine, every = vtkDoubleArray(), vtkDoubleArray()
    mine.SetNumberOfTuples(len(lo_hi))
    for k, v in enumerate(lo_hi):
        mine.SetValue(k, -v if k % 2 == 0 else v)
    ranks.AllReduce(mine, every, vtkCommunicator.MAX_OP)
    return tuple(-every.GetValue(k) if k % 2 == 0 else every.GetValue(k)
                 for k in range(len(lo_hi)))


def DoCoProcessing(datadescription):
    grid = datadescription.GetInputDescriptionByName("input").GetGrid()
    time = datadescription.GetTime()
    if not _pipeline:
        _build(grid, datadescription)   # with these particles
    else:
        _pipeline["producer"].GetClientSideObject().SetOutput(grid, time)
        _pipeline["producer"].MarkModified(_pipeline["producer"])
    p = _pipeline
    p["producer"].UpdatePipeline(time)
    p["label"].Text = render.ANNOTATION_FORMAT.format(time=time)
    if RANGE:
        lo, hi = RANGE
    else:
        try:
            mine = render.data_range(p["particles"], FIELD, "Magnitude", [time])
        except render.RenderError:   # no fluid here: perhaps on another rank
            mine = (float("inf"), float("-inf"))
        lo, hi = _all_ranks(mine)
        if lo > hi:
            raise RuntimeError("no values of '%s' to colour by" % FIELD)
        lo, hi = render.readable_range(lo, hi)
    p["lut"].RescaleTransferFunction(lo, hi)
    pv.GetOpacityTransferFunction(FIELD).RescaleTransferFunction(lo, hi)
    p["lut"].AutomaticRescaleRangeMode = "Never"
    p["view"].ViewTime = time
    out = "%s_%05d.png" % (p["prefix"], p["frame"])
    pv.SaveScreenshot(out, p["view"], ImageResolution=list(SIZE),
                      TransparentBackground=0)
    p["frame"] += 1


def Finalize():
    """Delete the view while its OpenGL context is alive (see render.py)."""
    for view in list(pv.GetViews()):
        pv.Delete(view)
    _pipeline.clear()
