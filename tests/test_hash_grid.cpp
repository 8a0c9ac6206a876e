// Neighbour search (hashed grid + neighbour list) against an O(N^2)
// brute-force search: random, clustered and sparse points, points on cell
// faces, negative coordinates, hash collisions, and after a re-sort.
#include "sph/hash_grid.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"

#include <boost/test/unit_test.hpp>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

using namespace sph;

namespace {

template <int D>
using PairSet = std::set<std::pair<std::int64_t, std::int64_t>>;

// Pairs (id_i, id_j), i != j, with |x_i - x_j| < radius.
template <int D>
PairSet<D> bruteForce(const std::vector<Vec<D>>& x, const std::vector<std::int64_t>& id, Real radius) {
  PairSet<D> pairs;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < x.size(); ++j)
      if (i != j && (x[i] - x[j]).squaredNorm() < radius * radius) pairs.insert({id[i], id[j]});
  return pairs;
}

// Sort by cell, build the list, and return its pairs by id. Also checks that
// each particle's neighbours are listed once.
template <int D>
PairSet<D> gridSearch(Particles<D>& P, Real radius) {
  HashGrid<D> grid(radius);
  grid.build(P.x);
  P.permute(grid.order());
  NeighbourList<D> list;
  list.build(grid, P.x, radius);
  PairSet<D> pairs;
  std::size_t count = 0;
  for (std::size_t i = 0; i < P.size(); ++i)
    list.forEach(i, [&](std::uint32_t j) {
      pairs.insert({P.id[i], P.id[j]});
      ++count;
    });
  BOOST_TEST(count == pairs.size());  // no duplicates
  BOOST_TEST(count == list.pairCount());
  return pairs;
}

template <int D>
Particles<D> particlesAt(const std::vector<Vec<D>>& x) {
  Particles<D> P;
  P.x = x;
  for (std::size_t i = 0; i < x.size(); ++i) P.id.push_back(static_cast<std::int64_t>(i));
  P.resize(x.size());
  return P;
}

template <int D>
void checkAgainstBruteForce(const std::vector<Vec<D>>& x, Real radius) {
  Particles<D> P = particlesAt<D>(x);
  const PairSet<D> expected = bruteForce<D>(P.x, P.id, radius);
  BOOST_TEST_REQUIRE(!expected.empty());
  const PairSet<D> found = gridSearch<D>(P, radius);
  BOOST_TEST((found == expected));
  // Move every particle a little and search again on the re-sorted arrays.
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> jitter(-0.3 * radius, 0.3 * radius);
  for (auto& xi : P.x)
    for (int d = 0; d < D; ++d) xi[d] += jitter(rng);
  const PairSet<D> expected2 = bruteForce<D>(P.x, P.id, radius);
  BOOST_TEST((gridSearch<D>(P, radius) == expected2));
}

template <int D>
std::vector<Vec<D>> uniform(std::size_t n, Real lo, Real hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(lo, hi);
  std::vector<Vec<D>> x(n);
  for (auto& xi : x)
    for (int d = 0; d < D; ++d) xi[d] = u(rng);
  return x;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(hash_grid)

BOOST_AUTO_TEST_CASE(random_points_2d) { checkAgainstBruteForce<2>(uniform<2>(2000, 0, 1, 1), 0.03); }
BOOST_AUTO_TEST_CASE(random_points_3d) { checkAgainstBruteForce<3>(uniform<3>(2000, 0, 1, 2), 0.08); }

BOOST_AUTO_TEST_CASE(negative_coordinates_3d) {
  checkAgainstBruteForce<3>(uniform<3>(1500, -2.0, -1.2, 3), 0.1);
}

// Points on a lattice whose spacing is the cell size: many pairs at exactly
// the radius (excluded) and points exactly on cell faces.
BOOST_AUTO_TEST_CASE(points_on_cell_faces_2d) {
  std::vector<Vec<2>> x;
  const Real r = 0.1;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      x.push_back(Vec<2>(i * r, j * r));
      x.push_back(Vec<2>(i * r + 0.5 * r, j * r + 0.999999 * r));
    }
  checkAgainstBruteForce<2>(x, r);
}

BOOST_AUTO_TEST_CASE(points_on_cell_faces_3d) {
  std::vector<Vec<3>> x;
  const Real r = 0.25;
  for (int i = -4; i < 4; ++i)
    for (int j = -4; j < 4; ++j)
      for (int k = -4; k < 4; ++k) {
        x.push_back(Vec<3>(i * r, j * r, k * r));
        x.push_back(Vec<3>(i * r + 0.5 * r, j * r, k * r + 0.75 * r));
      }
  checkAgainstBruteForce<3>(x, r);
}

// A dense Gaussian cluster next to a few distant particles.
BOOST_AUTO_TEST_CASE(clustered_points_2d) {
  std::mt19937 rng(11);
  std::normal_distribution<Real> n(0.5, 0.02);
  std::vector<Vec<2>> x;
  for (int i = 0; i < 1500; ++i) x.push_back(Vec<2>(n(rng), n(rng)));
  for (int i = 0; i < 10; ++i) x.push_back(Vec<2>(3.0 + 0.01 * i, -5.0));
  checkAgainstBruteForce<2>(x, 0.01);
}

// Few particles spread over a box of ~1e8 cells: the table (64 buckets) is
// far smaller than the box, so many cells share buckets.
BOOST_AUTO_TEST_CASE(sparse_points_with_hash_collisions_2d) {
  std::vector<Vec<2>> x = uniform<2>(30, 0, 100, 5);
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i) x.push_back(x[i] + Vec<2>(0.004, 0.003));
  checkAgainstBruteForce<2>(x, 0.01);
}

BOOST_AUTO_TEST_CASE(sparse_points_with_hash_collisions_3d) {
  std::vector<Vec<3>> x = uniform<3>(30, -50, 50, 6);
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i) x.push_back(x[i] + Vec<3>(0.004, -0.003, 0.002));
  checkAgainstBruteForce<3>(x, 0.01);
}

// Walls get a table sized by their own count. A tank's walls are a thin ring
// around a box their fluid fills only in part: a ring of walls (spacing half
// the radius) around the unit square, fluid in its upper-right 0.3 x 0.3
// (whose cells' hashes exceed the walls' table: they wrap around), ten
// particles a cell. The box's cells exceed 2 n_walls, so the walls'
// table is the power of two at or above 2 n_walls, with hash collisions
// (cells far apart sharing a bucket); the fluid's table is the box's cells,
// as 2 n_fluid exceed them. The grid's bucket starts take at most (box
// cells + 4 n_walls + 1) x 4 bytes, not one table of the box's cells per kind
// (the 2D dam break at 214 910 particles: 27.5 -> about 15 grid bytes per
// particle), and the pairs, by kind, are the brute force's.
BOOST_AUTO_TEST_CASE(walls_get_a_table_of_their_own_size) {
  const Real radius = std::sqrt(10.0 / 20000);  // ten particles a cell at 20 000 in the unit square
  std::vector<Vec<2>> x = uniform<2>(1800, 0.7, 1, 11);
  const std::size_t fluid = x.size();
  const int perSide = static_cast<int>(std::ceil(2 / radius));
  for (int s = 0; s < perSide; ++s) {
    const Real t = static_cast<Real>(s) / perSide;
    for (const Vec<2>& w : {Vec<2>(t, -0.01), Vec<2>(1.01, t), Vec<2>(1 - t, 1.01), Vec<2>(-0.01, 1 - t)})
      x.push_back(w);
  }
  const std::size_t walls = x.size() - fluid;
  Particles<2> P = particlesAt<2>(x);
  P.resize(x.size(), fluid);
  HashGrid<2> grid(radius);
  grid.build(P.x, fluid);
  P.permute(grid.order());
  const double boxCells = std::pow(std::ceil(1.02 / radius) + 3, 2);
  const double starts = static_cast<double>(grid.bytesAllocated()) - 8.0 * static_cast<double>(x.size());
  BOOST_TEST_CONTEXT("box cells " << boxCells << ", walls " << walls << ", bucket starts " << starts / 4) {
    BOOST_TEST_REQUIRE(2.0 * static_cast<double>(walls) < 0.5 * boxCells);  // collisions in the walls' table
    BOOST_TEST(starts <= 4 * (boxCells + 4.0 * static_cast<double>(walls) + 1));
  }
  // Pairs by kind: a fluid particle's fluid and wall neighbours, a wall
  // particle's fluid neighbours (the list holds no wall-wall pair).
  PairSet<2> expected, found;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < x.size(); ++j)
      if (i != j && (i < fluid || j < fluid) && (P.x[i] - P.x[j]).squaredNorm() < radius * radius)
        expected.insert({P.id[i], P.id[j]});
  BOOST_TEST_REQUIRE(expected.size() > 10 * fluid);
  NeighbourList<2> list;
  list.build(grid, P.x, radius, fluid);
  std::size_t wallPairs = 0;
  for (std::size_t i = 0; i < fluid; ++i)
    list.forEachByKind(
        i, [&](std::uint32_t j) { found.insert({P.id[i], P.id[j]}); },
        [&](std::uint32_t j) {
          found.insert({P.id[i], P.id[j]});
          ++wallPairs;
        });
  for (std::size_t i = fluid; i < x.size(); ++i)
    list.forEach(i, [&](std::uint32_t j) { found.insert({P.id[i], P.id[j]}); });
  BOOST_TEST(wallPairs > 0u);
  BOOST_TEST((found == expected));
}

// One list rebuilt with thread counts going up and down (its per-thread
// buffers and chunk bounds are reused), around the serial threshold too.
// A box the particles fill: its cells (a tenth of N here: about ten
// particles a cell, plus the margins) are far fewer than 2N, and the table
// has no more buckets than a power of two above them, not the 2-4 N of a
// sparse set: under 3 bytes per particle for the bucket starts, 11 with the
// bucket and order arrays (2N buckets would be 8-16 for the starts alone).
// It stays collision-free, so the pairs are the brute force's.
BOOST_AUTO_TEST_CASE(table_of_a_filled_box_has_about_its_cells) {
  for (const std::size_t n : {20000u, 60000u}) {
    Particles<2> P = particlesAt<2>(uniform<2>(n, 0, 1, 9));
    const Real radius = std::sqrt(10.0 / static_cast<Real>(n));  // ten particles per cell
    HashGrid<2> grid(radius);
    grid.build(P.x);
    const double bytes = static_cast<double>(grid.bytesAllocated()) / static_cast<double>(n);
    const double cells = std::pow(std::ceil(1 / radius) + 3, 2);
    BOOST_TEST_CONTEXT("n = " << n << ", box cells " << cells << ", grid " << bytes << " B/p") {
      BOOST_TEST(cells < 0.15 * static_cast<double>(n));
      BOOST_TEST(bytes < 11.0);
    }
  }
  checkAgainstBruteForce<2>(uniform<2>(3000, 0, 1, 4), std::sqrt(10.0 / 3000));
}

BOOST_AUTO_TEST_CASE(neighbour_list_survives_changing_thread_counts) {
  const int before = omp_get_max_threads();
  NeighbourList<2> list;
  for (std::size_t n : {100u, 513u, 520u, 3000u})
    for (int threads : {2, 1, 4, 3, 8, 1, 7, 2}) {
      omp_set_num_threads(threads);
      Particles<2> P = particlesAt<2>(uniform<2>(n, 0, 1, static_cast<unsigned>(n + threads)));
      const Real radius = 2.5 / std::sqrt(static_cast<Real>(n));
      const auto expected = bruteForce<2>(P.x, P.id, radius);
      HashGrid<2> grid(radius);
      grid.build(P.x);
      P.permute(grid.order());
      list.build(grid, P.x, radius);
      PairSet<2> found;
      for (std::size_t i = 0; i < P.size(); ++i) list.forEach(i, [&](std::uint32_t j) { found.insert({P.id[i], P.id[j]}); });
      BOOST_TEST_CONTEXT("n = " << n << ", threads = " << threads) {
        BOOST_TEST((found == expected));
        BOOST_TEST(list.pairCount() == expected.size());
      }
    }
  omp_set_num_threads(before);
}

namespace {

// n random particles in the unit square, each with its index as id, v (i, -i)
// and m 1 + i, so that a permutation's result can be checked.
Particles<2> numberedParticles(std::size_t n, unsigned seed) {
  Particles<2> P = particlesAt<2>(uniform<2>(n, 0, 1, seed));
  for (std::size_t i = 0; i < P.size(); ++i) {
    P.v[i] = Vec<2>(static_cast<Real>(i), -static_cast<Real>(i));
    P.m[i] = 1.0 + static_cast<Real>(i);
  }
  return P;
}

// Whether P, permuted by `order`, holds at k the data of numbered particle
// order[k] (positions x0 before the permutation): every particle once.
bool keptTheirData(const Particles<2>& P, const std::vector<Vec<2>>& x0, const std::vector<std::uint32_t>& order) {
  std::vector<bool> seen(P.size(), false);
  for (std::size_t k = 0; k < P.size(); ++k) {
    const auto i = static_cast<std::size_t>(P.id[k]);
    if (i != order[k] || seen[i] || P.x[k] != x0[i] || P.v[k][0] != static_cast<Real>(i) ||
        P.m[k] != 1.0 + static_cast<Real>(i))
      return false;
    seen[i] = true;
  }
  return true;
}

}  // namespace

// The sort is a permutation: every particle keeps its data.
BOOST_AUTO_TEST_CASE(resort_keeps_particle_data) {
  Particles<2> P = numberedParticles(500, 9);
  const std::vector<Vec<2>> x0 = P.x;
  HashGrid<2> grid(0.05);
  grid.build(P.x);
  P.permute(grid.order());
  BOOST_TEST(keptTheirData(P, x0, grid.order()));
}

// The grid's build may keep each particle's bucket number in bytes the
// caller lends (the scene lends the particles' re-sort scratch, idle until
// the permute that applies the order): the same order as with the grid's
// own array, 4 bytes per particle fewer in the grid, and the permute that
// then reuses those bytes keeps every particle's data.
BOOST_AUTO_TEST_CASE(bucket_numbers_in_lent_bytes) {
  Particles<2> P = numberedParticles(5000, 5);
  const std::vector<Vec<2>> x0 = P.x;
  HashGrid<2> own(0.03), lent(0.03);
  own.build(P.x);
  lent.build(P.x, SIZE_MAX, SIZE_MAX, SIZE_MAX, P.lendScratchBytes(4 * P.size()));
  BOOST_TEST(lent.order() == own.order());
  BOOST_TEST(own.bytesAllocated() - lent.bytesAllocated() == 4 * P.size());
  P.permute(lent.order());
  BOOST_TEST(keptTheirData(P, x0, own.order()));
}

// The list's memory is the part of its buffer ever written: the fill, one
// particle's candidates and 4096 entries ahead (NeighbourList::grow); the
// first build reserves an upper bound (every candidate), which is never
// touched beyond that and so takes no memory. One thread: one buffer.
BOOST_AUTO_TEST_CASE(neighbour_list_memory_is_its_fill_and_a_stretch_ahead) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  for (std::size_t n : {3000u, 20000u}) {
    Particles<2> P = particlesAt<2>(uniform<2>(n, 0, 1, 5));
    const Real radius = 2.5 / std::sqrt(static_cast<Real>(n));
    HashGrid<2> grid(radius);
    grid.build(P.x);
    P.permute(grid.order());
    NeighbourList<2> list;
    list.build(grid, P.x, radius);
    const std::size_t rows = (n + 1) * sizeof(std::uint32_t) + 2 * sizeof(std::size_t);
    const double buffer = static_cast<double>(list.bytesAllocated() - rows) / sizeof(std::uint32_t);
    const double pairs = static_cast<double>(list.pairCount());
    // Candidates of one particle: its 9 cells hold about 9 n radius^2 = 56.
    BOOST_TEST_CONTEXT("n = " << n << ", pairs " << pairs << ", buffer " << buffer) {
      BOOST_TEST(buffer >= pairs);
      BOOST_TEST(buffer <= pairs + 4096 + 200 + 64);
    }
  }
  omp_set_num_threads(before);
}

// Several fields of each type go through one scratch array per type (the
// gather's swap hands a field's old buffer on to the next field of its
// type): after two re-sorts, with and without carrying the rates, every
// field still belongs to its particle; the list's positions (xList) stay.
BOOST_AUTO_TEST_CASE(resort_through_shared_scratch_keeps_every_field) {
  const std::size_t n = 400, fluid = 300;
  Particles<2> P;
  P.x = uniform<2>(n, 0, 1, 11);
  for (std::size_t i = 0; i < n; ++i) P.id.push_back(static_cast<std::int64_t>(i));
  P.resize(n, fluid);
  P.allocate(fieldBit(kFieldDrho) | fieldBit(kFieldVHalf) | fieldBit(kFieldXList));
  const auto value = [](std::size_t i, int field) { return static_cast<Real>(i) + 0.001 * field; };
  for (std::size_t i = 0; i < n; ++i) {
    P.v[i] = Vec<2>(value(i, 1), -value(i, 1));
    P.vHalf[i] = Vec<2>(value(i, 2), value(i, 2));
    P.a[i] = Vec<2>(value(i, 3), 0);
    P.rho[i] = value(i, 4);
    P.drho[i] = value(i, 5);
    P.m[i] = value(i, 6);
    P.p[i] = value(i, 7);
    P.xList[i] = Vec<2>(value(i, 8), 0);
  }
  const std::vector<Vec<2>> x0 = P.x;
  for (const bool carryAll : {false, true}) {
    HashGrid<2> grid(0.05 + (carryAll ? 0.02 : 0.0));
    grid.build(P.x, fluid);
    const std::vector<Vec<2>> xListBefore = P.xList;
    const std::vector<Vec<2>> aBefore = P.a;
    P.permute(grid.order(), carryAll);
    BOOST_TEST_CONTEXT("carryAll = " << carryAll) {
      BOOST_TEST((P.xList == xListBefore));
      if (!carryAll) BOOST_TEST((P.a == aBefore));  // a rate: not permuted
      for (std::size_t k = 0; k < n; ++k) {
        const auto i = static_cast<std::size_t>(P.id[k]);
        BOOST_TEST((P.x[k] == x0[i]));
        BOOST_TEST(P.kind[k] == (i < fluid ? kFluid : kWall));
        BOOST_TEST(P.v[k][0] == value(i, 1));
        BOOST_TEST(P.vHalf[k][1] == value(i, 2));
        BOOST_TEST(P.rho[k] == value(i, 4));
        BOOST_TEST(P.drho[k] == Narrow(value(i, 5)));  // (as stored: float in a mixed build)
        BOOST_TEST(P.m[k] == Narrow(value(i, 6)));
        if (carryAll) {
          BOOST_TEST(P.a[k][0] == value(i, 3));
          BOOST_TEST(P.p[k] == Narrow(value(i, 7)));
        }
      }
    }
    // Put the rates back in the particles' order for the carried pass.
    if (!carryAll)
      for (std::size_t k = 0; k < n; ++k) {
        const auto i = static_cast<std::size_t>(P.id[k]);
        P.a[k] = Vec<2>(value(i, 3), 0);
        P.p[k] = value(i, 7);
      }
  }
}

BOOST_AUTO_TEST_SUITE_END()
