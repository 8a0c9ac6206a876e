// The domain decomposition (mpi/domain_decomposition.hpp) on R ranks: its own
// executable, sph_mpi_tests, run by ctest under
// `mpirun --oversubscribe -n R` for R = 1, 2, 3, 4 (label mpi).
//
// Every rank builds the same set of particles (the same seed), holds every
// R-th of them at the start, then balances, migrates and makes the halos;
// the checks are exact (the fields are copied bytes, the pairs are compared
// as sets of ids with the neighbour list's own test |x_i - x_j|^2 < r^2 on
// the same values), so no tolerance is needed. A rank's failed check does
// not stop it: every rank goes through the same collective calls, so a
// failure cannot hang the others (ctest's timeout is the guard if it did).
#define BOOST_TEST_MODULE sph_mpi
#include <boost/test/unit_test.hpp>

#include "sph/hash_grid.hpp"
#include "sph/mpi/domain_decomposition.hpp"
#include "sph/mpi/session.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/periodic_ghosts.hpp"
#include "sph/regime_check.hpp"

#include "mpi_session_fixture.hpp"

#include <algorithm>
#include <cstdlib>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace {

using sph::FieldSet;
using sph::Particles;
using sph::Narrow;
using sph::Real;
using sph::Vec;
using sph::fieldBit;
using sph::mpi::Communicator;
using sph::mpi::DomainDecomposition;

using sph::test::world;

// The fields beyond the core ones that travel: a stage vector, a state
// density rate, a scalar.
constexpr FieldSet kExtra = fieldBit(sph::kFieldVHalf) | fieldBit(sph::kFieldDrho) | fieldBit(sph::kFieldColour);

// The whole set, the same on every rank: fluid (ids 0 ...) then walls.
template <int D>
struct Global {
  std::vector<Vec<D>> x;
  std::size_t fluid = 0;
  Real radius = 0;
  std::size_t size() const { return x.size(); }
  bool wall(std::size_t k) const { return k >= fluid; }
};

// Every field of particle id as a function of the id, so a check knows them.
template <int D>
Vec<D> velocityOf(std::int64_t id) { return Vec<D>::Constant(Real(0.25) * static_cast<Real>(id) - 3); }
// (As stored: a narrow field, float in a mixed-precision build.)
Narrow massOf(std::int64_t id) { return static_cast<Narrow>(Real(1) + Real(1e-3) * static_cast<Real>(id)); }
Real densityOf(std::int64_t id) { return Real(1000) + Real(0.5) * static_cast<Real>(id); }

// Random fluid in the unit box; points exactly on cell faces (one
// coordinate a multiple of the grid's cell); a lattice at half the radius
// (pairs exactly one radius apart); a dense block of walls in the middle,
// more than half of all particles, so every cut of the curve passes through it.
template <int D>
Global<D> makeGlobal(Real radius, std::size_t randomFluid, std::size_t facePoints, Real wallSpacing) {
  Global<D> g;
  g.radius = radius;
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<Real> u(0, 1);
  for (std::size_t k = 0; k < randomFluid; ++k) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = u(rng);
    g.x.push_back(x);
  }
  const Real cell = radius * (1 + 1e-9);  // hash_grid.hpp's
  std::uniform_int_distribution<int> face(1, static_cast<int>(1 / cell) - 1);
  std::uniform_int_distribution<int> axis(0, D - 1);
  for (std::size_t k = 0; k < facePoints; ++k) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = u(rng);
    x[axis(rng)] = face(rng) * cell;
    if (k % 4 == 0) x[(axis(rng) + 1) % D] = face(rng) * cell;  // on an edge
    g.x.push_back(x);
  }
  const int lattice = 6;
  for (int k = 0; k < (D == 2 ? lattice * lattice : lattice * lattice * lattice); ++k) {
    Vec<D> x;
    int rest = k;
    for (int d = 0; d < D; ++d, rest /= lattice) x[d] = Real(0.05) + (rest % lattice) * radius / 2;
    g.x.push_back(x);
  }
  g.fluid = g.x.size();
  const Vec<D> lo = Vec<D>::Constant(Real(0.4)), hi = Vec<D>::Constant(Real(0.6) + 1e-12);
  const int per = static_cast<int>((hi[0] - lo[0]) / wallSpacing) + 1;
  int cells = 1;
  for (int d = 0; d < D; ++d) cells *= per;
  for (int k = 0; k < cells; ++k) {
    Vec<D> x;
    int rest = k;
    for (int d = 0; d < D; ++d, rest /= per) x[d] = lo[d] + (rest % per) * wallSpacing;
    g.x.push_back(x);
  }
  return g;
}

template <int D>
void setFields(Particles<D>& P, std::size_t i) {
  const std::int64_t id = P.id[i];
  P.v[i] = velocityOf<D>(id);
  P.m[i] = massOf(id);
  P.rho[i] = densityOf(id);
  P.vHalf[i] = Vec<D>::Constant(static_cast<Real>(id) / 7);
  P.drho[i] = -static_cast<Real>(id);
  P.colour[i] = static_cast<Real>(id % 2);
}

// This rank's share at the start: every R-th particle (fluid, then walls).
template <int D>
Particles<D> share(const Global<D>& g, int rank, int ranks) {
  Particles<D> P;
  std::size_t fluid = 0;
  for (std::size_t k = static_cast<std::size_t>(rank); k < g.size(); k += static_cast<std::size_t>(ranks)) {
    P.x.push_back(g.x[k]);
    P.id.push_back(static_cast<std::int64_t>(k));
    fluid += !g.wall(k);
  }
  const std::size_t n = P.x.size();
  P.resize(n, fluid);
  P.allocate(kExtra);
  for (std::size_t i = 0; i < n; ++i) setFields(P, i);
  return P;
}

// Particle i (owned or halo) holds exactly the fields of its id.
template <int D>
bool fieldsOfItsId(const Global<D>& g, const Particles<D>& P, std::size_t i) {
  const std::int64_t id = P.id[i];
  if (id < 0 || static_cast<std::size_t>(id) >= g.size()) return false;
  const auto k = static_cast<std::size_t>(id);
  return P.x[i] == g.x[k] && P.v[i] == velocityOf<D>(id) && P.m[i] == massOf(id) && P.rho[i] == densityOf(id) &&
         P.vHalf[i] == Vec<D>::Constant(static_cast<Real>(id) / 7) && P.drho[i] == -static_cast<Real>(id) &&
         P.colour[i] == static_cast<Real>(id % 2) && P.kind[i] == (g.wall(k) ? sph::kWall : sph::kFluid);
}

std::vector<std::int64_t> allIds(const Communicator& c, const std::vector<std::int64_t>& mine) {
  std::vector<int> counts(static_cast<std::size_t>(c.size)), displs(static_cast<std::size_t>(c.size));
  const int n = static_cast<int>(mine.size());
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, c.comm);
  int total = 0;
  for (int r = 0; r < c.size; ++r) displs[r] = total, total += counts[r];
  std::vector<std::int64_t> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(mine.data(), n, MPI_INT64_T, all.data(), counts.data(), displs.data(), MPI_INT64_T, c.comm);
  return all;
}

int sumOver(const Communicator& c, int value) {
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT, MPI_SUM, c.comm);
  return value;
}

// This rank's share, balanced and migrated by dd.
template <int D>
Particles<D> migrated(const Global<D>& g, DomainDecomposition<D>& dd) {
  Particles<D> P = share(g, dd.rank(), dd.ranks());
  dd.balance(P);
  dd.migrate(P);
  return P;
}

// Balance and migrate: the owned ids are those of the whole set once each,
// on the rank owning their cell, with every field, fluid before walls.
template <int D>
void checkMigration(const Global<D>& g) {
  const Communicator c = world();
  DomainDecomposition<D> dd(c, g.radius);
  Particles<D> P = migrated(g, dd);
  const std::vector<std::int64_t> ids(P.id.begin(), P.id.begin() + static_cast<std::ptrdiff_t>(P.size()));
  std::vector<std::int64_t> all = allIds(c, ids);
  BOOST_CHECK_EQUAL(all.size(), g.size());
  std::sort(all.begin(), all.end());
  std::vector<std::int64_t> expected(g.size());
  for (std::size_t k = 0; k < g.size(); ++k) expected[k] = static_cast<std::int64_t>(k);
  BOOST_CHECK(all == expected);
  std::size_t wrongRank = 0, wrongFields = 0, wrongKind = 0;
  double mass = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    wrongRank += dd.ownerOf(P.x[i]) != c.rank;
    wrongFields += !fieldsOfItsId(g, P, i);
    wrongKind += (i < P.fluidCount()) != (P.kind[i] == sph::kFluid);
    mass += P.m[i];
  }
  BOOST_CHECK_EQUAL(wrongRank, 0u);
  BOOST_CHECK_EQUAL(wrongFields, 0u);
  BOOST_CHECK_EQUAL(wrongKind, 0u);
  BOOST_CHECK_EQUAL(P.totalSize(), P.size());
  // Total mass: the sum over ranks against the sum over the set. The
  // masses travel bit for bit; only the order of the additions differs, so
  // the sums agree to a few ulps of the total (1e-12 relative).
  MPI_Allreduce(MPI_IN_PLACE, &mass, 1, MPI_DOUBLE, MPI_SUM, c.comm);
  double expectedMass = 0;
  for (std::size_t k = 0; k < g.size(); ++k) expectedMass += massOf(static_cast<std::int64_t>(k));
  BOOST_CHECK_CLOSE_FRACTION(mass, expectedMass, 1e-12);
  BOOST_CHECK_EQUAL(sumOver(c, static_cast<int>(P.fluidCount())), static_cast<int>(g.fluid));
  // The walls' dense block is cut: with several ranks, walls on more than one.
  const int ranksWithWalls = sumOver(c, P.fluidCount() < P.size() ? 1 : 0);
  if (c.size > 1) BOOST_CHECK_GT(ranksWithWalls, 1);
}

// The pairs a neighbour list over owned + halo finds on each rank are the
// pairs of a brute-force search over the whole set restricted to the owned
// particles (a wall lists only fluid neighbours, as neighbour_list.hpp).
// Then refreshHalos carries exactly the fields it is given.
template <int D>
void checkHaloPairsAndRefresh(const Global<D>& g) {
  const Communicator c = world();
  DomainDecomposition<D> dd(c, g.radius);
  Particles<D> P = migrated(g, dd);
  dd.makeHalos(P, g.radius);
  BOOST_CHECK_EQUAL(P.totalSize() - P.size(), dd.haloCount());
  // Halos: other ranks' particles, with all their fields.
  std::set<std::int64_t> owned(P.id.begin(), P.id.begin() + static_cast<std::ptrdiff_t>(P.size()));
  std::size_t wrongHalo = 0, haloWallInFluidRange = 0;
  for (std::size_t i = P.size(); i < P.totalSize(); ++i) {
    wrongHalo += owned.count(P.id[i]) || !fieldsOfItsId(g, P, i) || dd.ownerOf(P.x[i]) == c.rank;
    haloWallInFluidRange += (i < P.ghostFluidEnd()) != (P.kind[i] == sph::kFluid);
  }
  BOOST_CHECK_EQUAL(wrongHalo, 0u);
  BOOST_CHECK_EQUAL(haloWallInFluidRange, 0u);

  // Sort by cell (owned and halos) and list, as sortByCell does.
  sph::HashGrid<D> grid(g.radius);
  sph::NeighbourList<D> list;
  grid.build(P.x, P.fluidCount(), P.size(), P.ghostFluidEnd());
  P.permute(grid.order());
  dd.followPermutation(grid.order(), P.size());
  list.build(grid, P.x, g.radius, P.fluidCount(), P.size());
  std::vector<std::pair<std::int64_t, std::int64_t>> found, expected;
  for (std::size_t i = 0; i < P.size(); ++i) list.forEach(i, [&](std::size_t j) { found.emplace_back(P.id[i], P.id[j]); });
  const Real r2 = g.radius * g.radius;
  for (std::size_t a = 0; a < g.size(); ++a) {
    if (!owned.count(static_cast<std::int64_t>(a))) continue;
    for (std::size_t b = 0; b < g.size(); ++b)
      if (b != a && !(g.wall(a) && g.wall(b)) && Vec<D>(g.x[a] - g.x[b]).squaredNorm() < r2)
        expected.emplace_back(static_cast<std::int64_t>(a), static_cast<std::int64_t>(b));
  }
  std::sort(found.begin(), found.end());
  std::sort(expected.begin(), expected.end());
  BOOST_CHECK_EQUAL(found.size(), expected.size());
  BOOST_CHECK(found == expected);
  BOOST_CHECK_EQUAL(sumOver(c, static_cast<int>(found.size()) > 0 ? 1 : 0), c.size);  // no rank idle

  // refreshHalos(p, v): the owners' new values arrive, after the sort; rho,
  // changed too but not sent, keeps the halo's old value.
  for (std::size_t i = 0; i < P.size(); ++i) {
    P.p[i] = 1000 + static_cast<Real>(P.id[i]);
    P.v[i] = Vec<D>::Constant(Real(0.5) * static_cast<Real>(P.id[i]));
    P.rho[i] = -1;
  }
  dd.refreshHalos(P, fieldBit(sph::kFieldP) | fieldBit(sph::kFieldV));
  std::size_t stale = 0, overwritten = 0;
  for (std::size_t i = P.size(); i < P.totalSize(); ++i) {
    stale += P.p[i] != 1000 + static_cast<Real>(P.id[i]) ||
             P.v[i] != Vec<D>::Constant(Real(0.5) * static_cast<Real>(P.id[i]));
    overwritten += P.rho[i] != densityOf(P.id[i]);
  }
  BOOST_CHECK_EQUAL(stale, 0u);
  BOOST_CHECK_EQUAL(overwritten, 0u);
  if (c.size > 1) BOOST_CHECK_GT(sumOver(c, static_cast<int>(dd.haloCount())), 0);
}

// One rank (the world when R = 1; else each rank alone on MPI_COMM_SELF):
// nothing moves, no halo exists.
template <int D>
void checkOneRank(const Global<D>& g) {
  const Communicator alone = world().size == 1 ? world() : Communicator{MPI_COMM_SELF, 0, 1};
  Particles<D> P = share(g, 0, 1);
  const Particles<D> before = P;
  DomainDecomposition<D> dd(alone, g.radius);
  dd.balance(P);
  dd.migrate(P);
  dd.makeHalos(P, g.radius);
  BOOST_CHECK_EQUAL(dd.haloCount(), 0u);
  BOOST_CHECK_EQUAL(P.totalSize(), before.size());
  BOOST_CHECK_EQUAL(P.fluidCount(), before.fluidCount());
  BOOST_CHECK(P.x == before.x);
  BOOST_CHECK(P.id == before.id);
  BOOST_CHECK(P.v == before.v);
  BOOST_CHECK(P.vHalf == before.vHalf);
  dd.refreshHalos(P, fieldBit(sph::kFieldP));
  BOOST_CHECK(P.p == before.p);
}

// Periodic ghosts made before the halos stay, with their sources and
// shifts, through makeHalos, a sort and a refresh; halos and ghosts keep
// the kinds' ranges. A periodic ghost near another rank's cells is sent
// there as a halo: a halo is its id's particle, or its image one box
// length away along x.
void checkPeriodicGhostsKept(const Global<2>& g) {
  const Communicator c = world();
  DomainDecomposition<2> dd(c, g.radius);
  Particles<2> P = migrated(g, dd);
  sph::PeriodicBox<2> box;
  box.axes = 1u;  // x periodic over [0, 1)
  sph::PeriodicGhosts<2> ghosts(box, g.radius);
  ghosts.make(P);
  const std::size_t local = P.totalSize() - P.size();
  dd.makeHalos(P, g.radius);
  const auto check = [&](const char* when, bool refreshed) {
    BOOST_TEST_CONTEXT(when) {
      std::size_t localNow = 0, wrongGhost = 0, wrongRange = 0, wrongHalo = 0, images = 0;
      for (std::size_t k = 0; k < P.ghostSource().size(); ++k) {
        const std::size_t i = P.size() + k;
        const std::uint32_t s = P.ghostSource()[k];
        wrongRange += (i < P.ghostFluidEnd()) != (P.kind[i] == sph::kFluid);
        if (s & Particles<2>::kRemoteSource) {
          const auto own = static_cast<std::size_t>(P.id[i]);
          const bool image = P.id[i] >= 0 && own < g.size() && P.x[i] != g.x[own];
          if (image) {
            const bool shifted = P.x[i] == Vec<2>(g.x[own] + Vec<2>(1, 0)) || P.x[i] == Vec<2>(g.x[own] - Vec<2>(1, 0));
            wrongHalo += !shifted;
            ++images;
          }
          const Vec<2> x = P.x[i];
          if (image) P.x[i] = g.x[own];
          wrongHalo += !fieldsOfItsId(g, P, i) || (refreshed && P.p[i] != 1000 + static_cast<Real>(P.id[i]));
          P.x[i] = x;
          continue;
        }
        ++localNow;
        wrongGhost += P.id[i] != P.id[s] || P.x[i] != Vec<2>(P.x[s] + P.ghostShift()[k]) || P.p[i] != P.p[s] ||
                      P.ghostShift()[k].norm() != 1;
      }
      BOOST_CHECK_EQUAL(localNow, local);
      BOOST_CHECK_EQUAL(P.ghostSource().size() - localNow, dd.haloCount());
      BOOST_CHECK_EQUAL(wrongGhost, 0u);
      BOOST_CHECK_EQUAL(wrongRange, 0u);
      BOOST_CHECK_EQUAL(wrongHalo, 0u);
      if (c.size > 1) BOOST_CHECK_GT(sumOver(c, static_cast<int>(images)), 0);  // images cross ranks
    }
  };
  check("after makeHalos", false);
  sph::HashGrid<2> grid(g.radius);
  grid.build(P.x, P.fluidCount(), P.size(), P.ghostFluidEnd());
  P.permute(grid.order());
  dd.followPermutation(grid.order(), P.size());
  for (std::size_t i = 0; i < P.size(); ++i) P.p[i] = 1000 + static_cast<Real>(P.id[i]);
  P.refreshGhosts(fieldBit(sph::kFieldP));
  dd.refreshHalos(P, fieldBit(sph::kFieldP));
  check("after a sort and a refresh", true);
  BOOST_CHECK_GT(sumOver(c, static_cast<int>(local)), 0);
}

Global<2> global2d() { return makeGlobal<2>(0.1, 600, 120, 0.01); }
Global<3> global3d() { return makeGlobal<3>(0.15, 800, 150, 0.02); }

// The regime check's density extremes over every rank's fluid
// (regime_check.hpp: the largest, and the least reduced as minus the
// largest of its negative): fluid id 0 given a negative density and id 1 a
// large one, each found on every rank, whichever rank holds it.
void checkRegimeExtremes(const Global<2>& g) {
  const Communicator c = world();
  DomainDecomposition<2> dd(c, g.radius);
  Particles<2> P = migrated(g, dd);
  sph::HashGrid<2> grid(g.radius);
  sph::NeighbourList<2> list;
  grid.build(P.x, P.fluidCount(), P.size(), P.ghostFluidEnd());
  P.permute(grid.order());
  list.build(grid, P.x, g.radius, P.fluidCount(), P.size());
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    if (P.id[i] == 0) P.rho[i] = -5;
    if (P.id[i] == 1) P.rho[i] = 1e6;
  }
  const sph::RegimeState s = sph::measureRegime(P, list, 10.0, 0.0, 1000.0, g.radius, c);
  BOOST_TEST(s.densityMin == -5.0);
  BOOST_TEST(s.densityMax == 1000.0);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mpi_decomposition)

// A program a rank starts (sph study's runs) inherits the launcher's
// variables but is no rank: sph started so runs alone (mpi/session.hpp)
// instead of failing in MPI_Init. `timeout`: a failing MPI_Init can hang.
BOOST_AUTO_TEST_CASE(child_process_runs_alone) {
  if (world().rank != 0) return;
  const int status = std::system("timeout 30 \"" SPH_EXECUTABLE "\" --version > /dev/null 2>&1");
  BOOST_CHECK_EQUAL(status, 0);
}

BOOST_AUTO_TEST_CASE(migration_2d) { checkMigration(global2d()); }
BOOST_AUTO_TEST_CASE(migration_3d) { checkMigration(global3d()); }
BOOST_AUTO_TEST_CASE(halo_pairs_and_refresh_2d) { checkHaloPairsAndRefresh(global2d()); }
BOOST_AUTO_TEST_CASE(halo_pairs_and_refresh_3d) { checkHaloPairsAndRefresh(global3d()); }
BOOST_AUTO_TEST_CASE(periodic_ghosts_kept_2d) { checkPeriodicGhostsKept(global2d()); }
BOOST_AUTO_TEST_CASE(one_rank_2d) { checkOneRank(global2d()); }
BOOST_AUTO_TEST_CASE(one_rank_3d) { checkOneRank(global3d()); }
BOOST_AUTO_TEST_CASE(regime_extremes_over_ranks) { checkRegimeExtremes(global2d()); }

BOOST_AUTO_TEST_SUITE_END()
