// The particles of one snapshot as a vtkPolyData: what a .vtp file holds
// (sph/io/vtp_io.hpp lists the arrays) and what Catalyst is handed
// (sph/io/catalyst.hpp), built by this one function so that the two agree
// array for array. Every point array carries its SI unit as the
// vtkDataArray::UNITS_LABEL information key, from the field table
// (fields.hpp): per unit depth in 2D (density kg/m^2, pressure N/m).
// borrow: arrays point at the particles' storage where the layout allows
// (scalars, integers, 3D vectors) instead of copies; only for a polydata
// that dies before the particles change (the .vtp writer).
#pragma once

#include "sph/io/vtp_io.hpp"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace sph {

template <int D>
vtkSmartPointer<vtkPolyData> snapshotPolyData(const Particles<D>& P, const SnapshotInfo& info, bool borrow = false);

}  // namespace sph
