// Parallel snapshots (io/pvtp_io.hpp, mpi/parallel_snapshot.hpp) on R ranks:
// its own executable, sph_mpi_pvtp_tests, run by ctest under
// `mpirun --oversubscribe -n R` for R = 2, 3 (label mpi).
//
// Every rank builds the same known set of particles (every value a function
// of the id), keeps those with id % R == rank, and writes its part as one
// .pvtp with writeParallelSnapshot. Rank 0 then checks that (a) VTK's
// vtkXMLPPolyDataReader reads the whole set: every point, every array a
// one-rank .vtp of the whole set has (name, components) with its values by
// id, and the field data (TimeValue, step, ...); every piece has the units;
// (b) sph's own reader (readVtp, what --particle_file and --resume use)
// gives back the set by id;
// (c) pvpython opens the .pvtp and counts every point (skipped, with a
// message, without pvpython or xvfb-run); (d) with one piece deleted, readVtp
// fails with one line naming that piece. Values are copied bytes: exact
// comparisons, no tolerance. A failed check does not stop a rank before a
// collective call, so a failure cannot hang the others.
#define BOOST_TEST_MODULE sph_mpi_pvtp
#include <boost/test/unit_test.hpp>

#include "sph/io/pvtp_io.hpp"
#include "sph/io/vtp_io.hpp"
#include "sph/mpi/parallel_snapshot.hpp"
#include "sph/mpi/session.hpp"
#include "sph/particles.hpp"

#include "mpi_session_fixture.hpp"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

namespace {

using namespace sph;
using sph::mpi::Communicator;

using sph::test::world;

// Particle id's values: all distinct, fluid (id < fluid) then walls.
template <int D>
Particles<D> knownSet(std::size_t n, std::size_t fluid) {
  Particles<D> all;
  all.x.resize(n);
  all.resize(n, fluid);
  all.allocate(fieldBit(kFieldDrho) | fieldBit(kFieldColour));
  for (std::size_t i = 0; i < n; ++i) {
    const Real s = static_cast<Real>(i) + 0.25;
    for (int d = 0; d < D; ++d) {
      all.x[i][d] = s + 0.1 * d;
      all.v[i][d] = -s - 0.2 * d;
      all.a[i][d] = 3 * s + d;
    }
    all.rho[i] = 1000 + s;
    all.drho[i] = -s;
    all.p[i] = 7 * s;
    all.m[i] = 0.5 + s;
    all.colour[i] = i % 2;
    all.id[i] = static_cast<std::int64_t>(i);
  }
  return all;
}

// This rank's part of `all`: every c.size-th particle, fluid then walls.
template <int D>
Particles<D> partOf(const Particles<D>& all, const Communicator& c) {
  const std::size_t n = all.size(), fluid = all.fluidCount();
  Particles<D> mine;
  std::vector<std::size_t> keep;
  std::size_t keptFluid = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(c.size)) == c.rank) {
      keep.push_back(i);
      keptFluid += i < fluid;
    }
  mine.x.resize(keep.size());
  mine.resize(keep.size(), keptFluid);
  mine.allocate(all.allocated());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    const std::size_t i = keep[k];
    mine.x[k] = all.x[i];
    mine.v[k] = all.v[i];
    mine.a[k] = all.a[i];
    mine.rho[k] = all.rho[i];
    mine.drho[k] = all.drho[i];
    mine.p[k] = all.p[i];
    mine.m[k] = all.m[i];
    mine.colour[k] = all.colour[i];
    mine.id[k] = all.id[i];
    if (!all.kind.empty()) mine.kind[k] = all.kind[i];
  }
  return mine;
}

const SnapshotInfo kInfo{0.125, 42, 0.013, 0.0065, {0, 0}, {1, 2}};

// A folder every rank sees, emptied by rank 0.
std::filesystem::path sharedFolder(const std::string& name, const Communicator& c) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("sph_mpi_pvtp_" + std::to_string(c.size) + "_" + name);
  if (c.rank == 0) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  MPI_Barrier(c.comm);
  return dir;
}

// Every point array of `a` is in `b` with the same components and, matched
// by id, the same values; the field data of `a` are in `b`.
std::string unitOf(vtkDataArray* a) {
  const char* unit = a->GetInformation()->Get(vtkDataArray::UNITS_LABEL());
  return unit ? unit : "";
}

void expectSameById(vtkPolyData* a, vtkPolyData* b) {
  BOOST_TEST_REQUIRE(a->GetNumberOfPoints() == b->GetNumberOfPoints());
  vtkDataArray* idA = a->GetPointData()->GetArray("id");
  vtkDataArray* idB = b->GetPointData()->GetArray("id");
  BOOST_TEST_REQUIRE((idA && idB));
  std::map<long long, vtkIdType> inB;
  for (vtkIdType i = 0; i < b->GetNumberOfPoints(); ++i) inB[static_cast<long long>(idB->GetTuple1(i))] = i;
  BOOST_TEST_REQUIRE(inB.size() == static_cast<std::size_t>(b->GetNumberOfPoints()));
  vtkPointData* pa = a->GetPointData();
  BOOST_TEST(pa->GetNumberOfArrays() == b->GetPointData()->GetNumberOfArrays());
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i) {
    const vtkIdType j = inB.at(static_cast<long long>(idA->GetTuple1(i)));
    for (int c = 0; c < 3; ++c) BOOST_TEST(a->GetPoint(i)[c] == b->GetPoint(j)[c]);
  }
  for (int k = 0; k < pa->GetNumberOfArrays(); ++k) {
    vtkDataArray* x = pa->GetArray(k);
    vtkDataArray* y = b->GetPointData()->GetArray(x->GetName());
    BOOST_TEST_CONTEXT("array " << x->GetName()) {
      BOOST_TEST_REQUIRE(y != nullptr);
      BOOST_TEST(x->GetDataType() == y->GetDataType());
      BOOST_TEST_REQUIRE(x->GetNumberOfComponents() == y->GetNumberOfComponents());
      for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i) {
        const vtkIdType j = inB.at(static_cast<long long>(idA->GetTuple1(i)));
        for (int c = 0; c < x->GetNumberOfComponents(); ++c) BOOST_TEST(x->GetComponent(i, c) == y->GetComponent(j, c));
      }
    }
  }
  vtkFieldData* fa = a->GetFieldData();
  for (int k = 0; k < fa->GetNumberOfArrays(); ++k) {
    vtkDataArray* x = fa->GetArray(k);
    vtkDataArray* y = b->GetFieldData()->GetArray(x->GetName());
    BOOST_TEST_CONTEXT("field " << x->GetName()) {
      BOOST_TEST_REQUIRE(y != nullptr);
      BOOST_TEST_REQUIRE(x->GetNumberOfTuples() == y->GetNumberOfTuples());
      for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t) BOOST_TEST(x->GetTuple1(t) == y->GetTuple1(t));
    }
  }
}

// The output of a command, run without the launcher's environment (pvpython
// must not see itself as a rank).
std::string outputOf(const std::string& command) {
  std::string out;
  FILE* p = popen(("env -i PATH=\"$PATH\" HOME=\"$HOME\" " + command + " 2>&1").c_str(), "r");
  if (!p) return out;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, p)) out += buffer;
  pclose(p);
  return out;
}

template <int D>
void parallelSnapshotIsOneSet(std::size_t n, std::size_t fluid) {
  const Communicator c = world();
  const auto dir = sharedFolder("d" + std::to_string(D), c);
  const std::string pvtp = (dir / "snap_00003.pvtp").string();
  const Particles<D> all = knownSet<D>(n, fluid);
  const Particles<D> mine = partOf(all, c);
  BOOST_TEST_REQUIRE(mine.size() > 0);
  mpi::writeParallelSnapshot<D>(pvtp, mine, kInfo, c);
  MPI_Barrier(c.comm);
  if (c.rank != 0) return;

  // The reference: the whole set as today's one-rank .vtp.
  const std::string whole = (dir / "whole.vtp").string();
  writeVtp<D>(whole, all, kInfo);
  vtkNew<vtkXMLPolyDataReader> one;
  one->SetFileName(whole.c_str());
  one->Update();

  // (a) VTK's parallel reader.
  BOOST_TEST(std::filesystem::exists(pvtp));
  for (int r = 0; r < c.size; ++r) BOOST_TEST(std::filesystem::exists(dir / pvtpPieceName(pvtp, r)));
  vtkNew<vtkXMLPPolyDataReader> reader;
  reader->SetFileName(pvtp.c_str());
  reader->Update();
  vtkPolyData* got = reader->GetOutput();
  BOOST_TEST(reader->GetNumberOfPieces() == c.size);
  BOOST_TEST_REQUIRE(got->GetNumberOfPoints() == static_cast<vtkIdType>(n));
  expectSameById(one->GetOutput(), got);
  BOOST_TEST_REQUIRE(got->GetFieldData()->GetArray("TimeValue") != nullptr);
  BOOST_TEST(got->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == kInfo.time);
  // VTK's parallel reader drops the arrays' units (the summary declares
  // names and types only); each piece carries them, as the one-rank .vtp.
  vtkPointData* wholeArrays = one->GetOutput()->GetPointData();
  for (int r = 0; r < c.size; ++r) {
    vtkNew<vtkXMLPolyDataReader> piece;
    piece->SetFileName((dir / pvtpPieceName(pvtp, r)).string().c_str());
    piece->Update();
    for (int k = 0; k < wholeArrays->GetNumberOfArrays(); ++k) {
      vtkDataArray* x = wholeArrays->GetArray(k);
      vtkDataArray* y = piece->GetOutput()->GetPointData()->GetArray(x->GetName());
      BOOST_TEST_REQUIRE(y != nullptr, "piece " << r << " lacks " << x->GetName());
      BOOST_TEST(unitOf(y) == unitOf(x), "piece " << r << ", " << x->GetName());
      BOOST_TEST(!unitOf(x).empty(), x->GetName());
    }
  }

  // (b) sph's own reader, by id.
  const VtpParticles back = readVtp(pvtp);
  BOOST_TEST_REQUIRE(back.x.size() == n);
  BOOST_TEST(back.time == kInfo.time);
  BOOST_TEST(back.step == kInfo.step);
  BOOST_TEST_REQUIRE(back.id.size() == n);
  BOOST_TEST_REQUIRE(back.kind.size() == n);
  BOOST_TEST_REQUIRE(back.drho.size() == n);
  BOOST_TEST_REQUIRE(back.colour.size() == n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(back.id[k]);
    BOOST_TEST_REQUIRE(i < n);
    for (int d = 0; d < 3; ++d) {
      BOOST_TEST(back.x[k][d] == (d < D ? all.x[i][d] : 0));
      BOOST_TEST(back.v[k][d] == (d < D ? all.v[i][d] : 0));
      BOOST_TEST(back.a[k][d] == (d < D ? all.a[i][d] : 0));
    }
    BOOST_TEST(back.m[k] == all.m[i]);
    BOOST_TEST(back.rho[k] == all.rho[i]);
    BOOST_TEST(back.drho[k] == all.drho[i]);
    BOOST_TEST(back.colour[k] == all.colour[i]);
    BOOST_TEST(back.kind[k] == all.kind[i]);
  }

  // (c) pvpython opens it.
  if (outputOf("command -v pvpython").empty() || outputOf("command -v xvfb-run").empty()) {
    BOOST_TEST_MESSAGE("skipped: pvpython or xvfb-run is not installed, ParaView's reading of the .pvtp is not checked");
  } else {
    const auto script = dir / "count.py";
    std::ofstream(script) << "from paraview.simple import *\n"
                          << "r = OpenDataFile(r'" << pvtp << "')\n"
                          << "r.UpdatePipeline()\n"
                          << "print('points', r.GetDataInformation().GetNumberOfPoints())\n";
    const std::string out = outputOf("xvfb-run -a pvpython --disable-xdisplay-test " + script.string());
    BOOST_TEST(out.find("points " + std::to_string(n) + "\n") != std::string::npos, out);
  }

  // (d) a missing piece: one line naming it.
  const std::string last = (dir / pvtpPieceName(pvtp, c.size - 1)).string();
  std::filesystem::remove(last);
  try {
    readVtp(pvtp);
    BOOST_ERROR("a .pvtp with a missing piece was read");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    BOOST_TEST(what.find('\n') == std::string::npos, what);
    BOOST_TEST(what.find(last) != std::string::npos, what);
    BOOST_TEST(what.rfind(pvtp, 0) == 0, what);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(pvtp)

// One rank cannot write its piece (a folder has its name): every rank
// throws, the failing one naming its piece, and no .pvtp is written (rank 0
// did write its own piece: the summary is what must not exist).
BOOST_AUTO_TEST_CASE(a_piece_that_cannot_be_written_leaves_no_pvtp) {
  const Communicator c = world();
  const auto dir = sharedFolder("unwritable", c);
  const std::string pvtp = (dir / "snap_00001.pvtp").string();
  const std::string blocked = (dir / pvtpPieceName(pvtp, c.size - 1)).string();
  if (c.rank == 0) std::filesystem::create_directories(std::filesystem::path(blocked) / "in_the_way");
  MPI_Barrier(c.comm);
  const Particles<2> mine = partOf(knownSet<2>(20, 15), c);
  std::string message;
  try {
    mpi::writeParallelSnapshot<2>(pvtp, mine, kInfo, c);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  BOOST_TEST(!message.empty(), "rank " << c.rank << " did not throw");
  if (c.rank == c.size - 1) BOOST_TEST(message.find(blocked) != std::string::npos, message);
  MPI_Barrier(c.comm);
  BOOST_TEST(!std::filesystem::exists(pvtp));
  BOOST_TEST(!std::filesystem::exists(pvtp + ".tmp"));
}

BOOST_AUTO_TEST_CASE(every_rank_writes_its_piece_and_the_whole_set_reads_back_2d) { parallelSnapshotIsOneSet<2>(61, 47); }
BOOST_AUTO_TEST_CASE(every_rank_writes_its_piece_and_the_whole_set_reads_back_3d) { parallelSnapshotIsOneSet<3>(40, 29); }

BOOST_AUTO_TEST_SUITE_END()
