#!/usr/bin/env pvpython
"""Render the particles of an `sph` run to PNG, headless.

    xvfb-run -a pvpython --disable-xdisplay-test paraview/render.py RUN [options]

RUN is a run folder written by `sph run ... --output RUN` (it holds one .pvd
file) or the .pvd file itself.  By default the last output step is rendered
into RUN/<name>.png with a view built on the fly: particles as point Gaussians
of radius particle_spacing/2 coloured by pressure, a colour legend, the time,
white background; a top view for 2D runs, an isometric-like camera for 3D
(--clip: only the far half of the domain, cut through its middle, to show
the inside).  When the run has the point array `kind` (0 fluid, 1 wall
particle) the wall particles are drawn grey and the colour range is the
fluid's.

Examples:
    render.py runs/dam_break                          # last step, pressure
    render.py runs/dam_break --field density --time 0 --output t0.png
    render.py runs/dam_break --state paraview/water2d.pvsm --size 800 800
    render.py runs/dam_break --all --output frames/ --mp4   # every step
    render.py runs/dam_break_3d --state paraview/dam_break_3d.pvsm --time 0.3

Exit status: 0 on success, 1 on any error (with a message on stderr),
2 on bad command-line usage.
"""
import argparse
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
ONE_LINER = ("xvfb-run -a pvpython --disable-xdisplay-test "
             "paraview/render.py RUN_DIR [options]")
REEXEC_ENV = "SPH_RENDER_REEXEC"



class Layout:
    """Screen layout of a W x H image, in normalised viewport coordinates
    (origin lower left): the domain goes in plot_box, the colour legend in
    a strip on the right wide enough for its labels, the time on top.
    check_png.py uses it to tell particles from the legend and the text."""

    def __init__(self, W, H):
        small = min(W, H) < 400
        self.title_font = 12 if small else 14
        self.label_font = 10 if small else 12
        strip = max(0.19, (30 + 6.5 * self.label_font) / float(W))
        self.legend_x = 1.0 - strip              # legend strip starts here
        self.legend_position = (self.legend_x + 0.02, 0.08)
        self.legend_length = 0.80
        self.annotation_y = 1.0 - (6 + 2.2 * self.title_font) / float(H)
        self.plot_box = (0.03, 0.03, self.legend_x - 0.03,
                         min(0.88, self.annotation_y - 0.02))


def plot_box(size):
    return Layout(*size).plot_box
ANNOTATION_FORMAT = "t = {time:.4f} s"
DEFAULT_FIELD = "pressure"
DEFAULT_COLORMAP = "Turbo"
RADIUS_FACTOR = 0.5                   # Gaussian radius = factor * spacing
MIN_RADIUS_PX = 2.0                   # ... but at least this many pixels
MIN_RADIUS_PX_POINTS = 4.0            # ... or this for explicit points
VIEW_ANNOTATION = "sph."              # prefix of our keys in a view proxy
KIND_ARRAY = "kind"                   # point array: 0 fluid, 1 wall particle
WALL_COLOR = (0.7, 0.7, 0.7)          # wall particles: neutral grey
# Python Calculator expression of split_kind(): `kind`, or 0 without it.
KIND_EXPRESSION = ('inputs[0].PointData["kind"] if "kind" in '
                   'inputs[0].PointData.keys() else 0 * inputs[0].Points[:, 0]')


class RenderError(Exception):
    """An error to report to the user in one line, without a traceback."""


def fail(msg):
    sys.stderr.write("render.py: error: %s\n" % msg)
    sys.exit(1)


# ---------------------------------------------------------------------------
# Everything up to the ParaView import works with any Python 3, so that the
# common mistakes are reported fast and clearly.

def parse_args(argv):
    ap = argparse.ArgumentParser(
        prog="render.py",
        description=__doc__.split("\n\n")[0] + "\n\n    " + ONE_LINER,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="See docs/paraview.md for more.")
    ap.add_argument("run", metavar="RUN_DIR_OR_PVD",
                    help="sph output folder (holding one .pvd) or a .pvd file")
    ap.add_argument("--state", metavar="FILE.pvsm",
                    help="ParaView state to render with (its data file is "
                         "replaced by this run's .pvd); default: a view built "
                         "on the fly")
    ap.add_argument("--field", metavar="NAME",
                    help="point array to colour by (default: %s, or the "
                         "state's choice with --state); vectors are coloured "
                         "by magnitude unless --component is given"
                         % DEFAULT_FIELD)
    ap.add_argument("--component", choices=("Magnitude", "X", "Y", "Z"),
                    default="Magnitude", help="vector component to colour by")
    when = ap.add_mutually_exclusive_group()
    when.add_argument("--time", metavar="T",
                      help="simulation time to render (the nearest output "
                           "step is used), or 'first' / 'last' (default)")
    when.add_argument("--all", action="store_true",
                      help="render every output step into numbered PNGs")
    ap.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                    default=[800, 800], help="image size in pixels "
                    "(default 800 800)")
    ap.add_argument("--output", metavar="PNG_OR_DIR",
                    help="PNG file, or folder for the PNG(s); default: "
                         "RUN/<name>.png, or RUN/frames/<name>_NNNNN.png "
                         "with --all. With --all a FILE.png gives "
                         "FILE_NNNNN.png")
    ap.add_argument("--range", nargs=2, type=float, metavar=("MIN", "MAX"),
                    help="colour range (default: the data range at the "
                         "rendered time, or over all steps with --all)")
    ap.add_argument("--colormap", default=None,
                    help="ParaView colour preset (default %s, or the state's)"
                         % DEFAULT_COLORMAP)
    ap.add_argument("--bounds", nargs="+", type=float, metavar="B",
                    help="domain box to frame: XMIN XMAX YMIN YMAX "
                         "[ZMIN ZMAX] (default: see README)")
    ap.add_argument("--up", choices=("x", "y", "z"), default=None,
                    help="vertical axis of 3D views (default z)")
    ap.add_argument("--clip", action="store_true",
                    help="3D runs without --state: show only the far half "
                         "of the domain, cut through its middle, so that "
                         "the inside of the fluid shows (no effect in 2D)")
    ap.add_argument("--mp4", nargs="?", const="", metavar="FILE.mp4",
                    help="also join the frames into an mp4 with ffmpeg "
                         "(implies --all; default FILE: next to the frames)")
    ap.add_argument("--fps", type=float, default=10.0,
                    help="frames per second of the mp4 (default 10)")
    a = ap.parse_args(argv)
    if a.mp4 is not None:
        a.all = True
    if a.size[0] < 16 or a.size[1] < 16 or max(a.size) > 8192:
        ap.error("--size must be between 16 and 8192 pixels")
    if a.bounds is not None and len(a.bounds) not in (4, 6):
        ap.error("--bounds takes 4 (2D) or 6 (3D) numbers")
    if a.time is not None and a.time not in ("first", "last"):
        try:
            float(a.time)
        except ValueError:
            ap.error("--time takes a number, 'first' or 'last'")
    return a


def find_pvd(path):
    """Return the .pvd of a run folder or the .pvd given."""
    if not os.path.exists(path):
        raise RenderError("no such run folder or file: %s" % path)
    if os.path.isdir(path):
        pvds = sorted(glob.glob(os.path.join(path, "*.pvd")))
        if not pvds:
            raise RenderError(
                "no .pvd file in %s: is it the --output folder of "
                "'sph run'?" % path)
        if len(pvds) > 1:
            raise RenderError(
                "several .pvd files in %s (%s): pass the one to render"
                % (path, ", ".join(os.path.basename(p) for p in pvds)))
        return os.path.abspath(pvds[0])
    if not path.endswith(".pvd"):
        raise RenderError("%s is not a .pvd file nor a run folder" % path)
    return os.path.abspath(path)


def read_pvd(pvd):
    """[(time, absolute .vtp path)] of a .pvd collection, sorted by time."""
    try:
        root = ET.parse(pvd).getroot()
    except (ET.ParseError, OSError) as e:
        raise RenderError("cannot read %s: %s" % (pvd, e))
    base = os.path.dirname(pvd)
    steps = []
    for ds in root.iter("DataSet"):
        f = ds.get("file")
        if f is None:
            continue
        steps.append((float(ds.get("timestep", "0")),
                      os.path.normpath(os.path.join(base, f))))
    if not steps:
        raise RenderError("%s lists no output step" % pvd)
    missing = [f for _, f in steps if not os.path.isfile(f)]
    if missing:
        raise RenderError("%s refers to missing file(s): %s" % (
            pvd, ", ".join(missing[:3]) + (" ..." if len(missing) > 3 else "")))
    steps.sort(key=lambda s: s[0])
    return steps


def first_piece(pvtp):
    """The first piece a parallel snapshot (.pvtp, a run on several MPI
    ranks) lists, as a path: every piece has the same arrays."""
    with open(pvtp, "rb") as fh:
        text = fh.read().decode("latin-1")
    m = re.search(r'<Piece\s+Source="([^"]+)"', text)
    if not m:
        raise RenderError("%s lists no piece" % pvtp)
    return os.path.join(os.path.dirname(pvtp), m.group(1))


def vtp_point_data_xml(vtp):
    """The <PointData> element of a VTK XML file as text ("" without one),
    read from its XML header (works for inline and appended data; for a
    .pvtp, from its first piece)."""
    if vtp.endswith(".pvtp"):
        vtp = first_piece(vtp)
    head = []
    with open(vtp, "rb") as fh:
        for line in fh:
            if b"<AppendedData" in line:
                break
            head.append(line)
    text = b"".join(head).decode("latin-1")
    m = re.search(r"<PointData[^>]*>(.*?)</PointData>", text, re.S)
    return m.group(1) if m else ""


def vtp_point_arrays(vtp):
    """{name: number of components} of the point data of a VTK XML file."""
    arrays = {}
    for tag in re.finditer(r"<DataArray\b([^>]*)>", vtp_point_data_xml(vtp)):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', tag.group(1)))
        if "Name" in attrs:
            arrays[attrs["Name"]] = int(attrs.get("NumberOfComponents", "1"))
    return arrays


def vtp_point_units(vtp):
    """{name: unit} of the point arrays of a VTK XML file that carry one (the
    UNITS_LABEL information key sph writes: Pa, N/m, kg/m^3, ...), read from
    its XML header."""
    units = {}
    for arr in re.finditer(r"<DataArray\b([^>]*?)(/>|>(.*?)</DataArray>)",
                           vtp_point_data_xml(vtp), re.S):
        name = re.search(r'\bName="([^"]*)"', arr.group(1))
        unit = re.search(r'<InformationKey\s+name="UNITS_LABEL"[^>]*>\s*'
                         r'(.*?)\s*</InformationKey>', arr.group(3) or "",
                         re.S)
        if name and unit:
            units[name.group(1)] = unit.group(1)
    return units


def legend_title(field, component, ncomp, unit=None):
    """The colour legend's title: the field (speed for the velocity's
    magnitude) and its unit, "pressure [Pa]"; none for a dimensionless
    unit ("1") or an array without one."""
    # ("|v|" would be nicer, but the legend's font drops the bars)
    title = field if ncomp == 1 else (
        ("speed" if field == "velocity" else field + " mag.")
        if component == "Magnitude" else "%s %s" % (field, component))
    if unit and unit != "1":
        title += " [%s]" % unit
    return title


def check_field(field, arrays, vtp):
    if field not in arrays:
        raise RenderError(
            "no point array '%s' in %s; available arrays: %s"
            % (field, os.path.basename(vtp), ", ".join(sorted(arrays))))


def choose_steps(a, steps):
    """Indices (into steps) of the output steps to render."""
    if a.all:
        return list(range(len(steps)))
    if a.time in (None, "last"):
        return [len(steps) - 1]
    if a.time == "first":
        return [0]
    t = float(a.time)
    i = min(range(len(steps)), key=lambda k: abs(steps[k][0] - t))
    tol = 1e-9 * max(1.0, abs(t))
    if abs(steps[i][0] - t) > tol:
        sys.stderr.write("render.py: note: no output at t = %g, rendering "
                         "the nearest one, t = %g\n" % (t, steps[i][0]))
    return [i]


def output_paths(a, pvd, steps, indices):
    """PNG path for every index to render."""
    name = os.path.splitext(os.path.basename(pvd))[0]
    run_dir = os.path.dirname(pvd)
    out = a.output
    if a.all:
        if out is None:
            prefix = os.path.join(run_dir, "frames", name)
        elif out.lower().endswith(".png"):
            prefix = out[:-4]
        else:
            prefix = os.path.join(out, name)
        return [("%s_%05d.png" % (prefix, i)) for i in indices]
    if out is None:
        return [os.path.join(run_dir, name + ".png")]
    if out.lower().endswith(".png"):
        return [out]
    return [os.path.join(out, name + ".png")]


def ensure_paraview(argv):
    """Import paraview.simple, or re-run this script under xvfb-run/pvpython,
    or explain how to run it."""
    has_display = bool(os.environ.get("DISPLAY"))
    try:
        if not has_display:
            raise ImportError("no X display")
        import paraview.simple  # noqa: F401
        return
    except ImportError as e:
        reason = str(e)
    xvfb, pvpython = shutil.which("xvfb-run"), shutil.which("pvpython")
    if os.environ.get(REEXEC_ENV) != "1" and xvfb and pvpython:
        sys.stderr.write("render.py: note: %s; re-running as: xvfb-run -a "
                         "pvpython --disable-xdisplay-test render.py ...\n"
                         % ("no X display" if not has_display
                            else "cannot import paraview (%s)" % reason))
        sys.stderr.flush()
        env = dict(os.environ, **{REEXEC_ENV: "1"})
        cmd = [xvfb, "-a", pvpython, "--disable-xdisplay-test",
               os.path.abspath(__file__)] + list(argv)
        try:
            os.execvpe(xvfb, cmd, env)
        except OSError as e2:
            fail("cannot start %s: %s" % (xvfb, e2))
    if not has_display:
        fail("no X display to render with (ParaView 5.11 from Debian "
             "renders through X only). Run:\n    %s\n"
             "(install with: apt-get install paraview python3-paraview "
             "xvfb xauth)" % ONE_LINER)
    fail("ParaView's Python modules cannot be imported (%s). Run the script "
         "with ParaView's interpreter:\n    %s\n(install with: apt-get "
         "install paraview python3-paraview xvfb xauth)" % (reason, ONE_LINER))


# ---------------------------------------------------------------------------
# ParaView side.  `pv` is paraview.simple, imported lazily.

pv = None


def field_data(vtp):
    """Field data of one output file as {name: tuple of values}, plus bounds."""
    from vtkmodules.vtkIOXML import (vtkXMLPolyDataReader,
                                     vtkXMLPPolyDataReader)
    r = (vtkXMLPPolyDataReader() if vtp.endswith(".pvtp")
         else vtkXMLPolyDataReader())
    r.SetFileName(vtp)
    r.Update()
    return polydata_field_data(r.GetOutput())


def polydata_field_data(out):
    """Field data of a vtkPolyData as {name: tuple of values}, plus bounds."""
    fd = out.GetFieldData()
    values = {}
    for k in range(fd.GetNumberOfArrays()):
        arr = fd.GetAbstractArray(k)
        if arr is None or not hasattr(arr, "GetTuple"):
            continue
        n = arr.GetNumberOfTuples() * arr.GetNumberOfComponents()
        values[arr.GetName()] = tuple(arr.GetValue(j) for j in range(n))
    bounds = out.GetBounds() if out.GetNumberOfPoints() > 0 else None
    return values, bounds


class RunInfo:
    """What the renderer needs to know about a run."""

    def __init__(self, steps, bounds_override=None, polydata=None):
        """steps: the run's (time, file) list; or, in situ (Catalyst),
        None and the particles' vtkPolyData."""
        if polydata is not None:
            first, self.first_bounds = polydata_field_data(polydata)
        else:
            first, self.first_bounds = field_data(steps[0][1])
        self.dimension = int(first.get("dimension", (0,))[0]) or None
        # Lattice runs: particle_spacing > 0; explicit points have 0 there,
        # and then the smoothing length stands in (radius h/2).
        self.spacing = first.get("particle_spacing", (0.0,))[0]
        self.explicit_points = not self.spacing
        if not self.spacing:
            self.spacing = first.get("smoothing_length", (0.0,))[0]
        if self.dimension is None:
            b = self.first_bounds or (0, 0, 0, 0, 0, 0)
            self.dimension = 2 if b[5] - b[4] == 0 else 3
        self.bounds = self._domain(steps, first, bounds_override)
        if not self.spacing:   # last resort: a fraction of the domain
            self.spacing = max(self.bounds[1] - self.bounds[0],
                               self.bounds[3] - self.bounds[2]) / 100.0

    def radius(self, size, factor=RADIUS_FACTOR):
        """Gaussian radius: factor * spacing, but at least MIN_RADIUS_PX
        pixels (more for a few explicit points) when the domain is framed
        in a size[0] x size[1] image, so that particles stay visible."""
        W, H = size
        x0, y0, x1, y1 = plot_box(size)
        b = self.bounds
        ext = [max(b[2 * k + 1] - b[2 * k], 1e-12) for k in range(3)]
        if self.dimension == 2:
            px = min((x1 - x0) * W / ext[0], (y1 - y0) * H / ext[1])
        else:
            px = min((x1 - x0) * W, (y1 - y0) * H) / math.sqrt(
                sum(e * e for e in ext))
        min_px = MIN_RADIUS_PX_POINTS if self.explicit_points else \
            MIN_RADIUS_PX
        return max(factor * self.spacing, min_px / px)

    def _domain(self, steps, first, override):
        d = self.dimension
        if override:
            b = list(override) + [0.0, 0.0]
            return tuple(b[:6])
        if "domain_bounds" in first and len(first["domain_bounds"]) >= 2 * d:
            b = list(first["domain_bounds"]) + [0.0, 0.0]
            return tuple(b[:6])
        if "domain_min" in first and "domain_max" in first:
            lo, hi = first["domain_min"], first["domain_max"]
            b = []
            for k in range(3):
                b += [lo[k] if k < len(lo) else 0.0,
                      hi[k] if k < len(hi) else 0.0]
            return tuple(b)
        # Box around the particles of (a sample of 11 of) all steps (in
        # situ: of the first) ...
        if steps is None:
            boxes = [self.first_bounds]
        else:
            picks = steps if len(steps) <= 11 else [
                steps[int(round(k * (len(steps) - 1) / 10.0))]
                for k in range(11)]
            boxes = [field_data(f)[1] for _, f in picks]
        lo, hi = [math.inf] * 3, [-math.inf] * 3
        for b in boxes:
            if b is None:
                continue
            for k in range(3):
                lo[k], hi[k] = min(lo[k], b[2 * k]), max(hi[k], b[2 * k + 1])
        if lo[0] == math.inf:
            lo, hi = [0.0] * 3, [1.0] * 3
        # ... widened to the unit square / cube when the particles stay
        # inside it: every shipped case lives there, and it keeps the frame
        # fixed while the fluid moves.
        eps = 1e-9
        if all(lo[k] >= -eps and hi[k] <= 1 + eps for k in range(d)):
            lo[:d], hi[:d] = [0.0] * d, [1.0] * d
        if d == 2:
            lo[2] = hi[2] = 0.0
        return (lo[0], hi[0], lo[1], hi[1], lo[2], hi[2])


def padded(bounds, pad, dimension):
    b = list(bounds)
    for k in range(dimension):
        b[2 * k] -= pad
        b[2 * k + 1] += pad
    return b


def fit_camera(view, bounds, dimension, size, up="z", cut=False):
    """Frame `bounds` inside the plot box of a size[0] x size[1] image.
    3D: from a corner above the box; cut (a view cut open by add_clip):
    from lower and more in front, facing the cut."""
    W, H = float(size[0]), float(size[1])
    x0, y0, x1, y1 = plot_box(size)
    bw = max(bounds[1] - bounds[0], 1e-12)
    bh = max(bounds[3] - bounds[2], 1e-12)
    cx, cy = (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2
    cz = (bounds[4] + bounds[5]) / 2
    if dimension == 2:
        s = min((x1 - x0) * W / bw, (y1 - y0) * H / bh)   # pixels per unit
        fx = cx + (0.5 - (x0 + x1) / 2) * W / s
        fy = cy + (0.5 - (y0 + y1) / 2) * H / s
        dist = 10.0 * max(bw, bh)
        view.CameraParallelProjection = 1
        view.CameraFocalPoint = [fx, fy, cz]
        view.CameraPosition = [fx, fy, cz + dist]
        view.CameraViewUp = [0.0, 1.0, 0.0]
        view.CameraParallelScale = H / (2 * s)
        view.InteractionMode = "2D"
        return
    # 3D: perspective camera looking down on the box from a corner.
    ax = "xyz".index(up)
    upv = [0.0, 0.0, 0.0]
    upv[ax] = 1.0
    # horizontal axes (right-handed), then the viewing direction
    h1, h2 = [(1, 2), (2, 0), (0, 1)][ax]
    direction = [0.0, 0.0, 0.0]
    direction[h1], direction[h2], direction[ax] = \
        (0.5, -1.3, 0.5) if cut else (1.0, -1.3, 0.9)
    n = math.sqrt(sum(c * c for c in direction))
    direction = [c / n for c in direction]
    dz = max(bounds[5] - bounds[4], 1e-12)
    radius = 0.5 * math.sqrt(bw * bw + bh * bh + dz * dz)
    angle = 30.0
    tan_half = math.tan(math.radians(angle / 2))
    fit_px = min((x1 - x0) * W, (y1 - y0) * H)
    # the bounding sphere must subtend at most fit_px of the H-pixel view
    theta = math.atan(tan_half * fit_px / H)
    dist = radius / math.sin(theta)
    wpp = 2 * dist * tan_half / H           # world units per pixel at focus
    # camera frame: right = dir_to_camera x up ... built from forward/up
    fwd = [-c for c in direction]
    right = [fwd[1] * upv[2] - fwd[2] * upv[1],
             fwd[2] * upv[0] - fwd[0] * upv[2],
             fwd[0] * upv[1] - fwd[1] * upv[0]]
    rn = math.sqrt(sum(c * c for c in right))
    right = [c / rn for c in right]
    cam_up = [right[1] * fwd[2] - right[2] * fwd[1],
              right[2] * fwd[0] - right[0] * fwd[2],
              right[0] * fwd[1] - right[1] * fwd[0]]
    sx = -(0.5 - (x0 + x1) / 2) * W * wpp
    sy = -(0.5 - (y0 + y1) / 2) * H * wpp
    centre = [cx, cy, cz]
    focal = [centre[k] - sx * right[k] - sy * cam_up[k] for k in range(3)]
    view.CameraParallelProjection = 0
    view.CameraViewAngle = angle
    view.CameraFocalPoint = focal
    view.CameraPosition = [focal[k] + dist * direction[k] for k in range(3)]
    view.CameraViewUp = cam_up
    view.InteractionMode = "3D"


def style_view(view, dimension, size):
    view.ViewSize = list(size)
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 1 if dimension == 3 else 0
    if dimension == 3:
        view.OrientationAxesLabelColor = [0.0, 0.0, 0.0]


def place_legend(bar, size):
    lay = Layout(*size)
    bar.Position = list(lay.legend_position)
    bar.ScalarBarLength = lay.legend_length
    bar.TitleFontSize = lay.title_font
    bar.LabelFontSize = lay.label_font


def place_texts(view, size):
    """Legends and time annotation of a (loaded) view, for this size."""
    lay = Layout(*size)
    for rep in view.Representations:
        xml = rep.GetXMLName()
        if xml == "ScalarBarWidgetRepresentation" and rep.Visibility:
            place_legend(rep, size)
        elif xml == "TextSourceRepresentation":
            rep.FontSize = lay.title_font


def color_by(display, view, field, component, ncomp, colormap, size,
             unit=None):
    if ncomp > 1:
        pv.ColorBy(display, ("POINTS", field, component))
    else:
        pv.ColorBy(display, ("POINTS", field))
    lut = pv.GetColorTransferFunction(field)
    if colormap:
        if not lut.ApplyPreset(colormap, True):
            raise RenderError("unknown colour preset '%s'" % colormap)
    display.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title = legend_title(field, component, ncomp, unit)
    bar.ComponentTitle = ""
    bar.Orientation = "Vertical"
    bar.HorizontalTitle = 1
    bar.TitleJustification = "Left"
    bar.WindowLocation = "Any Location"
    place_legend(bar, size)
    bar.TitleColor = [0.0, 0.0, 0.0]
    bar.LabelColor = [0.0, 0.0, 0.0]
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = "%-.3g"
    bar.RangeLabelFormat = "%-.3g"
    bar.AddRangeLabels = 1
    return lut


def build_default(pvd, info, field, component, ncomp, colormap, size, up,
                  split=False, clip=False, unit=None):
    """Reader, particle display and view of the on-the-fly view.  Also used
    by make_states.py to build the state files (with a relative pvd).

    split: separate fluid from wall particles by the `kind` array (see
    split_kind); clip: 3D only, show the far half of the domain cut through
    its middle (see add_clip), so that the inside of the fluid shows."""
    reader = pv.PVDReader(registrationName=os.path.basename(pvd),
                          FileName=pvd)
    view = pv.CreateView("RenderView")
    # A layout holding the view: without one the GUI loads the state but
    # shows no view (an empty render area).
    layout = pv.CreateLayout("sph")
    pv.AssignViewToLayout(view=view, layout=layout, hint=0)
    style_view(view, info.dimension, size)
    particles = reader
    if clip and info.dimension == 3:
        particles = add_clip(reader, info.bounds, up)
    walls = None
    if split:
        particles, walls = split_kind(particles)
    radius = info.radius(size)
    display = show_particles(particles, view, info.dimension, radius)
    color_by(display, view, field, component, ncomp, colormap, size, unit)
    if walls is not None:
        wdisp = show_particles(walls, view, info.dimension, radius)
        wdisp.ColorArrayName = ["POINTS", ""]
        wdisp.AmbientColor = wdisp.DiffuseColor = list(WALL_COLOR)
    label = pv.AnnotateTimeFilter(registrationName="time", Input=reader)
    label.Format = ANNOTATION_FORMAT
    ldisp = pv.Show(label, view)
    ldisp.WindowLocation = "Upper Left Corner"
    ldisp.FontSize = Layout(*size).title_font
    ldisp.Color = [0.0, 0.0, 0.0]
    domain_outline(view, info.bounds)
    # Remember what the camera frames, so that renders at another size (or
    # of another run) can frame it again: see refit_from_state().
    ann = view.SMProxy
    ann.SetAnnotation(VIEW_ANNOTATION + "bounds",
                      " ".join("%.17g" % v for v in info.bounds))
    ann.SetAnnotation(VIEW_ANNOTATION + "dimension", str(info.dimension))
    ann.SetAnnotation(VIEW_ANNOTATION + "up", up)
    ann.SetAnnotation(VIEW_ANNOTATION + "radius_factor", str(RADIUS_FACTOR))
    fit_camera(view, padded(info.bounds, radius, info.dimension),
               info.dimension, size, up, cut=clip and info.dimension == 3)
    return reader, display, view


def show_particles(source, view, dimension, radius):
    """Particles as point Gaussians: flat discs in 2D, shaded balls in 3D."""
    d = pv.Show(source, view)
    d.SetRepresentationType("Point Gaussian")
    d.GaussianRadius = radius
    d.ShaderPreset = "Plain circle" if dimension == 2 else "Sphere"
    return d


def set_role(proxy, role):
    """Tag a pipeline proxy (saved in the state) so that a loaded state's
    fluid, walls and clip can be found again: see find_role()."""
    proxy.SMProxy.SetAnnotation(VIEW_ANNOTATION + "role", role)


def find_role(role):
    for src in pv.GetSources().values():
        key = VIEW_ANNOTATION + "role"
        if src.SMProxy.HasAnnotation(key) and \
                src.SMProxy.GetAnnotation(key) == role:
            return src
    return None


def split_kind(source):
    """(fluid, walls) sources from the point array `kind` (0 fluid, 1 wall).

    A Python Calculator copies `kind` into `sph_kind`, or writes zeros when
    the run has no `kind`; two Thresholds then pick the fluid (sph_kind 0)
    and the walls (sph_kind >= 1).  A Threshold straight on `kind` would
    drop every particle of a run without the array, so this keeps states
    working for both kinds of runs, in the GUI too (no script needed)."""
    calc = pv.PythonCalculator(registrationName="kind", Input=source)
    calc.Expression = KIND_EXPRESSION
    calc.ArrayName = "sph_kind"
    fluid = pv.Threshold(registrationName="fluid", Input=calc)
    fluid.Scalars = ["POINTS", "sph_kind"]
    fluid.LowerThreshold, fluid.UpperThreshold = -0.5, 0.5
    walls = pv.Threshold(registrationName="walls", Input=calc)
    walls.Scalars = ["POINTS", "sph_kind"]
    walls.LowerThreshold, walls.UpperThreshold = 0.5, 1e9
    set_role(fluid, "fluid")
    set_role(walls, "walls")
    return fluid, walls


def add_clip(source, bounds, up):
    """Keep the far half of the particles, cut by the vertical plane through
    the domain's centre that faces the 3D camera (see fit_camera: it looks
    from the -h2 side), so that the cut shows the inside of the fluid."""
    clip = pv.Clip(registrationName="clip", Input=source)
    clip.ClipType = "Plane"
    clip.Crinkleclip = 1          # whole particles (vertex cells), no cutting
    clip.Invert = 0               # keep the side the normal points to
    set_clip_plane(clip, bounds, up)
    set_role(clip, "clip")
    return clip


def set_clip_plane(clip, bounds, up):
    h2 = [(1, 2), (2, 0), (0, 1)]["xyz".index(up)][1]
    normal = [0.0, 0.0, 0.0]
    normal[h2] = 1.0
    clip.ClipType.Origin = [(bounds[2 * k] + bounds[2 * k + 1]) / 2
                            for k in range(3)]
    clip.ClipType.Normal = normal


def domain_outline(view, bounds):
    """A thin grey outline of the framed domain box."""
    box = pv.Box(registrationName="domain")
    set_box(box, bounds)
    d = pv.Show(box, view)
    d.SetRepresentationType("Outline")
    d.ColorArrayName = ["POINTS", ""]
    d.AmbientColor = d.DiffuseColor = [0.6, 0.6, 0.6]
    d.Pickable = 0
    return box


def set_box(box, bounds):
    box.XLength = bounds[1] - bounds[0]
    box.YLength = bounds[3] - bounds[2]
    box.ZLength = bounds[5] - bounds[4]
    box.Center = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
                  (bounds[4] + bounds[5]) / 2]


def state_reader_ids(state):
    """Ids of the PVDReader proxies in a .pvsm file."""
    try:
        root = ET.parse(state).getroot()
    except (ET.ParseError, OSError) as e:
        raise RenderError("cannot read state file %s: %s" % (state, e))
    return [p.get("id") for p in root.iter("Proxy")
            if p.get("group") == "sources" and p.get("type") == "PVDReader"]


def load_state(state, pvd):
    ids = state_reader_ids(state)
    if not ids:
        raise RenderError("state %s has no PVD reader to point at %s"
                          % (state, pvd))
    pv.LoadState(state, filenames=[{"id": i, "FileName": pvd} for i in ids])
    readers = [p for p in pv.GetSources().values()
               if p.GetXMLName() == "PVDReader"]
    if not readers:
        raise RenderError("state %s: no PVD reader after loading" % state)
    reader = readers[0]
    views = [v for v in pv.GetViews() if v.GetXMLName() == "RenderView"]
    if not views:
        raise RenderError("state %s has no render view" % state)
    view = views[0]
    pv.SetActiveView(view)
    display = pv.GetDisplayProperties(particle_source(reader), view)
    return reader, display, view


def particle_source(reader):
    """The source whose display is coloured by the field: the fluid part
    when the pipeline splits fluid from walls (split_kind), else the
    reader (or the clip in front of it)."""
    return find_role("fluid") or find_role("clip") or reader


def refit_from_state(view, display, info, size, up_arg):
    """Frame the run and size the particles again after loading a state made
    by make_states.py (other runs have other spacings, other sizes other
    aspect ratios).  States from elsewhere keep their camera."""
    get = view.SMProxy.GetAnnotation
    key = VIEW_ANNOTATION + "bounds"
    if not view.SMProxy.HasAnnotation(key):
        return
    bounds = info.bounds
    dim = info.dimension
    up = up_arg or get(VIEW_ANNOTATION + "up") or "z"
    factor = float(get(VIEW_ANNOTATION + "radius_factor") or RADIUS_FACTOR)
    radius = info.radius(size, factor)
    for rep in view.Representations:        # fluid and walls alike
        if "GaussianRadius" in rep.ListProperties() and \
                rep.Representation == "Point Gaussian":
            rep.GaussianRadius = radius
    clip = find_role("clip")
    if clip is not None:
        set_clip_plane(clip, bounds, up)
    fit_camera(view, padded(bounds, radius, dim), dim, size, up,
               cut=clip is not None and dim == 3)
    for (name, _), src in pv.GetSources().items():
        if src.GetXMLName() == "Box" and name == "domain":
            set_box(src, bounds)
    view.OrientationAxesVisibility = 1 if dim == 3 else 0


def current_field(display):
    """(field, component) the display colours by, or (None, None)."""
    ca = display.ColorArrayName
    if not ca or not ca[1]:
        return None, None
    lut = display.LookupTable
    comp = "Magnitude"
    if lut is not None and lut.VectorMode == "Component":
        comp = "XYZ"[min(2, int(lut.VectorComponent))]
    return ca[1], comp


def data_range(source, field, component, times):
    """Exact (min, max) of a point array of source over the given times
    (source: the coloured particles, so the fluid only when walls are
    split off)."""
    lo, hi = math.inf, -math.inf
    for t in times:
        source.UpdatePipeline(t)
        arr = source.PointData[field]
        if arr is None:
            continue
        if arr.GetNumberOfComponents() == 1:
            k = 0
        else:
            k = -1 if component == "Magnitude" else "XYZ".index(component)
        r = arr.GetRange(k)
        lo, hi = min(lo, r[0]), max(hi, r[1])
    if lo > hi:
        raise RenderError("no values of '%s' to colour by" % field)
    return lo, hi


def readable_range(lo, hi):
    """(lo, hi), or for a constant field a range with it in the middle."""
    if hi - lo <= 1e-9 * max(abs(lo), abs(hi)):
        v = 0.5 * (lo + hi)
        d = abs(v) if v else 1.0
        lo, hi = v - d, v + d
    return lo, hi


def set_color_range(display, lut, a, source, field, component, times):
    if a.range is not None:
        lo, hi = a.range
    else:
        lo, hi = readable_range(*data_range(source, field, component, times))
    lut.RescaleTransferFunction(lo, hi)
    pwf = pv.GetOpacityTransferFunction(field)
    pwf.RescaleTransferFunction(lo, hi)
    lut.AutomaticRescaleRangeMode = "Never"


def render(a, pvd, steps, indices, outputs, field_arg, arrays):
    global pv
    import paraview.simple as simple
    pv = simple
    # Keep our cameras: without this the first pv.Render() resets them.
    pv._DisableFirstRenderCameraReset()
    try:
        return render_views(a, pvd, steps, indices, outputs, field_arg,
                            arrays)
    finally:
        # Delete the views while their OpenGL context is alive: left to the
        # interpreter's exit, the scalar bar releases its resources after the
        # context is gone and Xlib kills pvpython (GLXBadContext, status 1).
        for view in list(pv.GetViews()):
            pv.Delete(view)


def render_views(a, pvd, steps, indices, outputs, field_arg, arrays):
    pv.LoadPalette("WhiteBackground")
    units = vtp_point_units(steps[0][1])
    info = RunInfo(steps, a.bounds)
    size = a.size
    up = a.up or "z"
    if a.state:
        reader, display, view = load_state(a.state, pvd)
        view.ViewSize = list(size)
        refit_from_state(view, display, info, size, a.up)
        place_texts(view, size)
        field, comp = current_field(display)
        if field_arg:
            field, comp = field_arg, a.component
        if field is None:
            field, comp = DEFAULT_FIELD, a.component
            check_field(field, arrays, steps[0][1])
        if field_arg or a.colormap or display.ColorArrayName[1] != field:
            lut = color_by(display, view, field, comp, arrays.get(field, 1),
                           a.colormap, size, units.get(field))
        else:
            lut = pv.GetColorTransferFunction(field)
            # the unit of this run (a 2D state on a 3D run: Pa, not N/m)
            pv.GetScalarBar(lut, view).Title = legend_title(
                field, comp, arrays.get(field, 1), units.get(field))
        if field not in reader.PointData.keys():
            raise RenderError("no point array '%s' in this run; available "
                              "arrays: %s" % (field, ", ".join(
                                  sorted(reader.PointData.keys()))))
    else:
        field = field_arg or DEFAULT_FIELD
        comp = a.component
        # Walls split off only when the run has `kind`: otherwise the
        # pipeline is the plain one.
        reader, display, view = build_default(
            pvd, info, field, a.component, arrays[field],
            a.colormap or DEFAULT_COLORMAP, size, up,
            split=KIND_ARRAY in arrays, clip=a.clip, unit=units.get(field))
        lut = pv.GetColorTransferFunction(field)

    view.StillRender()
    scene = pv.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()

    def go_to(i):
        t = steps[i][0]
        scene.AnimationTime = t
        view.ViewTime = t
        reader.UpdatePipeline(t)

    set_color_range(display, lut, a, particle_source(reader), field, comp,
                    [steps[i][0] for i in indices])
    written = []
    for i, out in zip(indices, outputs):
        go_to(i)
        d = os.path.dirname(os.path.abspath(out))
        os.makedirs(d, exist_ok=True)
        pv.SaveScreenshot(out, view, ImageResolution=list(size),
                          TransparentBackground=0)
        if not os.path.isfile(out):
            raise RenderError("ParaView wrote no image to %s" % out)
        print("wrote %s (t = %g)" % (out, steps[i][0]))
        written.append(out)
    return written


def make_mp4(a, pvd, outputs):
    ffmpeg = shutil.which("ffmpeg")
    first = outputs[0]
    pattern = re.sub(r"_\d{5}\.png$", "_%05d.png", first)
    mp4 = a.mp4 or re.sub(r"_\d{5}\.png$", ".mp4", first)
    cmd = [ffmpeg, "-y", "-loglevel", "error", "-framerate", str(a.fps),
           "-start_number", "0", "-i", pattern,
           "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
           "-c:v", "libx264", "-pix_fmt", "yuv420p", mp4]
    r = subprocess.run(cmd)
    if r.returncode != 0 or not os.path.isfile(mp4):
        raise RenderError("ffmpeg failed (%s)" % " ".join(cmd))
    print("wrote %s" % mp4)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    a = parse_args(argv)
    try:
        pvd = find_pvd(a.run)
        steps = read_pvd(pvd)
        if a.state and not os.path.isfile(a.state):
            raise RenderError("no such state file: %s" % a.state)
        if a.state:
            a.state = os.path.abspath(a.state)
        arrays = vtp_point_arrays(steps[0][1])
        if a.field:
            check_field(a.field, arrays, steps[0][1])
        elif not a.state:
            check_field(DEFAULT_FIELD, arrays, steps[0][1])
        if a.mp4 is not None and not shutil.which("ffmpeg"):
            raise RenderError("--mp4 needs ffmpeg, which is not installed "
                              "(apt-get install ffmpeg); or render the "
                              "frames with --all and join them elsewhere")
        if a.clip and a.state:
            sys.stderr.write("render.py: note: --clip is ignored with "
                             "--state (the state decides)\n")
        indices = choose_steps(a, steps)
        outputs = output_paths(a, pvd, steps, indices)
        ensure_paraview(argv)
        written = render(a, pvd, steps, indices, outputs, a.field, arrays)
        if a.mp4 is not None:
            make_mp4(a, pvd, written)
    except RenderError as e:
        fail(str(e))
    return 0


if __name__ == "__main__":
    sys.exit(main())
