#include "sph/io/vtp_io.hpp"

#include "sph/io/atomic_file.hpp"
#include "sph/io/plane_vector_array.hpp"
#include "sph/io/snapshot_polydata.hpp"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <malloc.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <utility>
#include <stdexcept>
#include <type_traits>

namespace sph {
namespace {

// The first n entries of a field (the owned particles: ghosts are never
// written). borrow: the array points at the field's own storage instead of
// a copy (the writer's polydata, which dies before the field changes; not
// for Catalyst, whose pipeline may keep it), where the layout allows it:
// scalars, integers and 3D vectors; 2D vectors (and positions) through a
// view that adds the zero third component (plane_vector_array.hpp). A copy
// of every array at once was about 150 bytes per particle in 3D and 100 in
// 2D on top of the run's arrays at each snapshot.
template <class Array, class T>
vtkSmartPointer<Array> borrowed(const char* name, const T* values, std::size_t n, int components) {
  using V = std::remove_pointer_t<decltype(std::declval<Array>().GetPointer(0))>;
  static_assert(sizeof(T) % sizeof(V) == 0, "a whole number of VTK values per entry");
  auto arr = vtkSmartPointer<Array>::New();
  arr->SetName(name);
  arr->SetNumberOfComponents(components);
  // save = 1: VTK never frees or writes the particles' storage.
  arr->SetArray(const_cast<V*>(reinterpret_cast<const V*>(values)), static_cast<vtkIdType>(n) * components, 1);
  return arr;
}

template <int D>
vtkSmartPointer<vtkDataArray> vectorArray(const char* name, const std::vector<Vec<D>>& v, std::size_t n,
                                          bool borrow) {
  static_assert(sizeof(Vec<D>) == D * sizeof(double), "vectors stored as D contiguous doubles");
  if (borrow && D == 3) return borrowed<vtkDoubleArray>(name, v.data(), n, 3);
  if (borrow && D == 2) {
    auto view = vtkSmartPointer<PlaneVectorArray>::New();
    view->SetName(name);
    view->View(reinterpret_cast<const double*>(v.data()), static_cast<vtkIdType>(n));
    return view;
  }
  auto arr = vtkSmartPointer<vtkDoubleArray>::New();
  arr->SetName(name);
  arr->SetNumberOfComponents(3);
  arr->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) {
    double t[3] = {0, 0, 0};
    for (int d = 0; d < D; ++d) t[d] = v[i][d];
    arr->SetTypedTuple(static_cast<vtkIdType>(i), t);
  }
  return arr;
}

// Scalars in the type they are stored in: Float64, or Float32 for a
// mixed-precision build's narrow fields (sph::Narrow, types.hpp).
template <class T>
vtkSmartPointer<vtkDataArray> scalarArray(const char* name, const std::vector<T>& s, std::size_t n,
                                          bool borrow = false) {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, float>);
  using Array = std::conditional_t<std::is_same_v<T, double>, vtkDoubleArray, vtkFloatArray>;
  if (borrow) return borrowed<Array>(name, s.data(), n, 1);
  auto arr = vtkSmartPointer<Array>::New();
  arr->SetName(name);
  arr->SetNumberOfValues(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) arr->SetValue(static_cast<vtkIdType>(i), s[i]);
  return arr;
}

// Integer fields: id as Int64, kind as UInt8.
template <class T>
vtkSmartPointer<vtkDataArray> integerArray(const char* name, const std::vector<T>& s, std::size_t n, bool borrow) {
  using Array = std::conditional_t<std::is_same_v<T, std::uint8_t>, vtkUnsignedCharArray, vtkTypeInt64Array>;
  static_assert(sizeof(T) == sizeof(typename Array::ValueType));
  if (borrow) return borrowed<Array>(name, s.data(), n, 1);
  auto arr = vtkSmartPointer<Array>::New();
  arr->SetName(name);
  arr->SetNumberOfValues(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) arr->SetValue(static_cast<vtkIdType>(i), s[i]);
  return arr;
}

// One vertex cell per point: offsets 0..n, connectivity 0..n-1. In 32-bit
// integers when n allows (the writer then keeps them as they are, Int32 in
// the file, and copies n offsets of 4 bytes, not 8: peak RSS of a 1-step
// run per added particle 186.9 -> 181.2 B in 2D, 254.3 -> 250.7 in 3D).
// shareBuffer: the connectivity is the offsets' first n entries, a view
// that lives only as long as the offsets array (the file writers, whose
// polydata dies at once); else an array of its own (Catalyst, whose
// pipeline may keep the connectivity alone).
template <class Array>
void vertexCells(vtkCellArray* verts, vtkIdType n, bool shareBuffer) {
  vtkNew<Array> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, static_cast<typename Array::ValueType>(i));
  if (shareBuffer) {
    connectivity->SetArray(offsets->GetPointer(0), n, 1);
  } else {
    connectivity->SetNumberOfValues(n);
    std::copy(offsets->GetPointer(0), offsets->GetPointer(0) + n, connectivity->GetPointer(0));
  }
  verts->SetData(offsets, connectivity);
}

void addFieldValue(vtkFieldData* fd, const char* name, double value) {
  vtkNew<vtkDoubleArray> arr;
  arr->SetName(name);
  arr->SetNumberOfValues(1);
  arr->SetValue(0, value);
  fd->AddArray(arr);
}

void addFieldValue(vtkFieldData* fd, const char* name, long long value) {
  vtkNew<vtkTypeInt64Array> arr;
  arr->SetName(name);
  arr->SetNumberOfValues(1);
  arr->SetValue(0, value);
  fd->AddArray(arr);
}


// zlib allocates ~300 KB per compressed block; above glibc's mmap threshold
// each block then costs an mmap, page faults and an munmap with TLB
// shoot-downs (18 ms per 2k-particle snapshot, 4x the stepping). Serving
// such buffers from the heap, and not trimming it, removes that.
void keepCompressionBuffersOnHeap() {
  static const bool once = [] {
    mallopt(M_MMAP_THRESHOLD, 64 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
    return true;
  }();
  (void)once;
}

}  // namespace

template <int D>
vtkSmartPointer<vtkPolyData> snapshotPolyData(const Particles<D>& P, const SnapshotInfo& info, bool borrow) {
  const auto n = static_cast<vtkIdType>(P.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  if (borrow) {
    points->SetData(vectorArray<D>("Points", P.x, P.size(), borrow));
  } else {
    points->SetNumberOfPoints(n);
    for (vtkIdType i = 0; i < n; ++i) {
      double t[3] = {0, 0, 0};
      for (int d = 0; d < D; ++d) t[d] = P.x[static_cast<std::size_t>(i)][d];
      points->SetPoint(i, t);
    }
  }
  vtkNew<vtkCellArray> verts;
  if (n < INT32_MAX) vertexCells<vtkTypeInt32Array>(verts, n, borrow);
  else vertexCells<vtkTypeInt64Array>(verts, n, borrow);

  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetVerts(verts);
  // Every allocated field of the table that has a snapshot name, with its unit.
  vtkPointData* pd = poly->GetPointData();
  P.forEachField([&](const FieldInfo& f, const auto& field) {
    if (f.vtkName == nullptr || field.empty()) return;
    using T = typename std::decay_t<decltype(field)>::value_type;
    vtkSmartPointer<vtkDataArray> arr;
    const std::size_t owned = P.size();
    if constexpr (std::is_same_v<T, Vec<D>>) arr = vectorArray<D>(f.vtkName, field, owned, borrow);
    else if constexpr (std::is_floating_point_v<T>) arr = scalarArray(f.vtkName, field, owned, borrow);
    else if constexpr (std::is_integral_v<T>) arr = integerArray(f.vtkName, field, owned, borrow);
    else static_assert(std::is_same_v<T, Mat<D>>, "a field type the writer does not know");
    if (!arr) return;
    arr->GetInformation()->Set(vtkDataArray::UNITS_LABEL(), f.unit(D));
    pd->AddArray(arr);
  });
  pd->SetActiveScalars("pressure");

  vtkFieldData* fd = poly->GetFieldData();
  addFieldValue(fd, "TimeValue", info.time);
  addFieldValue(fd, "step", static_cast<long long>(info.step));
  addFieldValue(fd, "smoothing_length", info.smoothingLength);
  addFieldValue(fd, "dimension", static_cast<long long>(D));
  addFieldValue(fd, "particle_spacing", info.particleSpacing);
  for (const auto& [name, values] : {std::pair<const char*, const std::vector<Real>&>{"domain_min", info.domainMin},
                                     {"domain_max", info.domainMax}}) {
    if (values.empty()) continue;
    fd->AddArray(scalarArray(name, values, values.size()));
  }
  return poly;
}

template <int D>
void writeVtp(const std::string& path, const Particles<D>& P, const SnapshotInfo& info) {
  keepCompressionBuffersOnHeap();
  const vtkSmartPointer<vtkPolyData> poly = snapshotPolyData<D>(P, info, /*borrow=*/true);
  vtkNew<vtkXMLPolyDataWriter> writer;
  const std::string tmp = temporaryName(path);
  writer->SetFileName(tmp.c_str());
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();  // raw binary after the XML header
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  writer->SetCompressionLevel(1);  // doubles barely compress harder; level 1 is 3x faster
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path);
  }
  commitTemporary(path);
}

template vtkSmartPointer<vtkPolyData> snapshotPolyData<2>(const Particles<2>&, const SnapshotInfo&, bool);
template vtkSmartPointer<vtkPolyData> snapshotPolyData<3>(const Particles<3>&, const SnapshotInfo&, bool);
template void writeVtp<2>(const std::string&, const Particles<2>&, const SnapshotInfo&);
template void writeVtp<3>(const std::string&, const Particles<3>&, const SnapshotInfo&);

}  // namespace sph
