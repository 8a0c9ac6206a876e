// The packed list and the cell walk (neighbour_walk = packed | cells,
// neighbour_list.hpp): the list kept as one bit per candidate of the grid's
// cells around a particle, unpacked at every visit, or no stored list at all
// (every visit scans the cells again, with the build's own scan); both at
// the build's positions.
//
// - Unit: for random particles with walls and periodic ghosts, in 2D and 3D,
//   each visits exactly the stored list's rows, fluid and wall neighbours
//   apart, in the list's order, serially and from two threads; still after
//   the particles moved (they keep the build's positions, as the list keeps
//   the build's pairs); the pair counts agree; the cell walk stores nothing
//   and the packed list less than a sixth (2D) or a third (3D) of the
//   list's bytes (the bits per candidate: 2.9 and 6.4 times the neighbours,
//   against 32 per neighbour, plus 4 bytes a particle).
// - Runs: a run with either is the run with the list bit for bit (tolerance
//   0: the same pairs summed in the same order): the water dam break (skin
//   0.1, 2 threads), the periodic Poiseuille channel (ghosts), the dam break
//   with no skin, CSPM and MLS (leap-frog's half-step density rate uses the
//   list of x^n at x^{n+1/2}) and the 3D periodic channel (walls, ghosts).
#include "sph/hash_grid.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/periodic_box.hpp"
#include "sph/periodic_ghosts.hpp"
#include "cli_support.hpp"
#include "snapshot_by_id.hpp"

#include <boost/test/unit_test.hpp>
#include <omp.h>

#include <random>
#include <vector>

using namespace sph;

namespace {

// Particle i's row: its fluid neighbours, then (after a -1) its wall ones.
template <int D>
std::vector<std::int64_t> row(const NeighbourList<D>& list, std::size_t i) {
  std::vector<std::int64_t> r;
  list.forEachByKind(
      i, [&](std::uint32_t j) { r.push_back(j); },
      [&](std::uint32_t j) {
        if (r.empty() || r.back() >= 0) r.push_back(-1);
        r.push_back(j);
      });
  return r;
}

// Every row, computed by `threads` threads.
template <int D>
std::vector<std::vector<std::int64_t>> rows(const NeighbourList<D>& list, std::size_t n, int threads) {
  std::vector<std::vector<std::int64_t>> out(n);
#pragma omp parallel for schedule(dynamic, 7) num_threads(threads)
  for (std::size_t i = 0; i < n; ++i) out[i] = row(list, i);
  return out;
}

// n random particles in a box 5 supports wide, periodic along axis 0, the
// last quarter walls; sorted and listed once with a stored list and once
// (a copy) with `storage`.
template <int D>
void checkRows(std::size_t n, unsigned seed, NeighbourStorage storage) {
  const bool packed = storage == NeighbourStorage::kPacked;
  const Real support = 1.0, skin = 0.1, radius = support * (1 + skin);
  PeriodicBox<D> box;
  box.lo = Vec<D>::Zero();
  box.length = Vec<D>::Constant(5 * support);
  box.axes = 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(0, 1);
  Particles<D> P;
  P.x.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < D; ++d) P.x[i][d] = u(rng) * box.length[d];
    P.id.push_back(static_cast<std::int64_t>(i));
  }
  P.resize(n, n - n / 4);
  P.allocate(fieldBit(kFieldXList));
  Particles<D> Q = P;
  HashGrid<D> gridP(radius), gridQ(radius);
  PeriodicGhosts<D> ghostsP(box, radius), ghostsQ(box, radius);
  NeighbourList<D> stored, walked;
  walked.setStorage(storage);
  sortByCell(P, gridP, stored, radius, &ghostsP);
  // Built on one thread, walked on two below (threads = auto changes the
  // count between builds).
  const int threadsBefore = omp_get_max_threads();
  omp_set_num_threads(1);
  sortByCell(Q, gridQ, walked, radius, &ghostsQ);
  omp_set_num_threads(threadsBefore);
  BOOST_TEST_REQUIRE(P.totalSize() > P.size());  // ghosts were made
  const auto expected = rows(stored, P.size(), 1);
  std::size_t pairs = 0, wallRows = 0;
  for (const auto& r : expected) {
    pairs += r.size();
    wallRows += std::find(r.begin(), r.end(), -1) != r.end();
  }
  BOOST_TEST_REQUIRE(pairs > 10 * n);
  BOOST_TEST_REQUIRE(wallRows > 0u);
  BOOST_TEST((rows(walked, Q.size(), 1) == expected), D << "D, one thread, packed " << packed);
  BOOST_TEST((rows(walked, Q.size(), 2) == expected), D << "D, two threads, packed " << packed);
  BOOST_TEST(walked.pairCount() == stored.pairCount());
  // A copy (or a moved scene's list) does not point at another's build.
  const NeighbourList<D> copy = walked;
  BOOST_TEST(walked.bound());
  BOOST_TEST(!copy.bound());
  // Moved by up to a tenth of the skin: both still give the build's pairs.
  for (std::size_t i = 0; i < Q.size(); ++i)
    for (int d = 0; d < D; ++d) Q.x[i][d] += (u(rng) - 0.5) * 0.1 * skin * support;
  BOOST_TEST((rows(walked, Q.size(), 2) == expected), D << "D, after the particles moved, packed " << packed);
  // Cells: nothing stored (the row buffers, one row per thread, are not
  // counted). Packed: the bits of the candidates.
  const std::size_t share = packed ? (D == 2 ? 6 : 3) : 20;
  BOOST_TEST(walked.bytesAllocated() * share < stored.bytesAllocated(),
             walked.bytesAllocated() << " bytes against the list's " << stored.bytesAllocated() << ", packed "
                                     << packed);
}

// A run's last snapshot with the list, packed and with the cells, by particle id.
void runsAgree(const std::string& name, const std::string& end, const std::vector<std::string>& extra) {
  const auto dir = test::scratchDir("cell_walk_" + name);
  auto run = [&](const std::string& walk) {
    std::vector<std::string> args{"run", test::caseFile(name), "--output", (dir / walk).string(), "--end_time", end,
                                  "--output_interval", end, "--no-progress", "--neighbour_walk", walk};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = test::runSph(args);
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
    return test::load(dir / walk / (name + "_00001.vtp"));
  };
  const auto list = run("list");
  for (const std::string walk : {"packed", "cells"}) {
    const test::Difference d = test::compare(list, run(walk));
    BOOST_TEST(d.x == 0.0, name << ", " << walk);
    BOOST_TEST(d.v == 0.0, name << ", " << walk);
    BOOST_TEST(d.rho == 0.0, name << ", " << walk);
    BOOST_TEST(d.kinds == 0, name << ", " << walk);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(cell_walk)

BOOST_AUTO_TEST_CASE(visits_the_stored_lists_rows_in_order_2d) {
  checkRows<2>(3000, 11, NeighbourStorage::kCells);
  checkRows<2>(3000, 11, NeighbourStorage::kPacked);
}
BOOST_AUTO_TEST_CASE(visits_the_stored_lists_rows_in_order_3d) {
  checkRows<3>(4000, 12, NeighbourStorage::kCells);
  checkRows<3>(4000, 12, NeighbourStorage::kPacked);
}

BOOST_AUTO_TEST_CASE(water_dam_break_is_bit_for_bit_the_lists) {
  runsAgree("dam_break", "0.02", {"--threads", "2"});
}
BOOST_AUTO_TEST_CASE(periodic_channel_is_bit_for_bit_the_lists) {
  runsAgree("poiseuille_2d", "0.05", {"--threads", "1"});
}
BOOST_AUTO_TEST_CASE(no_skin_with_corrections_is_bit_for_bit_the_lists) {
  runsAgree("dam_break", "0.01",
            {"--threads", "1", "--neighbour_skin", "0", "--gradient_correction", "cspm", "--density_reinit", "mls",
             "--density_reinit_every", "5"});
}
BOOST_AUTO_TEST_CASE(periodic_channel_3d_is_bit_for_bit_the_lists) {
  runsAgree("poiseuille_3d", "0.02", {"--threads", "2"});
}

BOOST_AUTO_TEST_SUITE_END()
