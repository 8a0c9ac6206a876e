// Mass scaling: after m = N rho0 / sum rho_i(m = 1), the mean summation
// density equals rho0 (to round-off: it is an identity of the summation).
#include "test_support.hpp"
#include "stored_precision.hpp"

#include "sph/particle_sources.hpp"

using namespace sph;

BOOST_AUTO_TEST_SUITE(mass_scaling)

BOOST_AUTO_TEST_CASE(mean_density_equals_rho0_for_a_block) {
  CaseConfig c;
  c.blockMin = {0.01, 0.01};
  c.blockMax = {0.26, 0.51};
  c.spacing = 0.0075;
  auto init = buildInitialState<2>(withDefaults(c));
  const std::size_t n = init.particles.size();
  BOOST_TEST(n == 33u * 67u);  // round(0.25/0.0075) x round(0.5/0.0075)
  SeedWcsphParameters prm;
  prm.rho0 = 1000;
  auto scene = test::makeScene<2>(init.particles.x, {}, prm, true, 1e-4);
  Real sum = 0;
  for (Real rho : scene.particles().rho) sum += rho;
  BOOST_TEST(sum / static_cast<Real>(n) == 1000.0, boost::test_tools::tolerance(test::storedTolerance(1e-12)));
  // Interior particles of a block at h/dx = 1.33 sit near rho0, edges below.
  const auto [lo, hi] = std::minmax_element(scene.particles().rho.begin(), scene.particles().rho.end());
  BOOST_TEST(*hi > 1000.0);
  BOOST_TEST(*lo < 1000.0);
  // All particles carry the same mass.
  for (Real m : scene.particles().m) BOOST_TEST(m == scene.particles().m[0]);
}

BOOST_AUTO_TEST_CASE(mean_density_equals_rho0_for_a_disc_and_in_3d) {
  CaseConfig c;
  c.discCenter = {0.2, 0.5};
  c.discRadius = {0.1};
  c.spacing = 0.0075;
  auto disc = buildInitialState<2>(withDefaults(c));
  SeedWcsphParameters prm;
  prm.rho0 = 998.2;
  auto s2 = test::makeScene<2>(disc.particles.x, {}, prm, true, 1e-4);
  Real sum = 0;
  for (Real rho : s2.particles().rho) sum += rho;
  BOOST_TEST(sum / static_cast<Real>(s2.particles().size()) == 998.2, boost::test_tools::tolerance(test::storedTolerance(1e-12)));

  c.dimension = 3;
  c.domainMin = {0, 0, 0};
  c.domainMax = {1, 1, 1};
  c.discCenter = {0.5, 0.5, 0.5};
  c.discRadius = {0.05};
  auto ball = buildInitialState<3>(withDefaults(c));
  auto s3 = test::makeScene<3>(ball.particles.x, {}, prm, true, 1e-4);
  sum = 0;
  for (Real rho : s3.particles().rho) sum += rho;
  BOOST_TEST(sum / static_cast<Real>(s3.particles().size()) == 998.2, boost::test_tools::tolerance(test::storedTolerance(1e-12)));
}

BOOST_AUTO_TEST_SUITE_END()
