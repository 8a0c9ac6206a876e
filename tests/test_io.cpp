// Output files: .vtp round trip through VTK's reader, the .pvd series read
// with VTK's XML parser and readers, energy.csv, and continuing a run from a .vtp.
#include "pvd_reader.hpp"
#include "test_support.hpp"

#include "sph/io/plane_vector_array.hpp"
#include "sph/io/pvtp_io.hpp"
#include "sph/io/snapshot_polydata.hpp"
#include "sph/io/vtp_io.hpp"
#include "sph/particle_sources.hpp"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdlib>

using namespace sph;

namespace {

// A snapshot of the default dam break after 2 steps (fluid and dummy walls,
// continuity density: velocities, densities and rates all non-trivial).
std::string damBreakSnapshot(const std::filesystem::path& dir) {
  const auto r = test::runSph({"run", test::caseFile("dam_break"), "--output", (dir / "run").string(), "--end_time",
                               "0.0001", "--output_every", "2", "--threads", "1", "--no-progress"});
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  return (dir / "run" / "dam_break_00001.vtp").string();
}

// Every value sph reads, bit for bit.
void expectSame(const VtpParticles& a, const VtpParticles& b, const std::string& what) {
  BOOST_TEST_CONTEXT(what) {
    BOOST_TEST_REQUIRE(a.x.size() == b.x.size());
    BOOST_TEST(a.x == b.x);
    BOOST_TEST(a.hasVelocity == b.hasVelocity);
    BOOST_TEST(a.v == b.v);
    BOOST_TEST(a.m == b.m);
    BOOST_TEST(a.id == b.id);
    BOOST_TEST(a.rho == b.rho);
    BOOST_TEST(a.drho == b.drho);
    BOOST_TEST(a.a == b.a);
    BOOST_TEST(a.kind == b.kind);
    BOOST_TEST(a.time == b.time);
    BOOST_TEST(a.step == b.step);
  }
}

// Particles with every value distinct (fluid and walls, a field of each
// type the writer handles: vectors, scalars, id, kind, and xList).
template <int D>
Particles<D> distinctParticles(std::size_t n, std::size_t fluid) {
  Particles<D> P;
  P.x.resize(n);
  P.resize(n, fluid);
  P.allocate(fieldBit(kFieldDrho) | fieldBit(kFieldXList));
  for (std::size_t i = 0; i < n; ++i) {
    const Real s = static_cast<Real>(i) + 0.25;
    for (int d = 0; d < D; ++d) {
      P.x[i][d] = s + 0.1 * d;
      P.v[i][d] = -s - 0.2 * d;
      P.a[i][d] = 3 * s + d;
      P.xList[i][d] = s * s + d;
    }
    P.rho[i] = 1000 + s;
    P.drho[i] = -s;
    P.p[i] = 7 * s;
    P.m[i] = 0.5 + s;
    P.id[i] = static_cast<std::int64_t>(n - i);
  }
  return P;
}

// The polydata with arrays borrowed from the particles (the .vtp writer's)
// holds exactly what the one with copies (Catalyst's) holds: the same
// arrays, names, types, components and values, the same points and
// vertices. A mistake in the borrowing (count, components, type) shows here.
template <int D>
void expectBorrowedEqualsCopied() {
  const Particles<D> P = distinctParticles<D>(37, 30);
  const SnapshotInfo info{0.5, 3, 0.01, 0.0075, {0, 0}, {1, 1}};
  const vtkSmartPointer<vtkPolyData> copied = snapshotPolyData<D>(P, info, false);
  const vtkSmartPointer<vtkPolyData> borrowed = snapshotPolyData<D>(P, info, true);
  const auto sameArray = [](vtkDataArray* a, vtkDataArray* b, const std::string& name) {
    BOOST_TEST_CONTEXT(name) {
      BOOST_TEST_REQUIRE(a != nullptr);
      BOOST_TEST_REQUIRE(b != nullptr);
      BOOST_TEST(a->GetDataType() == b->GetDataType());
      BOOST_TEST(a->GetNumberOfComponents() == b->GetNumberOfComponents());
      BOOST_TEST_REQUIRE(a->GetNumberOfTuples() == b->GetNumberOfTuples());
      for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
        for (int c = 0; c < a->GetNumberOfComponents(); ++c)
          BOOST_TEST(a->GetComponent(i, c) == b->GetComponent(i, c));
    }
  };
  BOOST_TEST_REQUIRE(copied->GetNumberOfPoints() == 37);
  sameArray(copied->GetPoints()->GetData(), borrowed->GetPoints()->GetData(), "Points");
  sameArray(copied->GetVerts()->GetOffsetsArray(), borrowed->GetVerts()->GetOffsetsArray(), "offsets");
  sameArray(copied->GetVerts()->GetConnectivityArray(), borrowed->GetVerts()->GetConnectivityArray(), "connectivity");
  vtkPointData* a = copied->GetPointData();
  vtkPointData* b = borrowed->GetPointData();
  BOOST_TEST_REQUIRE(a->GetNumberOfArrays() == b->GetNumberOfArrays());
  BOOST_TEST(a->GetNumberOfArrays() == 9);  // velocity ... kind, list_build_position
  for (int k = 0; k < a->GetNumberOfArrays(); ++k) {
    const std::string name = a->GetArrayName(k);
    BOOST_TEST(name == b->GetArrayName(k));
    sameArray(a->GetArray(k), b->GetArray(name.c_str()), name);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(io)

BOOST_AUTO_TEST_CASE(borrowed_snapshot_arrays_equal_copies_2d) { expectBorrowedEqualsCopied<2>(); }
BOOST_AUTO_TEST_CASE(borrowed_snapshot_arrays_equal_copies_3d) { expectBorrowedEqualsCopied<3>(); }

// The 2D writer's view of a vector field (x, y, 0): VTK's XML writer reads
// it block by block through its accessors (32 KiB blocks: 5000 particles are
// 15000 values, four blocks and a partial one), so a file written through it
// holds the values a copy holds, every block's and the last partial one's.
// The view cannot be written to, and a copy of it is an ordinary array.
BOOST_AUTO_TEST_CASE(plane_vector_view_writes_what_a_copy_writes) {
  const std::size_t n = 5000;
  const Particles<2> P = distinctParticles<2>(n, n - 300);
  const auto dir = test::scratchDir("plane_view");
  const std::string path = (dir / "view.vtp").string();
  writeVtp<2>(path, P, SnapshotInfo{0.5, 3, 0.01, 0.0075, {0, 0}, {1, 1}});
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  BOOST_TEST_REQUIRE(poly->GetNumberOfPoints() == static_cast<vtkIdType>(n));
  vtkDataArray* points = poly->GetPoints()->GetData();
  vtkPointData* pd = poly->GetPointData();
  BOOST_TEST(points->GetDataType() == VTK_DOUBLE);
  std::size_t wrong = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<vtkIdType>(k);
    for (int c = 0; c < 3; ++c) {
      const double x = c < 2 ? P.x[k][c] : 0.0, v = c < 2 ? P.v[k][c] : 0.0, a = c < 2 ? P.a[k][c] : 0.0,
                   xl = c < 2 ? P.xList[k][c] : 0.0;
      wrong += points->GetComponent(i, c) != x;
      wrong += pd->GetArray("velocity")->GetComponent(i, c) != v;
      wrong += pd->GetArray("acceleration")->GetComponent(i, c) != a;
      wrong += pd->GetArray("list_build_position")->GetComponent(i, c) != xl;
    }
  }
  BOOST_TEST(wrong == 0u);

  vtkNew<PlaneVectorArray> view;
  view->View(reinterpret_cast<const double*>(P.v.data()), static_cast<vtkIdType>(n));
  BOOST_TEST(view->GetNumberOfTuples() == static_cast<vtkIdType>(n));
  BOOST_TEST(view->GetNumberOfComponents() == 3);
  const double before = view->GetComponent(7, 1);
  BOOST_TEST(before == P.v[7][1]);
  // (GetTuple writes 3 values into a buffer the view must size for 3: a
  // smaller one overflowed, which only AddressSanitizer sees; the values.)
  const double* tuple = view->GetTuple(n - 1);
  BOOST_TEST(tuple[0] == P.v[n - 1][0]);
  BOOST_TEST(tuple[1] == P.v[n - 1][1]);
  BOOST_TEST(tuple[2] == 0.0);
  view->GlobalWarningDisplayOff();
  view->SetComponent(7, 1, 123.0);  // refused: the particles' storage is never written
  view->GlobalWarningDisplayOn();
  BOOST_TEST(P.v[7][1] == before);
  vtkSmartPointer<vtkDataArray> copy = vtk::TakeSmartPointer(view->NewInstance());
  BOOST_TEST(vtkDoubleArray::SafeDownCast(copy) != nullptr);
  copy->DeepCopy(view);
  BOOST_TEST(copy->GetNumberOfTuples() == static_cast<vtkIdType>(n));
  BOOST_TEST(copy->GetComponent(n - 1, 0) == P.v[n - 1][0]);
  BOOST_TEST(copy->GetComponent(n - 1, 2) == 0.0);
}

BOOST_AUTO_TEST_CASE(vtp_round_trip_keeps_count_arrays_and_values) {
  const auto dir = test::scratchDir("vtp");
  std::vector<Vec<2>> x;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 7; ++j) x.push_back(Vec<2>(0.2 + 0.0075 * i, 0.3 + 0.0075 * j));
  auto s = test::makeScene<2>(x, {}, SeedWcsphParameters{}, true, 1e-4);
  for (int n = 0; n < 5; ++n) BOOST_REQUIRE(!s.step());
  const auto& P = s.particles();
  const std::string path = (dir / "snap.vtp").string();
  writeVtp<2>(path, P, SnapshotInfo{s.time(), s.stepIndex(), 0.01, 0.0075, {0, 0}, {1, 1}});
  BOOST_TEST(!std::filesystem::exists(path + ".tmp"));

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  BOOST_TEST_REQUIRE(poly->GetNumberOfPoints() == static_cast<vtkIdType>(P.size()));
  BOOST_TEST(poly->GetNumberOfVerts() == static_cast<vtkIdType>(P.size()));
  vtkPointData* pd = poly->GetPointData();
  for (const char* name : {"velocity", "acceleration", "density", "pressure", "mass", "id"})
    BOOST_TEST(pd->GetArray(name) != nullptr, "missing array " << name);
  BOOST_TEST(pd->GetArray("velocity")->GetNumberOfComponents() == 3);
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    double xi[3];
    poly->GetPoint(i, xi);
    BOOST_TEST(xi[0] == P.x[k][0]);
    BOOST_TEST(xi[1] == P.x[k][1]);
    BOOST_TEST(xi[2] == 0.0);
    BOOST_TEST(pd->GetArray("velocity")->GetComponent(i, 1) == P.v[k][1]);
    BOOST_TEST(pd->GetArray("acceleration")->GetComponent(i, 0) == P.a[k][0]);
    BOOST_TEST(pd->GetArray("density")->GetTuple1(i) == P.rho[k]);
    BOOST_TEST(pd->GetArray("pressure")->GetTuple1(i) == P.p[k]);
    BOOST_TEST(pd->GetArray("mass")->GetTuple1(i) == P.m[k]);
    BOOST_TEST(pd->GetArray("id")->GetTuple1(i) == static_cast<double>(P.id[k]));
  }
  vtkFieldData* fd = poly->GetFieldData();
  BOOST_TEST(fd->GetArray("TimeValue")->GetTuple1(0) == s.time());
  BOOST_TEST(fd->GetArray("step")->GetTuple1(0) == 5.0);
  BOOST_TEST(fd->GetArray("dimension")->GetTuple1(0) == 2.0);
  BOOST_TEST(fd->GetArray("domain_max")->GetNumberOfTuples() == 2);
  BOOST_TEST(fd->GetArray("domain_max")->GetTuple1(1) == 1.0);

  // And back through sph's own reader.
  const VtpParticles back = readVtp(path);
  BOOST_TEST(back.x.size() == P.size());
  BOOST_TEST(back.m.size() == P.size());
  BOOST_TEST(back.time == s.time());
}

// A whole run through the executable: the .pvd lists every snapshot with its
// time, VTK's collection reader opens it, energy.csv has one row per snapshot.
BOOST_AUTO_TEST_CASE(pvd_series_of_a_run_is_read_by_vtk) {
  const auto dir = test::scratchDir("pvd");
  const auto r = test::runSph({"run", test::caseFile("droplet"), "--output", dir.string(),
                               "--end_time", "0.01", "--output_every", "25"});
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  const auto series = test::readPvd(dir / "droplet.pvd");
  BOOST_TEST_REQUIRE(series.size() == 5u);  // steps 0, 25, 50, 75, 100
  BOOST_TEST(series[0].time == 0.0);
  BOOST_TEST(series[4].time == 0.01, boost::test_tools::tolerance(1e-12));
  for (const auto& e : series) BOOST_TEST(e.data->GetNumberOfPoints() == series[0].data->GetNumberOfPoints());
  BOOST_TEST(series[0].data->GetNumberOfPoints() > 500);
  BOOST_TEST(series[4].data->GetFieldData()->GetArray("step")->GetTuple1(0) == 100.0);

  std::ifstream energy(dir / "energy.csv");
  std::string line;
  int rows = 0;
  std::getline(energy, line);
  BOOST_TEST(line == "time,kinetic,potential,total");
  while (std::getline(energy, line)) ++rows;
  BOOST_TEST(rows == 5);
}

// A new run from a snapshot (particle_file): it starts at the snapshot's
// time with its masses, end_time is absolute, and 5 + 5 steps agree with 10
// steps to O(dt^2) (a new run re-starts leap-frog; --resume continues bit
// for bit, tests/test_run_folder.cpp).
BOOST_AUTO_TEST_CASE(a_run_continues_from_a_vtp) {
  const auto dir = test::scratchDir("continue");
  auto run = [&](const std::string& out, const std::vector<std::string>& extra) {
    std::vector<std::string> args{"run", test::caseFile("block_drop"), "--output", (dir / out).string(),
                                  "--output_every", "5"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = test::runSph(args);
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  };
  run("a", {"--end_time", "0.0005"});
  run("b", {"--end_time", "0.001", "--particle_file", (dir / "a" / "block_drop_00001.vtp").string()});
  run("c", {"--end_time", "0.001"});
  const VtpParticles b = readVtp((dir / "b" / "block_drop_00001.vtp").string());
  const VtpParticles c = readVtp((dir / "c" / "block_drop_00002.vtp").string());
  BOOST_TEST(b.time == 0.001, boost::test_tools::tolerance(1e-12));
  BOOST_TEST_REQUIRE(b.x.size() == c.x.size());
  // The restart re-starts leap-frog with a half kick from v^n, which differs
  // from the running scheme by O(dt^2 da/dt): compare to 1e-6 m.
  std::map<std::int64_t, std::array<Real, 3>> byId;
  for (std::size_t i = 0; i < c.x.size(); ++i) byId[c.id[i]] = c.x[i];
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    BOOST_TEST(std::abs(b.x[i][0] - byId[b.id[i]][0]) < 1e-6);
    BOOST_TEST(std::abs(b.x[i][1] - byId[b.id[i]][1]) < 1e-6);
  }
}

// Every layout VTK's XML writer gives a .vtp (ParaView's SaveData drives the
// same writer; the paraview_files suite below checks files pvpython saved):
// ascii, inline base64 ("binary"), appended raw and base64; no, zlib, LZ4 or
// LZMA compression; UInt32 or UInt64 block headers. readVtp reads the same
// values from each as from sph's own snapshot, bit for bit (VTK writes ascii
// doubles with 17 significant digits, which read back exactly).
BOOST_AUTO_TEST_CASE(every_layout_vtk_writes_is_read_the_same) {
  const auto dir = test::scratchDir("vtp_layouts");
  const std::string original = damBreakSnapshot(dir);
  const VtpParticles expected = readVtp(original);
  BOOST_TEST_REQUIRE(!expected.kind.empty());
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(original.c_str());
  reader->Update();
  int files = 0;
  for (int mode : {vtkXMLWriter::Ascii, vtkXMLWriter::Binary, vtkXMLWriter::Appended})
    for (bool encode : {false, true})
      for (int compressor : {vtkXMLWriter::NONE, vtkXMLWriter::ZLIB, vtkXMLWriter::LZ4, vtkXMLWriter::LZMA})
        for (int header : {vtkXMLWriter::UInt32, vtkXMLWriter::UInt64}) {
          if (mode != vtkXMLWriter::Appended && encode) continue;  // encoding applies to appended data
          const std::string name = "mode" + std::to_string(mode) + "_encode" + std::to_string(encode) + "_compressor" +
                                   std::to_string(compressor) + "_header" + std::to_string(header) + ".vtp";
          const std::string path = (dir / name).string();
          vtkNew<vtkXMLPolyDataWriter> writer;
          writer->SetFileName(path.c_str());
          writer->SetInputConnection(reader->GetOutputPort());
          writer->SetDataMode(mode);
          writer->SetEncodeAppendedData(encode);
          writer->SetCompressorType(compressor);
          writer->SetHeaderType(header);
          BOOST_TEST_REQUIRE(writer->Write() == 1);
          expectSame(readVtp(path), expected, name);
          ++files;
        }
  BOOST_TEST(files == 32);
}

// A parallel snapshot made without MPI: pieces written as the ranks would
// (writeVtp), one of them empty, and the summary. sph's reader appends the
// pieces in order; a piece that is missing, damaged or of another time gives
// one line naming the .pvtp and the piece. (The ranks writing their pieces:
// test_mpi_pvtp.cpp, label mpi.)
BOOST_AUTO_TEST_CASE(pvtp_pieces_are_read_in_order_and_bad_pieces_named) {
  const auto dir = test::scratchDir("pvtp");
  const Particles<2> P = distinctParticles<2>(23, 17);
  const SnapshotInfo info{0.5, 3, 0.01, 0.0075, {0, 0}, {1, 1}};
  // Pieces 0 and 2 hold the particles [0, 10) and [10, 23); piece 1 none.
  auto piece = [&](std::size_t from, std::size_t to) {
    Particles<2> Q;
    Q.x.assign(P.x.begin() + static_cast<long>(from), P.x.begin() + static_cast<long>(to));
    Q.resize(to - from, from < 17 ? std::min<std::size_t>(17, to) - from : 0);
    Q.allocate(P.allocated());
    for (std::size_t k = 0; k < to - from; ++k) {
      Q.v[k] = P.v[from + k];
      Q.a[k] = P.a[from + k];
      Q.xList[k] = P.xList[from + k];
      Q.rho[k] = P.rho[from + k];
      Q.drho[k] = P.drho[from + k];
      Q.m[k] = P.m[from + k];
      Q.id[k] = P.id[from + k];
    }
    return Q;
  };
  const std::string pvtp = (dir / "snap_00002.pvtp").string();
  auto pieceFile = [&](int r) { return (dir / pvtpPieceName(pvtp, r)).string(); };
  BOOST_TEST(pvtpPieceName(pvtp, 2) == "snap_00002_2.vtp");
  writeVtp<2>(pieceFile(0), piece(0, 10), info);
  writeVtp<2>(pieceFile(1), piece(10, 10), info);
  writeVtp<2>(pieceFile(2), piece(10, 23), info);
  writePvtpSummary<2>(pvtp, P, info, 3);
  BOOST_TEST(!std::filesystem::exists(pvtp + ".tmp"));

  const std::string whole = (dir / "whole.vtp").string();
  writeVtp<2>(whole, P, info);
  expectSame(readVtp(pvtp), readVtp(whole), "the pieces appended = the whole set");

  auto expectNamed = [&](const std::string& named, const std::string& what) {
    try {
      readVtp(pvtp);
      BOOST_ERROR("read despite " << what);
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      BOOST_TEST(message.rfind(pvtp + ": its piece " + named, 0) == 0, message);
      BOOST_TEST(message.find('\n') == std::string::npos, message);
      BOOST_TEST(message.find(what) != std::string::npos, message);
    }
  };
  // Another time in one piece.
  writeVtp<2>(pieceFile(2), piece(10, 23), SnapshotInfo{0.75, 3, 0.01, 0.0075, {0, 0}, {1, 1}});
  expectNamed(pieceFile(2), "is of time 0.75");
  // A damaged piece.
  {
    std::ofstream out(pieceFile(2), std::ios::binary | std::ios::trunc);
    out << "<VTKFile type=\"PolyData\"><PolyData>";
  }
  expectNamed(pieceFile(2), "truncated");
  // A missing piece.
  std::filesystem::remove(pieceFile(2));
  expectNamed(pieceFile(2), "does not exist");
}

BOOST_AUTO_TEST_CASE(csv_particle_file_is_read) {
  const auto dir = test::scratchDir("csv");
  {
    std::ofstream f(dir / "p.csv");
    f << "# two particles\nx,y,vx,vy\n0.5,0.5,1,0\n0.2, 0.3, 0, -1\n";
  }
  CaseConfig c;
  c.particleFile = (dir / "p.csv").string();
  const auto s = buildInitialState<2>(withDefaults(c));
  BOOST_TEST_REQUIRE(s.particles.size() == 2u);
  BOOST_TEST(s.particles.x[1][1] == 0.3);
  BOOST_TEST(s.particles.v[1][1] == -1.0);
  BOOST_TEST(s.particles.v[0][0] == 1.0);
}

BOOST_AUTO_TEST_SUITE_END()

// Particle files saved by ParaView itself: pvpython's SaveData(..., DataMode
// = Ascii | Binary | Appended, EncodeAppendedData = 0 | 1, CompressorType =
// None | ZLib | LZ4) of an sph snapshot, made by tests/paraview_saved_files.sh
// (ctest paraview.saved_particle_files, label paraview), which names the
// folder in SPH_PARAVIEW_FILES: sph reads each and gets the values of the
// snapshot, bit for bit. Off by default (it needs pvpython).
BOOST_AUTO_TEST_SUITE(paraview_files, *boost::unit_test::disabled())

BOOST_AUTO_TEST_CASE(every_data_mode_paraview_saves_is_read_the_same) {
  const char* folder = std::getenv("SPH_PARAVIEW_FILES");
  BOOST_TEST_REQUIRE(folder != nullptr, "SPH_PARAVIEW_FILES is not set (run ctest -R paraview.saved_particle_files)");
  const std::filesystem::path dir(folder);
  const VtpParticles expected = readVtp((dir / "original.vtp").string());
  BOOST_TEST_REQUIRE(!expected.kind.empty());
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "saved")) {
    expectSame(readVtp(entry.path().string()), expected, entry.path().filename().string());
    ++files;
  }
  BOOST_TEST(files == 10);  // 1 ascii + 3 compressors x (binary, appended raw, appended base64)
}

BOOST_AUTO_TEST_SUITE_END()
