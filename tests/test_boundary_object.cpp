// A boundary is one type (boundaries/boundary.hpp): a new one needs its
// definition and one registration line, nothing else. "open_walls" below is
// such a boundary, defined here (and registered for the one test that uses
// it, so that the key reference does not list it): no wall particles, no passes, no
// constraint (the walls are not there at all). Registered, it is a valid
// `boundary` choice, it builds, and it runs: a block thrown at the floor
// leaves the box through it and the state check stops the run, where the
// reflecting boundary of the same case holds the block in.
#include "test_support.hpp"

#include <algorithm>
#include <string>

using namespace sph;

namespace {

struct OpenWalls : NoWallsBoundary {
  static constexpr const char* name = "open_walls";
  static constexpr const char* summary = "walls that let everything through (a test's boundary)";
};

CaseConfig thrownBlock(const std::string& boundary) {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = "wendland_c2";
  c.eos = "tait";
  c.c0 = 40;
  c.h = 0.015;
  c.spacing = 0.01;
  c.walls = true;
  c.boundary = boundary;
  c.domainMin = {0, 0};
  c.domainMax = {1, 1};
  c.blockMin = {0.4, 0.02};
  c.blockMax = {0.6, 0.2};
  c.blockVelocity = {0, -2};  // the lowest row (y = 0.025) reaches y = 0 after 12.5 ms
  c.dt = 1e-4;
  c.endTime = 1;
  return c;
}

// Steps until the state check fails (or `steps`), and what failed.
std::pair<long, std::string> runUntilFailure(Scene<2>& s, long steps) {
  for (long n = 1; n <= steps; ++n)
    if (const auto failure = s.step()) return {n, failure->quantity};
  return {steps, ""};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(boundary_object)

BOOST_AUTO_TEST_CASE(a_boundary_defined_in_a_test_is_a_choice_and_runs) {
  const BoundaryRegistration registered = registerBoundary<OpenWalls>();  // the one registration line
  const auto names = methodNames(boundaryMethods());
  BOOST_TEST((std::find(names.begin(), names.end(), "open_walls") != names.end()));

  Scene<2> open = test::sceneOf<2>(thrownBlock("open_walls"));
  // No wall particles and no pass of its own: the terms of a case without walls.
  BOOST_TEST(open.particles().size() == open.particles().fluidCount());
  CaseConfig noWalls = thrownBlock("reflecting");
  noWalls.walls = false;
  BOOST_TEST(open.model().termNames() == test::sceneOf<2>(noWalls).model().termNames(),
             boost::test_tools::per_element());

  // Nothing stops the block: a particle of its lowest row leaves through
  // the floor within 200 steps (at step 76: the row reaches y = 0 after
  // 12.5 ms at 2 m/s, sooner where the free surface's pressure speeds it).
  const auto [openSteps, why] = runUntilFailure(open, 200);
  BOOST_TEST(openSteps < 200);
  BOOST_TEST(why == "domain");

  Scene<2> reflecting = test::sceneOf<2>(thrownBlock("reflecting"));
  const auto [steps, none] = runUntilFailure(reflecting, 200);
  BOOST_TEST(none.empty(), none);
  BOOST_TEST(steps == 200);
}

BOOST_AUTO_TEST_CASE(each_boundary_states_what_the_sums_take_from_its_walls) {
  const Boundary reflecting = describeBoundary<ReflectingBoundary>(), dummy = describeBoundary<DummyBoundary>(),
                 dynamic = describeBoundary<DynamicBoundary>(), repulsive = describeBoundary<RepulsiveBoundary>();
  BOOST_TEST(!reflecting.wallParticles());
  BOOST_TEST((dummy.particles == WallLattice::kLayers && dynamic.particles == WallLattice::kLayers));
  BOOST_TEST((repulsive.particles == WallLattice::kOnSurface));
  BOOST_TEST((dummy.sums.inSums && !dummy.sums.densityRates));
  BOOST_TEST((dynamic.sums.inSums && dynamic.sums.densityRates));
  BOOST_TEST((!repulsive.sums.inSums && !repulsive.sums.densityRates));
  BOOST_TEST((dummy.wallDensityFromFluid && !dynamic.wallDensityFromFluid && !repulsive.wallDensityFromFluid));
}

BOOST_AUTO_TEST_SUITE_END()
