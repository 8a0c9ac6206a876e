// A 2D vector field shown to VTK as 3-component tuples (x, y, 0), without a
// copy: the snapshot writer's view of a run's positions and 2D vectors.
//
// VTK's points and vectors have 3 components; a 2D run stores 2. A padded
// copy of every vector field at once cost 24 bytes per particle and field
// at each snapshot (points, velocity, acceleration, list build position:
// about 100 bytes per particle in 2D, more than the neighbour list). VTK's
// XML writer reads an array that is not a plain contiguous one block by block
// through its value accessors (vtkXMLWriter's generic path for a
// vtkGenericDataArray, documented in vtkGenericDataArray.h), so the view
// costs a block of 32 KiB, not a copy.
//
// Read-only: the setters refuse, and so does growing it (the writer never
// calls them; growing throws std::bad_alloc, VTK's answer to a failed
// allocation). NewInstance() gives a plain vtkDoubleArray, so a filter that copies
// the array gets an ordinary one. The field must outlive the view and not
// change while VTK reads it (the writer's polydata dies before the step
// goes on).
#pragma once

#include <vtkGenericDataArray.h>
#include <vtkObjectFactory.h>

#include <array>

namespace sph {

class PlaneVectorArray : public vtkGenericDataArray<PlaneVectorArray, double> {
  using GenericDataArrayType = vtkGenericDataArray<PlaneVectorArray, double>;
  friend class vtkGenericDataArray<PlaneVectorArray, double>;

 public:
  // NewInstance(): a vtkDataArray, the plain vtkDoubleArray of
  // vtkAOSArrayNewInstanceMacro.
  vtkAbstractTypeMacroWithNewInstanceType(PlaneVectorArray, GenericDataArrayType, vtkDataArray, "PlaneVectorArray")
  vtkAOSArrayNewInstanceMacro(PlaneVectorArray)
  static PlaneVectorArray* New() { VTK_STANDARD_NEW_BODY(PlaneVectorArray); }

  // Show `tuples` 2D vectors starting at xy (x0, y0, x1, y1, ...).
  void View(const double* xy, vtkIdType tuples) {
    xy_ = xy;
    this->SetNumberOfComponents(3);  // (also sizes GetTuple()'s buffer)
    this->Size = 3 * tuples;
    this->MaxId = this->Size - 1;
    this->DataChanged();
    this->Modified();
  }

  double GetValue(vtkIdType valueIdx) const {
    return GetTypedComponent(valueIdx / 3, static_cast<int>(valueIdx % 3));
  }
  void GetTypedTuple(vtkIdType tupleIdx, double* tuple) const {
    tuple[0] = xy_[2 * tupleIdx];
    tuple[1] = xy_[2 * tupleIdx + 1];
    tuple[2] = 0.0;
  }
  double GetTypedComponent(vtkIdType tupleIdx, int comp) const { return comp < 2 ? xy_[2 * tupleIdx + comp] : 0.0; }

  void SetValue(vtkIdType, double) { refuse(); }
  void SetTypedTuple(vtkIdType, const double*) { refuse(); }
  void SetTypedComponent(vtkIdType, int, double) { refuse(); }

 protected:
  PlaneVectorArray() = default;
  ~PlaneVectorArray() override = default;

  bool AllocateTuples(vtkIdType tuples) { return tuples == 0; }
  bool ReallocateTuples(vtkIdType tuples) { return tuples * 3 == this->Size; }

 private:
  void refuse() { vtkErrorMacro("PlaneVectorArray is a read-only view of a 2D field"); }

  const double* xy_ = nullptr;

  PlaneVectorArray(const PlaneVectorArray&) = delete;
  void operator=(const PlaneVectorArray&) = delete;
};

}  // namespace sph
