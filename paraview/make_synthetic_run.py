#!/usr/bin/env python3
"""Write a synthetic, sph-like output series (for testing the render scripts
without the simulator).

Follows the output contract of `sph run`: DIR/<name>.pvd plus one
DIR/<name>_NNNNN.vtp per output step (VTK XML PolyData, binary, zlib), one
vertex per particle, point data velocity/acceleration/density/pressure/mass/id
and field data TimeValue/step/smoothing_length/dimension/particle_spacing.

The particles form a dam-break-like water column in the lower-left of the unit
square (2D) or unit cube (3D) that slumps to the right over the steps.

    /usr/bin/python3 paraview/make_synthetic_run.py OUT_DIR [--name dam_break]
        [--steps 5] [--dim 2] [--dx 0.02]
"""
import argparse
import os
import sys

try:
    from vtkmodules.vtkCommonCore import (vtkPoints, vtkDoubleArray,
                                          vtkTypeInt64Array)
    from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkCellArray
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
except ImportError:
    sys.exit("make_synthetic_run.py: needs VTK's Python modules; run it with "
             "/usr/bin/python3 (Debian's python3-paraview) or pvpython")


def write_step(path, pts, vel, rho, p, mass, ids, t, step, h, dim, dx):
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


def generate(out_dir, name="dam_break", steps=5, dim=2, dx=0.02):
    """Write the series; returns the path of the .pvd."""
    os.makedirs(out_dir, exist_ok=True)
    rho0, g = 1000.0, 9.81
    width, height = 0.25, 0.5
    nx, ny = int(round(width / dx)), int(round(height / dx))
    nz = nx if dim == 3 else 1
    base = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                z = (k + 0.5) * dx if dim == 3 else 0.0
                base.append(((i + 0.5) * dx, (j + 0.5) * dx, z))
    n = len(base)
    mass = [rho0 * dx ** dim] * n
    ids = list(range(n))
    up = 2 if dim == 3 else 1
    entries = []
    for s in range(steps):
        t = 0.05 * s
        f = s / max(1, steps - 1)        # 0 .. 1: column slumps
        pts, vel, rho, p = [], [], [], []
        for x in base:
            q = list(x)
            stretch = 1.0 + 2.0 * f * (1.0 - x[up] / height)
            q[0] = x[0] * stretch
            q[up] = x[up] / (1.0 + f)
            pts.append(tuple(q))
            vel.append((q[0] - x[0], q[up] - x[up], 0.0))
            hyd = rho0 * g * (height / (1.0 + f) - q[up])
            p.append(hyd - 50.0)
            rho.append(rho0 * (1.0 + hyd / (rho0 * 100.0)))
        fname = "%s_%05d.vtp" % (name, s)
        write_step(os.path.join(out_dir, fname), pts, vel, rho, p, mass,
                   ids, t, 10 * s, 1.3 * dx, dim, dx)
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
    a = ap.parse_args()
    _, steps, n = generate(a.out_dir, a.name, a.steps, a.dim, a.dx)
    print("wrote %d steps of %d particles to %s" % (steps, n, a.out_dir))


if __name__ == "__main__":
    main()
