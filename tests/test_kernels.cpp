// The seed scheme's kernel factors against numbers worked out by hand, their
// normalisation, and derivatives against finite differences.
#include "sph/kernels/seed_kernels.hpp"

#include <boost/test/unit_test.hpp>

#include <cmath>

using sph::Real;
using sph::SeedKernels;

BOOST_AUTO_TEST_SUITE(kernels)

// h = 0.01, q = 0.5 (r = 0.005), by hand:
//   W(0)  = 4 / (pi 1e-4)                 = 12732.395447351626
//   W(r)  = W(0) (1 - 0.25)^3 = W(0) 0.421875 = 5371.479329351468
//   G(q)  = -30 / (pi 1e-6) (0.5)^2 / 0.5 = -4774648.292756859
//   L(q)  = 40 / (pi 1e-8) (0.5)          = 636619772.3675814
BOOST_AUTO_TEST_CASE(values_match_hand_computed_numbers) {
  const SeedKernels k(0.01);
  BOOST_TEST(k.densityAtZero() == 12732.395447351626, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(k.density(0.0) == 12732.395447351626, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(k.density(0.005 * 0.005) == 5371.479329351468, boost::test_tools::tolerance(1e-13));
  BOOST_TEST(k.pressureFactor(0.5) == -4774648.292756859, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(k.viscosityLaplacian(0.5) == 636619772.3675814, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(compact_support) {
  const SeedKernels k(0.02);
  BOOST_TEST(k.density(0.02 * 0.02) == 0.0);
  BOOST_TEST(k.density(0.03 * 0.03) == 0.0);
  BOOST_TEST(k.density(0.0199 * 0.0199) > 0.0);
  BOOST_TEST(k.pressureFactor(1.0) == 0.0);
  BOOST_TEST(k.viscosityLaplacian(1.0) == 0.0);
}

// 4/(pi h^2) (1 - q^2)^3 is the normalised 2D poly6 kernel: sum dx^2 W over a
// fine lattice is 1. Tolerance: lattice quadrature error at h/dx = 100 is
// ~1e-6 (smooth kernel, compact support); 1e-5 leaves room.
BOOST_AUTO_TEST_CASE(density_kernel_integrates_to_one_in_2d) {
  const Real h = 1.0, dx = h / 100;
  const SeedKernels k(h);
  Real sum = 0;
  for (int i = -100; i <= 100; ++i)
    for (int j = -100; j <= 100; ++j) sum += dx * dx * k.density(dx * dx * (i * i + j * j));
  BOOST_TEST(sum == 1.0, boost::test_tools::tolerance(1e-5));
}

// The pressure factor is h times the gradient of the 2D spiky kernel
// W_s = 10/(pi h^2) (1 - q)^3: G(q) r_ij = h grad W_s(r_ij). Central finite
// differences with step 1e-6 h have error ~1e-10 relative.
BOOST_AUTO_TEST_CASE(pressure_factor_is_h_times_spiky_gradient) {
  const Real h = 0.01;
  const SeedKernels k(h);
  auto spiky = [&](Real x, Real y) {
    const Real q = std::sqrt(x * x + y * y) / h;
    return q < 1 ? 10 / (M_PI * h * h) * std::pow(1 - q, 3) : 0.0;
  };
  for (Real q : {0.1, 0.3, 0.5, 0.8, 0.95}) {
    const Real angle = 0.7, x = q * h * std::cos(angle), y = q * h * std::sin(angle);
    const Real e = 1e-6 * h;
    const Real gx = (spiky(x + e, y) - spiky(x - e, y)) / (2 * e);
    const Real gy = (spiky(x, y + e) - spiky(x, y - e)) / (2 * e);
    BOOST_TEST(k.pressureFactor(q) * x == h * gx, boost::test_tools::tolerance(1e-7));
    BOOST_TEST(k.pressureFactor(q) * y == h * gy, boost::test_tools::tolerance(1e-7));
  }
}

// d/dr of the density kernel: -24 r/(pi h^4) (1 - q^2)^2, by hand, against a
// central difference of density(r^2).
BOOST_AUTO_TEST_CASE(density_kernel_derivative_matches_finite_difference) {
  const Real h = 0.01;
  const SeedKernels k(h);
  for (Real q : {0.1, 0.4, 0.7, 0.9}) {
    const Real r = q * h, e = 1e-7 * h;
    const Real fd = (k.density((r + e) * (r + e)) - k.density((r - e) * (r - e))) / (2 * e);
    const Real exact = -24 * r / (M_PI * std::pow(h, 4)) * std::pow(1 - q * q, 2);
    BOOST_TEST(fd == exact, boost::test_tools::tolerance(1e-6));
  }
}

// The viscosity factor is linear in q and vanishes at the support:
// L(q) = L(0) (1 - q), L(0) = 40/(pi h^4).
BOOST_AUTO_TEST_CASE(viscosity_factor_is_linear_in_q) {
  const Real h = 0.02;
  const SeedKernels k(h);
  const Real L0 = 40 / (M_PI * std::pow(h, 4));
  for (Real q : {0.0, 0.25, 0.5, 0.75}) BOOST_TEST(k.viscosityLaplacian(q) == L0 * (1 - q), boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_SUITE_END()
