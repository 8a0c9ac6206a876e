// Hand-sized systems: forces of two particles worked out by hand, equal and
// opposite pair forces, and conservation of total momentum with walls and
// gravity off (the pair forces m_i a_i are antisymmetric in i, j).
#include "test_support.hpp"
#include "stored_precision.hpp"

#include <omp.h>

#include <random>

using namespace sph;

namespace {

template <int D>
Vec<D> totalMomentum(const Particles<D>& P) {
  Vec<D> p = Vec<D>::Zero();
  for (std::size_t i = 0; i < P.size(); ++i) p += P.m[i] * P.v[i];
  return p;
}

template <int D>
Real momentumScale(const Particles<D>& P) {
  Real s = 0;
  for (std::size_t i = 0; i < P.size(); ++i) s += P.m[i] * P.v[i].norm();
  return s;
}

SeedWcsphParameters noGravity() {
  SeedWcsphParameters prm;
  prm.g = 0;
  return prm;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(momentum)

// Two particles, m = 1 (no scaling), h = 0.01, 0.005 apart on the x axis
// (q = 0.5), k = 2000, rho0 = 1000, mu = 1, g = 9.81; particle 0 at x = 0.5
// moves with v = (1, 0). By hand (see test_kernels for the kernel factors):
//   rho   = 1 * (W(0) + W(r)) = 12732.395447 + 5371.479329 = 18103.874776703095
//   p     = 2000 (rho - 1000)                                = 34207749.55340619
//   F_p,0 = -(1/rho) (p + p)/2 G(q) r_01,  r_01 = (-0.005, 0), G = -4774648.29
//         = (-45109120.290205956, 0)
//   F_v,0 = -mu (1/rho) v_01 L(q) = -(1/rho) 636619772.37 = (-35164.835164835, 0)
//   a_0   = (F_p + F_v)/rho + (0, -9.81)
BOOST_AUTO_TEST_CASE(two_particle_forces_match_hand_computation) {
  SeedWcsphParameters prm;
  auto s = test::makeScene<2>({Vec<2>(0.5, 0.5), Vec<2>(0.505, 0.5)},
                              {Vec<2>(1, 0), Vec<2>(0, 0)}, prm, false, 1e-5, 1.0);
  const auto& P = s.particles();
  const std::size_t a = test::indexOf(s, 0), b = test::indexOf(s, 1);
  const Real rho = 18103.874776703095;
  // (The mass and pressure are stored in a narrow field: a mixed build's
  // tolerance is a few of float's epsilon, test::storedTolerance.)
  BOOST_TEST(P.rho[a] == rho, boost::test_tools::tolerance(test::storedTolerance(1e-13)));
  BOOST_TEST(P.p[a] == 34207749.55340619, boost::test_tools::tolerance(test::storedTolerance(1e-12)));
  const Real ax = (-45109120.290205956 - 35164.83516483517) / rho;
  BOOST_TEST(P.a[a][0] == ax, boost::test_tools::tolerance(test::storedTolerance(1e-12)));
  BOOST_TEST(P.a[a][1] == -9.81, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(P.a[b][0] == -ax, boost::test_tools::tolerance(test::storedTolerance(1e-12)));
}

BOOST_AUTO_TEST_CASE(two_particle_forces_are_equal_and_opposite) {
  auto s = test::makeScene<2>({Vec<2>(0.5, 0.5), Vec<2>(0.503, 0.506)},
                              {Vec<2>(0.3, -0.1), Vec<2>(-0.2, 0.4)}, noGravity(), false, 1e-5);
  const auto& P = s.particles();
  const Vec<2> f0 = P.m[0] * P.a[0], f1 = P.m[1] * P.a[1];
  BOOST_TEST(f0.norm() > 0.0);
  BOOST_TEST((f0 + f1).norm() <= 1e-12 * f0.norm());
}

// Three particles of the three_particles case, moved within h of each other
// and set moving; 2000 steps with walls and gravity off.
BOOST_AUTO_TEST_CASE(three_particles_conserve_momentum) {
  auto s = test::makeScene<2>({Vec<2>(0.5, 0.5), Vec<2>(0.495, 0.503), Vec<2>(0.505, 0.503)},
                              {Vec<2>(0.2, 0), Vec<2>(0, -0.3), Vec<2>(-0.1, 0.1)}, noGravity(),
                              false, 1e-5);
  const Vec<2> p0 = totalMomentum(s.particles());
  const Real scale = momentumScale(s.particles());
  Vec<2> f = Vec<2>::Zero();
  for (std::size_t i = 0; i < 3; ++i) f += s.particles().m[i] * s.particles().a[i];
  Real fScale = 0;
  for (std::size_t i = 0; i < 3; ++i) fScale += s.particles().m[i] * s.particles().a[i].norm();
  BOOST_TEST(f.norm() <= 1e-13 * fScale);
  for (int n = 0; n < 2000; ++n) BOOST_REQUIRE(!s.step());
  // Round-off: each step adds ~1e-16 relative per pair; 1e-12 of the scale.
  BOOST_TEST((totalMomentum(s.particles()) - p0).norm() <= 1e-12 * scale);
  BOOST_TEST(momentumScale(s.particles()) > 0.0);
}

// A 3D cloud of 400 particles at h/dx ~ 1.6 with random velocities.
BOOST_AUTO_TEST_CASE(random_cloud_3d_conserves_momentum) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> u(-1, 1);
  std::vector<Vec<3>> x, v;
  const Real dx = 0.006;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 6; ++k) {
        x.push_back(Vec<3>(i * dx, j * dx, k * dx) + 0.1 * dx * Vec<3>(u(rng), u(rng), u(rng)));
        v.push_back(0.05 * Vec<3>(u(rng), u(rng), u(rng)));
      }
  auto s = test::makeScene<3>(x, v, noGravity(), false, 1e-5);
  const Vec<3> p0 = totalMomentum(s.particles());
  const Real scale = momentumScale(s.particles());
  for (int n = 0; n < 300; ++n) BOOST_REQUIRE(!s.step());
  BOOST_TEST((totalMomentum(s.particles()) - p0).norm() <= 1e-12 * scale);
}

// Gather-form loops: 1 and 2 threads give bit-identical states.
BOOST_AUTO_TEST_CASE(results_do_not_depend_on_thread_count) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> u(-1, 1);
  std::vector<Vec<2>> x;
  for (int i = 0; i < 28; ++i)
    for (int j = 0; j < 28; ++j)
      x.push_back(Vec<2>(0.2 + 0.0075 * i + 0.001 * u(rng), 0.2 + 0.0075 * j + 0.001 * u(rng)));
  const int threads = omp_get_max_threads();
  std::vector<Vec<2>> result[2];
  for (int t : {1, 2}) {
    omp_set_num_threads(t);
    auto s = test::makeScene<2>(x, {}, SeedWcsphParameters{}, true, 1e-5);
    for (int n = 0; n < 50; ++n) BOOST_REQUIRE(!s.step());
    result[t - 1].resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      result[t - 1][static_cast<std::size_t>(s.particles().id[i])] = s.particles().x[i];
  }
  omp_set_num_threads(threads);
  for (std::size_t i = 0; i < x.size(); ++i) BOOST_TEST((result[0][i] == result[1][i]));
}

BOOST_AUTO_TEST_SUITE_END()
