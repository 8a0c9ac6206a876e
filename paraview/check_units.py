#!/usr/bin/env pvpython
"""Check the units of the point arrays of sph's particle files, as ParaView
reads them.

    pvpython paraview/check_units.py FILE.vtp [FILE.vtp ...]

Each file is opened with ParaView's XML PolyData reader (paraview.simple),
fetched, and every point array must carry the UNITS_LABEL information key
with the SI unit below, for the file's `dimension` (field data). In 2D the
quantities are per unit depth: a particle is a prism 1 m deep, so its mass
is in kg (rho0 [kg/m^2] times dx^2 [m^2]), its density in kg/m^2 (mass per
area of the plane) and its pressure in N/m (force per length of a line).
The table is written here from those definitions, not taken from sph's
field table (include/sph/fields.hpp), so that the two are checked against
each other. "1": dimensionless (a count, a label, a colour function).

Prints one line per array; exit status 0 when every array of every file
has its unit, 1 otherwise.
"""
import sys
sys.dont_write_bytecode = True

EXPECTED = {
    3: {"velocity": "m/s", "acceleration": "m/s^2", "density": "kg/m^3",
        "density_rate": "kg/m^3/s", "pressure": "Pa", "mass": "kg",
        "id": "1", "kind": "1", "xsph_velocity": "m/s", "colour": "1",
        "colour_normal": "1/m", "curvature": "1/m", "list_build_position": "m",
        "velocity_previous": "m/s", "density_previous": "kg/m^3"},
    2: {"velocity": "m/s", "acceleration": "m/s^2", "density": "kg/m^2",
        "density_rate": "kg/m^2/s", "pressure": "N/m", "mass": "kg",
        "id": "1", "kind": "1", "xsph_velocity": "m/s", "colour": "1",
        "colour_normal": "1/m", "curvature": "1/m", "list_build_position": "m",
        "velocity_previous": "m/s", "density_previous": "kg/m^2"},
}


def check(path):
    import paraview.simple as pv
    from paraview import servermanager
    reader = pv.XMLPolyDataReader(FileName=[path])
    reader.UpdatePipeline()
    data = servermanager.Fetch(reader)
    pv.Delete(reader)
    fd = data.GetFieldData().GetArray("dimension")
    if fd is None:
        print("%s: FAIL: no field data `dimension`" % path)
        return False
    dim = int(fd.GetValue(0))
    pd = data.GetPointData()
    ok = pd.GetNumberOfArrays() > 0
    for k in range(pd.GetNumberOfArrays()):
        arr = pd.GetAbstractArray(k)
        name = arr.GetName()
        info = arr.GetInformation()
        unit = info.Get(arr.UNITS_LABEL()) if info.Has(arr.UNITS_LABEL()) \
            else None
        want = EXPECTED[dim].get(name)
        good = want is not None and unit == want
        ok = ok and good
        print("%s: %dD %-14s %-10s %s" % (
            path, dim, name, unit, "ok" if good else
            "FAIL (expected %s)" % (want or "an array of the table")))
    return ok


def main(argv):
    if not argv:
        sys.exit(__doc__)
    results = [check(p) for p in argv]
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
