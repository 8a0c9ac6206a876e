// Periodic boundaries (periodic_box.hpp, periodic_ghosts.hpp, hash_grid.hpp,
// neighbour_list.hpp, pair_loop.hpp): the neighbour search with ghosts against an O(N^2) brute force with
// the minimum image, on random points, points on the faces and in boxes only
// two to four supports wide, along every subset of the axes in 2D and 3D;
// r_ij of the pair loop against the brute-force nearest image; wrapping;
// the case key; no wall particles on periodic faces; and momentum kept to
// round-off in a fully periodic box (no wall, no body force: the sum of the
// antisymmetric pair forces is zero only if every pair is seen from both
// sides with opposite r_ij).
#include "sph/hash_grid.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/particles.hpp"
#include "sph/periodic_box.hpp"
#include "sph/periodic_ghosts.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/summation_density.hpp"
#include "sph/kernels/seed_kernels.hpp"
#include "sph/wall_particles.hpp"
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

using namespace sph;

namespace {

using PairSet = std::set<std::pair<std::int64_t, std::int64_t>>;

// The nearest image by brute force: every image shift in {-1, 0, 1} per
// periodic axis, the shortest one (independent of PeriodicBox::minimumImage).
template <int D>
Vec<D> nearestImage(const Vec<D>& xi, const Vec<D>& xj, const PeriodicBox<D>& box) {
  Vec<D> best = xi - xj;
  const int images = static_cast<int>(std::pow(3, D));
  for (int k = 0; k < images; ++k) {
    Vec<D> shift = Vec<D>::Zero();
    int rest = k;
    bool allowed = true;
    for (int d = 0; d < D; ++d, rest /= 3) {
      const int s = rest % 3 - 1;
      if (s != 0 && !box.periodic(d)) allowed = false;
      shift[d] = s * box.length[d];
    }
    if (!allowed) continue;
    const Vec<D> r = xi - xj + shift;
    if (r.squaredNorm() < best.squaredNorm()) best = r;
  }
  return best;
}

template <int D>
PairSet bruteForce(const std::vector<Vec<D>>& x, const std::vector<std::int64_t>& id, Real radius,
                   const PeriodicBox<D>& box) {
  PairSet pairs;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < x.size(); ++j)
      if (i != j && nearestImage<D>(x[i], x[j], box).squaredNorm() < radius * radius) pairs.insert({id[i], id[j]});
  return pairs;
}

// Random points in the box (non-periodic axes: the box too, the grid does
// not care), a fifth of them put exactly on a face (lo, or the largest
// double below hi) along a random axis.
template <int D>
std::vector<Vec<D>> randomPoints(std::size_t n, const PeriodicBox<D>& box, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(0, 1);
  std::vector<Vec<D>> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < D; ++d) x[i][d] = box.lo[d] + u(rng) * box.length[d];
    if (i % 5 == 0) {
      const int d = static_cast<int>(rng() % D);
      const Real hi = box.lo[d] + box.length[d];
      x[i][d] = (rng() % 2) ? box.lo[d] : std::nextafter(hi, box.lo[d]);
    }
  }
  return x;
}

// Sort with the ghosts, build the list, check every pair (ghosts carry their
// source's id) against brute force and every r_ij the pair loop forms
// against the brute-force nearest image.
template <int D>
void checkPeriodicSearch(const PeriodicBox<D>& box, Real radius, std::size_t n, unsigned seed) {
  Particles<D> P;
  P.x = randomPoints<D>(n, box, seed);
  for (std::size_t i = 0; i < n; ++i) P.id.push_back(static_cast<std::int64_t>(i));
  P.resize(n);
  const PairSet expected = bruteForce<D>(P.x, P.id, radius, box);
  BOOST_TEST_REQUIRE(!expected.empty());

  HashGrid<D> grid(radius);
  NeighbourList<D> list;
  PeriodicGhosts<D> ghosts(box, radius);
  sortByCell(P, grid, list, radius, &ghosts);
  PairSet found;
  std::size_t count = 0;
  Real worst = 0;
  for (std::size_t i = 0; i < P.size(); ++i)
    forEachNeighbourSeparation(P, list, i, [&](std::uint32_t j, const Vec<D>& rij) {
      found.insert({P.id[i], P.id[j]});
      ++count;
      worst = std::max(worst, (rij - nearestImage<D>(P.x[i], P.x[j], box)).cwiseAbs().maxCoeff());
    });
  BOOST_TEST(count == found.size());  // each neighbour listed once
  BOOST_TEST((found == expected), "periodic axes " << box.axes << ", box " << box.length.transpose() << " / support "
                                                   << radius << ": " << found.size() << " pairs found, "
                                                   << expected.size() << " expected");
  // The pair loop's r_ij is x_i - x_j shifted by whole box lengths: exact
  // up to the rounding of that one subtraction.
  BOOST_TEST(worst <= 1e-12 * box.length.maxCoeff());
}


// Points in the box with a fifth of them on the faces, and every corner of
// the box ({lo, the largest double below hi} per axis) and the middle of
// every edge/face, where the ghosts get their combined shifts.
template <int D>
std::vector<Vec<D>> pointsWithCorners(std::size_t n, const PeriodicBox<D>& box, unsigned seed) {
  std::vector<Vec<D>> x = randomPoints<D>(n, box, seed);
  const int combos = static_cast<int>(std::pow(3, D));
  for (int k = 0; k < combos; ++k) {
    Vec<D> c;
    int rest = k;
    for (int d = 0; d < D; ++d, rest /= 3) {
      const Real lo = box.lo[d], hi = lo + box.length[d];
      const int which = rest % 3;
      c[d] = which == 0 ? lo : which == 1 ? std::nextafter(hi, lo) : lo + 0.5 * box.length[d];
    }
    x.push_back(c);
  }
  return x;
}

// Ghosts against an O(N^2) minimum-image reference, with walls (the last
// quarter of the particles, so ghosts of walls too): for every owned
// particle its fluid and wall neighbour sets (by id) and its summed density
// rho_i = sum_j m_j W(|r_ij|) (the seed's density kernel, walls included),
// r_ij the nearest image. Returns the number of particles checked.
template <int D>
void checkGhostsAgainstMinimumImage(const PeriodicBox<D>& box, Real support, std::size_t n, unsigned seed) {
  Particles<D> P;
  P.x = pointsWithCorners<D>(n, box, seed);
  const std::size_t total = P.x.size(), nFluid = total - total / 4;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(0.5, 1.5);
  for (std::size_t i = 0; i < total; ++i) {
    P.id.push_back(static_cast<std::int64_t>(i));
    P.m.push_back(u(rng));
  }
  P.resize(total, nFluid);
  const std::vector<Vec<D>> x0 = P.x;
  const std::vector<Narrow> m0 = P.m;
  const SeedKernels W(support);

  // The reference, on the unsorted points.
  std::map<std::int64_t, std::set<std::int64_t>> fluidNear, wallNear;
  std::map<std::int64_t, Real> rhoRef;
  for (std::size_t i = 0; i < total; ++i) {
    Real rho = m0[i] * W.densityAtZero();
    for (std::size_t j = 0; j < total; ++j) {
      if (i == j) continue;
      const Real r2 = nearestImage<D>(x0[i], x0[j], box).squaredNorm();
      if (!(r2 < support * support)) continue;
      rho += m0[j] * W.density(r2);
      if (i >= nFluid && j >= nFluid) continue;  // no method couples two walls
      (j < nFluid ? fluidNear : wallNear)[static_cast<std::int64_t>(i)].insert(static_cast<std::int64_t>(j));
    }
    rhoRef[static_cast<std::int64_t>(i)] = rho;
  }

  HashGrid<D> grid(support);
  NeighbourList<D> list;
  PeriodicGhosts<D> ghosts(box, support);
  sortByCell(P, grid, list, support, &ghosts);
  BOOST_TEST_REQUIRE(P.size() == total);  // ghosts are not counted
  BOOST_TEST_REQUIRE(P.totalSize() > total);
  computeSummationDensity(P, list, W, LinearEos{1, 1});  // fluid particles only
  std::size_t setErrors = 0;
  Real worstRho = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    std::set<std::int64_t> fluid, wall;
    std::size_t listed = 0;
    list.forEachByKind(
        i,
        [&](std::uint32_t j) {
          BOOST_TEST_REQUIRE((j < nFluid || (j >= P.size() && j < P.ghostFluidEnd())));
          fluid.insert(P.id[j]);
          ++listed;
        },
        [&](std::uint32_t j) {
          BOOST_TEST_REQUIRE((j >= P.ghostFluidEnd() || (j >= nFluid && j < P.size())));
          wall.insert(P.id[j]);
          ++listed;
        });
    setErrors += listed != fluid.size() + wall.size();  // each neighbour once
    setErrors += fluid != fluidNear[P.id[i]];
    setErrors += wall != wallNear[P.id[i]];
    if (i < nFluid) worstRho = std::max(worstRho, std::abs(P.rho[i] / rhoRef[P.id[i]] - 1));
  }
  BOOST_TEST(setErrors == 0u, "periodic axes " << box.axes << ", box " << box.length.transpose() << " / support "
                                               << support << ": " << setErrors << " wrong neighbour sets");
  // Summation order differs from the reference's: round-off of ~50 terms.
  BOOST_TEST(worstRho < 1e-12);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(periodic)

// Every subset of the axes, in boxes 2, 2.5, 3 and 4.3 supports wide (two
// supports: the stencil's -1 and +1 cells are the same cell).
BOOST_AUTO_TEST_CASE(search_matches_brute_force_2d) {
  const Real radius = 0.1;
  unsigned seed = 1;
  for (unsigned axes = 1; axes < 4; ++axes)
    for (Real width : {2.0, 2.5, 3.0, 4.3}) {
      PeriodicBox<2> box{Vec<2>(-0.3, 0.7), Vec<2>(width * radius, 1.7 * width * radius), axes};
      checkPeriodicSearch<2>(box, radius, 300, seed++);
    }
}

BOOST_AUTO_TEST_CASE(search_matches_brute_force_3d) {
  const Real radius = 0.1;
  unsigned seed = 100;
  for (unsigned axes = 1; axes < 8; ++axes)
    for (Real width : {2.0, 3.0, 4.3}) {
      PeriodicBox<3> box{Vec<3>(0.2, -1.0, 5.0), Vec<3>(width * radius, 1.3 * width * radius, 2.2 * radius * width), axes};
      checkPeriodicSearch<3>(box, radius, 400, seed++);
    }
}

// A large box with many cells per axis and more points: the hashed table
// is full and the stencil wraps at both faces.
BOOST_AUTO_TEST_CASE(search_matches_brute_force_many_cells) {
  checkPeriodicSearch<2>(PeriodicBox<2>{Vec<2>(0, 0), Vec<2>(1.0, 0.63), 3u}, 0.05, 1500, 7);
  checkPeriodicSearch<3>(PeriodicBox<3>{Vec<3>(0, 0, 0), Vec<3>(0.5, 0.4, 0.3), 5u}, 0.07, 1500, 8);
}

BOOST_AUTO_TEST_CASE(wrap_brings_positions_into_the_box) {
  const PeriodicBox<2> box{Vec<2>(-1, 0), Vec<2>(2, 1), 1u};  // x periodic in [-1, 1)
  Vec<2> x(1.25, 3);
  box.wrap(x);
  BOOST_TEST(x[0] == -0.75);
  BOOST_TEST(x[1] == 3);  // not periodic: left alone
  x = Vec<2>(-1.5, 0);
  box.wrap(x);
  BOOST_TEST(x[0] == 0.5);
  x = Vec<2>(1, 0);  // on the upper face: that is the lower face
  box.wrap(x);
  BOOST_TEST(x[0] == -1);
  x = Vec<2>(-1 - 1e-17, 0);  // rounds to -1 + 2 = 1: must land on -1
  box.wrap(x);
  BOOST_TEST(x[0] >= -1);
  BOOST_TEST(x[0] < 1);
}

BOOST_AUTO_TEST_CASE(key_is_checked) {
  CaseConfig c = test::bareWcsph(2);
  c.domainMin = {0, 0};
  c.domainMax = {1, 1};
  c.h = 0.1;  // cubic spline: support 0.2, two supports 0.4
  c.points = {0.5, 0.5};
  for (const char* ok : {"x", "y", "xy", "yx", "none", ""}) {
    c.periodic = ok;
    BOOST_CHECK_NO_THROW(validateCase(c));
  }
  for (const char* bad : {"z", "xx", "X", "x y", "xz"}) {
    c.periodic = bad;
    BOOST_CHECK_THROW(validateCase(c), CaseError);
  }
  c.periodic = "x";
  c.domainMax = {0.39, 1};  // less than two supports along x
  BOOST_CHECK_THROW(validateCase(c), CaseError);
  c.dimension = 3;
  c.domainMin = {0, 0, 0};
  c.domainMax = {1, 1, 1};
  c.points = {0.5, 0.5, 0.5};
  c.periodic = "xz";
  BOOST_CHECK_NO_THROW(validateCase(c));
  BOOST_TEST(periodicAxes(c) == 5u);
}

// Dummy walls periodic along x: walls only below (and above, with a lid),
// none left or right of the box, and the bottom layers span [0, L) along x
// at the fluid spacing.
BOOST_AUTO_TEST_CASE(no_wall_particles_on_periodic_faces) {
  CaseConfig c;
  c.model = "wcsph";
  c.boundary = "dummy";
  c.spacing = 0.1;
  c.h = 0.13;
  c.domainMin = {0, 0};
  c.domainMax = {1, 1};
  c.lid = true;
  c.periodic = "x";
  validateCase(c);
  const int layers = wallLayersNeeded(c);
  const auto walls = wallParticlePositions<2>(withDefaults(c), layers);
  BOOST_TEST(walls.size() == static_cast<std::size_t>(2 * layers * 10));
  for (const auto& w : walls) {
    BOOST_TEST((w[0] > 0 && w[0] < 1));
    BOOST_TEST((w[1] < 0 || w[1] > 1));
  }
  c.periodic = "";
  BOOST_TEST(wallParticlePositions<2>(withDefaults(c), layers).size() > walls.size());
}

// A fully periodic box of fluid with random velocities and pressure,
// viscosity and XSPH: total momentum must stay at its start value to
// round-off (pair forces antisymmetric), and positions inside the box.
BOOST_AUTO_TEST_CASE(momentum_kept_in_a_periodic_box) {
  for (int D : {2, 3}) {
    CaseConfig c = test::bareWcsph(D);
    c.h = 0.13;
    c.spacing = 0.1;
    c.k = 200;
    c.viscosity = "laplacian";
    c.mu = 0.5;
    c.dt = 1e-3;  // c dt / h = 0.11
    c.periodic = D == 2 ? "xy" : "xyz";
    c.domainMin.assign(static_cast<std::size_t>(D), 0);
    c.domainMax.assign(static_cast<std::size_t>(D), D == 2 ? 1.0 : 0.6);
    c.blockMin = c.domainMin;
    c.blockMax = c.domainMax;
    auto run = [&](auto scene, bool scaleMass) {
      auto& P = scene.particles();
      std::mt19937 rng(3);
      std::normal_distribution<Real> u(0, 0.3);
      for (auto& v : P.v)
        for (int d = 0; d < static_cast<int>(v.size()); ++d) v[d] = u(rng);
      using V = std::decay_t<decltype(P.v[0])>;
      BOOST_REQUIRE(!scene.initialise(scaleMass));
      V p0 = V::Zero();
      std::map<std::int64_t, V> start;
      for (std::size_t i = 0; i < P.size(); ++i) p0 += P.m[i] * P.v[i], start[P.id[i]] = P.x[i];
      Real scale = 0;
      for (std::size_t i = 0; i < P.size(); ++i) scale += P.m[i] * P.v[i].norm();
      for (int s = 0; s < 200; ++s) BOOST_REQUIRE(!scene.step());
      V p1 = V::Zero();
      std::size_t wrapped = 0;
      for (std::size_t i = 0; i < P.size(); ++i) {
        wrapped += (P.x[i] - start[P.id[i]]).cwiseAbs().maxCoeff() > 0.5 * c.domainMax[0];
        p1 += scene.particles().m[i] * scene.particles().v[i];
        // Wrapped into the box at the list's last rebuild: since then a
        // particle moved at most half the skin (neighbour-search.md).
        const Real slack = scene.neighbourSkin() * scene.support() / 2;
        for (int d = 0; d < static_cast<int>(p1.size()); ++d) {
          BOOST_TEST(scene.particles().x[i][d] >= c.domainMin[static_cast<std::size_t>(d)] - slack);
          BOOST_TEST(scene.particles().x[i][d] < c.domainMax[static_cast<std::size_t>(d)] + slack);
        }
      }
      // Round-off of 200 steps of sums of N ~ 1000 terms: 1e-12 of the
      // momentum scale. A pair seen from one side only gives ~1e-3.
      BOOST_TEST((p1 - p0).norm() <= 1e-12 * scale, "D = " << D << ": momentum drift " << (p1 - p0).norm()
                                                            << " of " << scale);
      BOOST_TEST(wrapped > 0u, "no particle crossed a periodic face");
    };
    validateCase(c);
    const ResolvedCase cd = withDefaults(c);
    if (D == 2) {
      auto init = buildInitialState<2>(cd);
      const bool scale = !init.massesGiven;
      run(makeScene<2>(cd, std::move(init)), scale);
    } else {
      auto init = buildInitialState<3>(cd);
      const bool scale = !init.massesGiven;
      run(makeScene<3>(cd, std::move(init)), scale);
    }
  }
}

// After every step the range table holds fluid, walls, their ghosts in
// that order, and each ghost holds its source's value of every field a
// pass may read at a neighbour (x plus the ghost's shift): the scene
// refreshes after an advance only the declared state the integrator
// advances and what its finish() writes (integrator_support.hpp), and
// every pass the fields it declares it writes. Every integrator, continuity
// and summation density, with and without a Verlet skin (no sort between
// most steps), Adami walls across the periodic faces, 40 steps. The
// integrator's own fields (its stages, or what it carries from step to
// step) and the fields read only at their own particle (fields.hpp) are
// never read at a neighbour and may be stale in a ghost. Exact
// equality: a ghost's fields are copies.
BOOST_AUTO_TEST_CASE(ghosts_hold_their_sources_fields_after_every_step) {
  for (const char* integrator : {"leap_frog", "symplectic_euler", "rk4", "euler", "two_step_leap_frog"})
    for (const bool continuity : {true, false})
      for (const Real skin : {0.0, 0.3}) {
        CaseConfig c = test::bareWcsph(2);
        c.h = 0.026;
        c.spacing = 0.02;
        c.k = 200;
        c.g = 9.81;
        c.dt = 2e-4;  // c dt / h = 0.11
        c.integrator = integrator;
        c.density = continuity ? "continuity" : "summation";
        c.delta = continuity ? 0.1 : 0;
        c.neighbourSkin = skin;
        c.given.insert("neighbour_skin");
        c.walls = true;
        c.boundary = "dummy";
        c.periodic = "x";
        c.domainMin = {0, 0};
        c.domainMax = {0.6, 0.5};
        c.blockMin = {0, 0};
        c.blockMax = {0.6, 0.3};
        Scene<2> scene = test::sceneOf<2>(c);
        BOOST_REQUIRE(scene.neighbourSkin() == skin);
        Particles<2>& P = scene.particles();
        std::mt19937 rng(7);
        std::normal_distribution<Real> u(0, 0.3);
        for (std::size_t i = 0; i < P.fluidCount(); ++i) P.v[i] = Vec<2>(u(rng), u(rng));
        const FieldSet own = std::visit([&](const auto& i) { return i.needs(continuity); }, scene.integrator());
        const FieldSet checked = P.refreshed() & ~own;
        std::size_t stale = 0, compared = 0, ghosts = 0;
        for (int s = 0; s < 40; ++s) {
          BOOST_REQUIRE(!scene.step());
          const std::size_t owned = P.size();
          ghosts += P.ghostSource().size();
          // The range table: contiguous, covering every particle, each
          // range holding its kind (a ghost its source's).
          std::size_t next = 0, misplaced = 0;
          for (ParticleRange r : {ParticleRange::kFluid, ParticleRange::kWalls, ParticleRange::kFluidGhosts,
                                  ParticleRange::kWallGhosts}) {
            const IndexRange in = P.range(r);
            BOOST_REQUIRE(in.begin == next);
            next = in.end;
            const bool walls = r == ParticleRange::kWalls || r == ParticleRange::kWallGhosts;
            for (std::size_t i = in.begin; i < in.end; ++i) {
              const std::size_t self = i < owned ? i : P.ghostSource()[i - owned];
              misplaced += (P.kind[self] == kWall) != walls;
            }
          }
          BOOST_REQUIRE(next == P.totalSize());
          BOOST_TEST(misplaced == 0u);
          BOOST_TEST(!P.range(ParticleRange::kWallGhosts).empty());
          for (std::size_t g = 0; g < P.ghostSource().size(); ++g) {
            const std::size_t source = P.ghostSource()[g], k = owned + g;
            P.forEachField([&](const FieldInfo& info, const auto& field) {
              if (((checked >> info.id) & 1u) == 0) return;
              ++compared;
              if (info.id == kFieldX) stale += !(P.x[k] == Vec<2>(P.x[source] + P.ghostShift()[g]));
              else stale += !(field[k] == field[source]);
            });
          }
        }
        BOOST_TEST(ghosts > 0u);
        BOOST_TEST(stale == 0u, integrator << (continuity ? ", continuity" : ", summation") << ", skin " << skin
                                           << ": " << stale << " of " << compared << " ghost fields stale");
      }
}

// Ghosts, with walls, against the minimum image: boxes 2, 2.5, 3 and 4
// supports wide, every subset of the axes, points on the faces, edges and
// corners, 2D and 3D.
BOOST_AUTO_TEST_CASE(ghosts_match_minimum_image_2d) {
  unsigned seed = 300;
  for (unsigned axes = 1; axes < 4; ++axes)
    for (Real width : {2.0, 2.5, 3.0, 4.0})
      checkGhostsAgainstMinimumImage<2>(PeriodicBox<2>{Vec<2>(-0.3, 0.7), Vec<2>(width * 0.1, 1.3 * width * 0.1), axes},
                                        0.1, 250, seed++);
}

BOOST_AUTO_TEST_CASE(ghosts_match_minimum_image_3d) {
  unsigned seed = 400;
  for (unsigned axes = 1; axes < 8; ++axes)
    for (Real width : {2.0, 3.0, 4.0})
      checkGhostsAgainstMinimumImage<3>(
          PeriodicBox<3>{Vec<3>(0.2, -1.0, 5.0), Vec<3>(width * 0.1, 1.2 * width * 0.1, 1.1 * width * 0.1), axes}, 0.1,
          350, seed++);
}

BOOST_AUTO_TEST_SUITE_END()
