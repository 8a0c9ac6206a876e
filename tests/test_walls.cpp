// Wall particles: generation (layers, spacing, no overlap with the fluid),
// kinds kept through sorting, the layer count refused when too small, each
// boundary holding a small water column at rest, and the Adami
// extrapolation against a hand-worked example.
#include "test_support.hpp"

#include "sph/wall_particles.hpp"

#include <algorithm>
#include <map>

using namespace sph;

namespace {

// A tank 0.2 wide (and deep in 3D) with water 0.1 deep, dx = 0.01, Wendland
// with h = 1.5 dx (support 3 dx: three wall layers).
CaseConfig tank(int dimension, const std::string& boundary) {
  CaseConfig c;
  c.model = "wcsph";
  c.dimension = dimension;
  c.kernel = "wendland_c2";
  c.spacing = 0.01;
  c.h = 0.015;
  c.eos = "tait";
  c.c0 = 10;  // 10 sqrt(g H)
  c.density = "continuity";
  c.delta = 0.1;
  c.viscosity = "monaghan";
  c.alpha = 0.05;
  c.beta = 0;
  c.boundary = boundary;
  c.dt = 2e-4;
  const auto D = static_cast<std::size_t>(dimension);
  c.domainMin.assign(D, 0);
  c.domainMax.assign(D, 0.2);
  c.blockMin.assign(D, 0);
  c.blockMax.assign(D, 0.2);
  c.blockMax[D - 1] = 0.1;
  return c;
}

template <int D>
std::vector<Vec<D>> wallsOf(const Particles<D>& P) {
  return {P.x.begin() + static_cast<long>(P.fluidCount()), P.x.end()};
}

Real nearest(const std::vector<Vec<2>>& from, const Vec<2>& x) {
  Real best = 1e9;
  for (const auto& y : from)
    if ((y - x).norm() > 0) best = std::min(best, (y - x).norm());
  return best;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(walls)

// Three layers at dx behind the floor and the side walls (open top): on
// each axis 20 lattice points inside plus 3 below (and 3 above where the
// box is closed), less the 20^D inside.
BOOST_AUTO_TEST_CASE(layers_count_spacing_and_no_overlap) {
  CaseConfig c = tank(2, "dummy");
  BOOST_TEST(wallLayersNeeded(c) == 3);
  const auto init = buildInitialState<2>(withDefaults(c));
  const auto& P = init.particles;
  BOOST_TEST(P.fluidCount() == 200u);
  BOOST_TEST(P.size() - P.fluidCount() == (20u + 6) * (20 + 3) - 20 * 20);
  const auto w = wallsOf(P);
  const std::vector<Vec<2>> fluid(P.x.begin(), P.x.begin() + 200);
  Real lowest = 1;
  for (const auto& x : w) {
    // Every wall particle lies outside the box, on the fluid lattice.
    BOOST_TEST((x[0] < 0 || x[0] > 0.2 || x[1] < 0));
    BOOST_TEST(nearest(w, x) == 0.01, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(nearest(fluid, x) >= 0.01 * (1 - 1e-9));
    lowest = std::min(lowest, x[1]);
    BOOST_TEST(P.m[&x - &w[0] + 200] == 1000 * 0.01 * 0.01, boost::test_tools::tolerance(1e-12));
  }
  BOOST_TEST(lowest == -0.025, boost::test_tools::tolerance(1e-9));  // the third layer
  // A lid adds three layers on top; 3D has the same rule on every axis.
  c.lid = true;
  BOOST_TEST(buildInitialState<2>(withDefaults(c)).particles.size() == 200u + 26 * 26 - 20 * 20);
  CaseConfig c3 = tank(3, "dynamic");
  const auto P3 = buildInitialState<3>(withDefaults(c3)).particles;
  BOOST_TEST(P3.size() - P3.fluidCount() == 26u * 26 * 23 - 20 * 20 * 20);
}

BOOST_AUTO_TEST_CASE(repulsive_walls_are_one_layer_at_half_spacing) {
  const CaseConfig c = tank(2, "repulsive");
  const auto P = buildInitialState<2>(withDefaults(c)).particles;
  const auto w = wallsOf(P);
  // Floor and two side walls of the open box, on the wall lines, ends shared:
  // 41 + 2 x 40 points at dx/2.
  BOOST_TEST(w.size() == 41u + 2 * 40);
  for (const auto& x : w) {
    BOOST_TEST((x[0] == 0 || x[0] == 0.2 || x[1] == 0));
    BOOST_TEST(nearest(w, x) == 0.005, boost::test_tools::tolerance(1e-9));
  }
}

BOOST_AUTO_TEST_CASE(too_few_layers_is_refused_with_the_number_needed) {
  CaseConfig c = tank(2, "dummy");
  c.wallLayers = 2;
  try {
    validateCase(c);
    BOOST_FAIL("two layers were accepted");
  } catch (const CaseError& e) {
    const std::string what = e.what();
    BOOST_TEST(what.find("wall_layers = 2") != std::string::npos, what);
    BOOST_TEST(what.find("needs 3") != std::string::npos, what);
  }
  c.wallLayersOverride = true;
  BOOST_CHECK_NO_THROW(validateCase(c));
  c.wallLayers = 3;
  c.wallLayersOverride = false;
  BOOST_CHECK_NO_THROW(validateCase(c));
}

// Walls sit after the fluid through every re-sort, keep their ids and do
// not move; the fluid does.
BOOST_AUTO_TEST_CASE(kinds_survive_sorting_and_walls_stay_put) {
  CaseConfig c = tank(2, "dynamic");
  c.g = 9.81;
  Scene<2> s = test::sceneOf<2>(c);
  const auto& P = s.particles();
  std::map<std::int64_t, Vec<2>> wallAt;
  for (std::size_t i = P.fluidCount(); i < P.size(); ++i) wallAt[P.id[i]] = P.x[i];
  for (int n = 0; n < 20; ++n) BOOST_REQUIRE(!s.step());
  BOOST_TEST(P.kind.size() == P.size());
  for (std::size_t i = 0; i < P.size(); ++i) {
    BOOST_TEST(P.kind[i] == (i < P.fluidCount() ? kFluid : kWall));
    if (i < P.fluidCount()) {
      BOOST_TEST(wallAt.count(P.id[i]) == 0u);
    } else {
      BOOST_TEST_REQUIRE(wallAt.count(P.id[i]) == 1u);
      BOOST_TEST((P.x[i] - wallAt[P.id[i]]).norm() == 0.0);
    }
  }
}

// A column 0.1 deep started in hydrostatic balance stays in it for 0.3 s
// (about 30 sound crossings): mean pressure error against rho0 g (H - y)
// below 2% of rho0 g H. 2%: at ten particles of depth the kernel's lattice
// gradient error (0.3% at h = 1.5 dx), the wall truncation and the particle
// noise add up to about 1%; a boundary that does not hold the column is off
// by tens of percent within a few hundred steps. The fluid keeps its depth
// to 1%, and no particle passes a wall (the state check would stop the run).
BOOST_AUTO_TEST_CASE(each_boundary_holds_a_small_column) {
  for (const std::string boundary : {"dummy", "dynamic"}) {
    CaseConfig c = tank(2, boundary);
    c.g = 9.81;
    c.hydrostaticStart = true;
    c.endTime = 0.3;
    Scene<2> s = test::sceneOf<2>(c);
    while (s.time() < 0.3 - 1e-9) BOOST_REQUIRE(!s.step());
    const auto& P = s.particles();
    Real sum = 0, top = 0;
    for (std::size_t i = 0; i < P.fluidCount(); ++i) {
      sum += std::abs(P.p[i] - 1000 * 9.81 * (0.1 - P.x[i][1]));
      top = std::max(top, P.x[i][1]);
    }
    const Real meanError = sum / static_cast<Real>(P.fluidCount()) / (1000 * 9.81 * 0.1);
    BOOST_TEST_CONTEXT(boundary) {
      BOOST_TEST(meanError < 0.02);
      BOOST_TEST(std::abs(top + 0.005 - 0.1) < 0.001);
    }
  }
}

// The column also stands with repulsive walls for a short while, though the
// fluid sees a free surface at each wall: no particle enters the walls.
BOOST_AUTO_TEST_CASE(repulsive_walls_keep_the_fluid_in) {
  CaseConfig c = tank(2, "repulsive");
  c.g = 9.81;
  c.hydrostaticStart = true;
  Scene<2> s = test::sceneOf<2>(c);
  for (int n = 0; n < 500; ++n) BOOST_REQUIRE(!s.step());
  const auto& P = s.particles();
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    BOOST_TEST(P.x[i][0] > 0.0);
    BOOST_TEST(P.x[i][0] < 0.2);
    BOOST_TEST(P.x[i][1] > 0.0);
  }
}

// Adami 2012 eq. 27 by hand: one wall particle below two fluid particles.
BOOST_AUTO_TEST_CASE(adami_extrapolation_matches_a_hand_worked_example) {
  Particles<2> P;
  P.x = {Vec<2>(0, 0.01), Vec<2>(0.01, 0.015), Vec<2>(0, 0)};  // f1, f2, wall
  P.v = {Vec<2>(1, 0), Vec<2>(0, 2), Vec<2>::Zero()};
  P.m = {0.1, 0.1, 0.1};
  P.id = {0, 1, 2};
  P.resize(3, 2);
  P.allocate(fieldBit(kFieldVWall));
  HashGrid<2> grid(0.03);
  grid.build(P.x, 2);
  P.permute(grid.order());
  for (std::size_t i = 0; i < 3; ++i) {  // pressures and densities by id, after the sort
    P.p[i] = P.id[i] == 0 ? 100 : P.id[i] == 1 ? 300 : 0;
    P.rho[i] = P.id[i] == 0 ? 1000 : P.id[i] == 1 ? 1010 : 0;
  }
  NeighbourList<2> nl;
  nl.build(grid, P.x, 0.03, 2);
  const WendlandC2<2> k(0.015);
  const LinearEos eos{100, 1000};
  const Vec<2> g(0, -9.81);
  extrapolateToWalls(P, nl, k, eos, g, true, 1000);
  // By hand: W1 = W(0.01), W2 = W(sqrt(0.01^2 + 0.015^2)); r_wf = x_w - x_f.
  const Real W1 = k.W(0.01), W2 = k.W(std::sqrt(0.0001 + 0.000225));
  const Real gr1 = 9.81 * 0.01, gr2 = 9.81 * 0.015;  // g . r_wf = g |dy|
  const Real pw = (100 * W1 + 300 * W2 + 1000 * gr1 * W1 + 1010 * gr2 * W2) / (W1 + W2);
  const std::size_t w = 2;  // the wall stays after the fluid
  BOOST_TEST(P.kind[w] == kWall);
  BOOST_TEST(P.p[w] == pw, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(P.rho[w] == 1000 + pw / 100, boost::test_tools::tolerance(1e-12));
  const Vec<2> vTilde = (W1 * Vec<2>(1, 0) + W2 * Vec<2>(0, 2)) / (W1 + W2);
  BOOST_TEST((P.vWall[w] + vTilde).norm() < 1e-12);  // no-slip: 2 u_w - v~ with u_w = 0
}

BOOST_AUTO_TEST_SUITE_END()
