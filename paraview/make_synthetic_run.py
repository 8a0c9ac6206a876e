#!/usr/bin/env python3
"""Write a synthetic, sph-like output series (for testing the render scripts
without the simulator).

Follows the output contract of `sph run`: DIR/<name>.pvd plus one
DIR/<name>_NNNNN.vtp per output step (VTK XML PolyData, binary, zlib), one
vertex per particle, point data velocity/acceleration/density/pressure/mass/id
and field data TimeValue/step/smoothing_length/dimension/particle_spacing.

The particles form a dam-break-like water column in the lower-left of the unit
square (2D), or across the depth of the unit cube (3D, z up), that slumps to
the right over the steps.

With --walls, two layers of wall particles line the floor and the side walls
(inside the unit square / cube, the fluid is moved in by their thickness),
and the point array `kind` (int: 0 fluid, 1 wall) says which is which, as
sph will write once it has wall particles.  Wall particles get a pressure far
above the fluid's, so that a render which colours them by pressure shows it.
--no-kind leaves the array out (walls then look like fluid).

    /usr/bin/python3 paraview/make_synthetic_run.py OUT_DIR [--name dam_break]
        [--steps 5] [--dim 2] [--dx 0.02] [--walls [--no-kind]]
"""
import argparse
import os
import sys

try:
    from vtkmodules.vtkCommonCore import (vtkPoints, vtkDoubleArray,
                                          vtkIntArray, vtkTypeInt64Array)
    from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkCellArray
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
except ImportError:
    sys.exit("make_synthetic_run.py: needs VTK's Python modules; run it with "
             "/usr/bin/python3 (Debian's python3-paraview) or pvpython")


def write_step(path, pts, vel, rho, p, mass, ids, t, step, h, dim, dx,
               kind=None):
    poly = vtkPolyData()
    points = vtkPoints()
    points.SetDataTypeToDouble()
    verts = vtkCellArray()
    for i, x in enumerate(pts):
        points.InsertNextPoint(*x)
        verts.InsertNextCell(1)
        verts.InsertCellPoint(i)
    poly.SetPoints(points)
    poly.SetVerts(verts)

    def vec(name, data):
        a = vtkDoubleArray()
        a.SetName(name)
        a.SetNumberOfComponents(3)
        for v in data:
            a.InsertNextTuple3(*v)
        poly.GetPointData().AddArray(a)

    def scal(name, data, cls=vtkDoubleArray):
        a = cls()
        a.SetName(name)
        for v in data:
            a.InsertNextValue(v)
        return a

    vec("velocity", vel)
    vec("acceleration", [(0.0, -9.81, 0.0)] * len(pts))
    pd = poly.GetPointData()
    pd.AddArray(scal("density", rho))
    pd.AddArray(scal("pressure", p))
    pd.AddArray(scal("mass", mass))
    pd.AddArray(scal("id", ids, vtkTypeInt64Array))
    if kind is not None:
        pd.AddArray(scal("kind", kind, vtkIntArray))
    fd = poly.GetFieldData()
    fd.AddArray(scal("TimeValue", [t]))
    fd.AddArray(scal("step", [step], vtkTypeInt64Array))
    fd.AddArray(scal("smoothing_length", [h]))
    fd.AddArray(scal("dimension", [dim], vtkTypeInt64Array))
    fd.AddArray(scal("particle_spacing", [dx]))

    w = vtkXMLPolyDataWriter()
    w.SetFileName(path)
    w.SetInputData(poly)
    w.SetDataModeToBinary()
    w.SetCompressorTypeToZLib()
    if not w.Write():
        sys.exit("cannot write " + path)


def wall_points(dim, dx, layers=2):
    """Wall particles lining the floor and the side walls of the unit
    square / cube, `layers` deep, on the lattice (k + 1/2) dx."""
    m = int(round(1.0 / dx))
    up = 2 if dim == 3 else 1
    pts = []
    for idx in _lattice(dim, m):
        x = [(c + 0.5) * dx for c in idx]
        near = [min(c, m - 1 - c) < layers for c in idx]
        horizontal = [k for k in range(dim) if k != up]
        # floor, or a side wall (not the open top)
        if idx[up] < layers or any(near[k] for k in horizontal):
            pts.append(tuple(x) + (0.0,) * (3 - dim))
    return pts


def _lattice(dim, m):
    if dim == 2:
        return [(i, j) for j in range(m) for i in range(m)]
    return [(i, j, k) for k in range(m) for j in range(m) for i in range(m)]


def generate(out_dir, name="dam_break", steps=5, dim=2, dx=0.02,
             walls=False, kind=True):
    """Write the series; returns (path of the .pvd, steps, particles).
    walls: add wall particles (see the module docstring); kind: write the
    `kind` array (only with walls)."""
    os.makedirs(out_dir, exist_ok=True)
    rho0, g = 1000.0, 9.81
    width, height = 0.25, 0.5
    up = 2 if dim == 3 else 1            # z is up in 3D, y in 2D
    shift = 2 * dx if walls else 0.0     # fluid starts inside the walls
    nx, nup = int(round(width / dx)), int(round(height / dx))
    # 3D: the column spans the depth (y) of the box, so that a cut through
    # the middle (render.py --clip) goes through it.
    ndepth = int(round((1.0 - 2 * shift) / dx)) if dim == 3 else 1
    base = []
    for k in range(ndepth):
        for j in range(nup):
            for i in range(nx):
                x = (i + 0.5) * dx + shift
                u = (j + 0.5) * dx + shift
                if dim == 2:
                    base.append((x, u, 0.0))
                else:
                    base.append((x, (k + 0.5) * dx + shift, u))
    wall = wall_points(dim, dx) if walls else []
    n = len(base) + len(wall)
    mass = [rho0 * dx ** dim] * n
    ids = list(range(n))
    kinds = [0] * len(base) + [1] * len(wall) if walls and kind else None
    entries = []
    for s in range(steps):
        t = 0.05 * s
        f = s / max(1, steps - 1)        # 0 .. 1: column slumps
        pts, vel, rho, p = [], [], [], []
        for x in base:
            q = list(x)
            stretch = 1.0 + 2.0 * f * (1.0 - (x[up] - shift) / height)
            q[0] = shift + (x[0] - shift) * stretch
            q[up] = shift + (x[up] - shift) / (1.0 + f)
            pts.append(tuple(q))
            v = [q[0] - x[0], 0.0, 0.0]
            v[up] = q[up] - x[up]
            vel.append(tuple(v))
            hyd = rho0 * g * (height / (1.0 + f) - (q[up] - shift))
            p.append(hyd - 50.0)
            rho.append(rho0 * (1.0 + hyd / (rho0 * 100.0)))
        # walls: at rest, far above the fluid's pressure range
        pts += wall
        vel += [(0.0, 0.0, 0.0)] * len(wall)
        p += [20.0 * rho0 * g * height] * len(wall)
        rho += [1.1 * rho0] * len(wall)
        fname = "%s_%05d.vtp" % (name, s)
        write_step(os.path.join(out_dir, fname), pts, vel, rho, p, mass,
                   ids, t, 10 * s, 1.3 * dx, dim, dx, kinds)
        entries.append((t, fname))

    pvd = os.path.join(out_dir, name + ".pvd")
    with open(pvd, "w") as fh:
        fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" '
                 'version="0.1" byte_order="LittleEndian">\n  <Collection>\n')
        for t, fname in entries:
            fh.write('    <DataSet timestep="%.17g" group="" part="0" '
                     'file="%s"/>\n' % (t, fname))
        fh.write('  </Collection>\n</VTKFile>\n')
    return pvd, steps, n


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir")
    ap.add_argument("--name", default="dam_break")
    ap.add_argument("--steps", type=int, default=5)
    ap.add_argument("--dim", type=int, choices=(2, 3), default=2)
    ap.add_argument("--dx", type=float, default=0.02)
    ap.add_argument("--walls", action="store_true",
                    help="add wall particles and the kind array")
    ap.add_argument("--no-kind", action="store_true",
                    help="with --walls: leave the kind array out")
    a = ap.parse_args()
    _, steps, n = generate(a.out_dir, a.name, a.steps, a.dim, a.dx,
                           a.walls, not a.no_kind)
    print("wrote %d steps of %d particles to %s" % (steps, n, a.out_dir))


if __name__ == "__main__":
    main()
