// The .pvtp summary (pvtp_io.hpp), written by VTK's vtkXMLPPolyDataWriter
// to a string, then to its file atomically. VTK's writer also writes the
// pieces, non-atomically and each from the process that holds it; sph's
// pieces are written by writeVtp on their own ranks before the summary, so
// a writer that only writes the summary is VTK's with WritePiece() a no-op
// that reports success (the summary lists the pieces reported written).
#include "sph/io/pvtp_io.hpp"

#include "sph/io/atomic_file.hpp"
#include "sph/io/snapshot_polydata.hpp"

#include <vtkDataArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataWriter.h>

#include <filesystem>
#include <stdexcept>

namespace sph {
namespace {

class SummaryOnlyWriter : public vtkXMLPPolyDataWriter {
 public:
  static SummaryOnlyWriter* New();
  vtkTypeMacro(SummaryOnlyWriter, vtkXMLPPolyDataWriter)

 protected:
  int WritePiece(int) override { return 1; }  // the pieces exist already
};
vtkStandardNewMacro(SummaryOnlyWriter);

}  // namespace

std::string pvtpPieceName(const std::string& pvtpPath, int rank) {
  return std::filesystem::path(pvtpPath).stem().string() + "_" + std::to_string(rank) + ".vtp";
}

template <int D>
void writePvtpSummary(const std::string& pvtpPath, const Particles<D>& P, const SnapshotInfo& info, int pieces) {
  if (pieces < 1) throw std::logic_error("writePvtpSummary: pieces must be >= 1");
  vtkSmartPointer<vtkPolyData> poly = snapshotPolyData<D>(P, info, /*borrow=*/true);
  if (poly->GetNumberOfPoints() == 0) {
    // VTK's writer lists no piece for an empty data set (a rank 0 that owns
    // no particle): the summary is made from one zero point with the same
    // arrays (it holds their names and types, never their values).
    auto one = vtkSmartPointer<vtkPolyData>::New();
    one->DeepCopy(poly);
    if (!one->GetPoints()) one->SetPoints(vtkSmartPointer<vtkPoints>::New());
    one->GetPoints()->GetData()->SetNumberOfComponents(3);
    one->GetPoints()->SetDataTypeToDouble();
    one->GetPoints()->SetNumberOfPoints(1);
    one->GetPoints()->SetPoint(0, 0.0, 0.0, 0.0);
    vtkPointData* arrays = one->GetPointData();
    for (int k = 0; k < arrays->GetNumberOfArrays(); ++k) {
      vtkDataArray* array = arrays->GetArray(k);
      if (!array) continue;
      array->SetNumberOfTuples(1);
      for (int c = 0; c < array->GetNumberOfComponents(); ++c) array->SetComponent(0, c, 0.0);
    }
    poly = one;
  }
  vtkNew<SummaryOnlyWriter> writer;
  // Rank 0 alone writes the summary: no controller (Catalyst on several
  // ranks sets VTK's global one to MPI, whose writer would wait for the
  // other ranks).
  writer->SetController(nullptr);
  writer->SetFileName(pvtpPath.c_str());  // names the pieces; the text goes to a string
  writer->SetInputData(poly);
  writer->SetNumberOfPieces(pieces);
  writer->SetStartPiece(0);
  writer->SetEndPiece(pieces - 1);
  writer->SetGhostLevel(0);
  writer->SetDataModeToBinary();  // the field data inline (base64): exact, and one file
  writer->SetWriteToOutputString(1);
  if (writer->Write() != 1 || writer->GetErrorCode() != 0) throw std::runtime_error("cannot write " + pvtpPath);
  writeFileAtomically(pvtpPath, writer->GetOutputString());
}

template void writePvtpSummary<2>(const std::string&, const Particles<2>&, const SnapshotInfo&, int);
template void writePvtpSummary<3>(const std::string&, const Particles<3>&, const SnapshotInfo&, int);

}  // namespace sph
