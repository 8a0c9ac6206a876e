// The toy star against tests/reference/toystar_profiles.csv (analytic
// equilibrium for M = 2, R = 0.75, k = 0.1, n = 1), and the gate: a relaxed
// star of 800 particles is within 3% relative L2 of the analytic density
// inside 0.9 R, in 2D and 3D.
#include "cli_support.hpp"

#include "sph/io/vtp_io.hpp"
#include "sph/toy_star.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <regex>

using namespace sph;

namespace {

struct Reference {
  Real lambda2D = 0, lambda3D = 0;
  std::vector<Real> r, rho2D, rho3D;
};

Reference readReference() {
  std::ifstream in(test::referenceFile("toystar_profiles.csv"));
  BOOST_TEST_REQUIRE(in.good(), "cannot read toystar_profiles.csv");
  Reference ref;
  std::string line;
  const std::regex l2("lambda_2D=([0-9.]+)"), l3("lambda_3D=([0-9.]+)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, l2)) ref.lambda2D = std::stod(m[1]);
    if (std::regex_search(line, m, l3)) ref.lambda3D = std::stod(m[1]);
    if (line.empty() || line[0] == '#' || line[0] == 'r') continue;
    std::istringstream s(line);
    Real r, rho1, rho2, rho3;
    char comma;
    s >> r >> comma >> rho1 >> comma >> rho2 >> comma >> rho3;
    ref.r.push_back(r), ref.rho2D.push_back(rho2), ref.rho3D.push_back(rho3);
  }
  BOOST_TEST_REQUIRE(ref.r.size() > 50u);
  return ref;
}

// Run a star case through the executable and return the printed L2 error.
Real relaxedStarError(const std::string& caseName, const std::vector<std::string>& extra) {
  const auto dir = test::scratchDir(caseName);
  std::vector<std::string> args{"run", test::caseFile(caseName), "--output", dir.string(),
                                "--output_every", "100000"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = test::runSph(args);
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  std::smatch m;
  BOOST_TEST_REQUIRE(std::regex_search(r.output, m, std::regex("inside 0.9 R: ([0-9.]+)")), r.output);
  BOOST_TEST(std::filesystem::exists(dir / "star_profile.csv"));
  return std::stod(m[1]);
}

// The recommended setting for a star of mass M, radius R, stiffness k and
// index n (docs/methods/toy-stars.md): N and h from n (h = c R (pi/N)^(1/2) in 2D,
// c R (4 pi / 3N)^(1/3) in 3D, so h/R is fixed for a given n), and the
// damping, end time and largest step in units of the dynamical time
// 1/sqrt(lambda).
struct StarSetting {
  long particles;
  Real h, damping, endTime, dt;
  std::string kernel;
};

StarSetting recommendedStar(int dimension, Real M, Real R, Real k, Real n) {
  const Real tau = 1 / std::sqrt(toyStarLambda(dimension, M, R, k, n));
  StarSetting s{};
  if (dimension == 2) {
    const bool steep = n > 1;
    s.particles = steep ? 3200 : 1600;
    s.h = (steep ? 1.7 : 1.5) * R * std::sqrt(M_PI / s.particles);
    s.kernel = "cubic_spline";
  } else {
    // n > 1: the cubic spline's particle noise and its thin surface layer
    // keep it above 1% (n = 2: 1.4% at 8000, 1.05% at 16 000 particles);
    // Wendland C2 with ~3x the neighbours does not pair and reaches it
    // (at 8000 particles only just: n = 1.5, 0.72% and 0.97%).
    const bool steep = n > 1;
    s.particles = steep ? 16000 : 8000;
    s.h = (steep ? 1.35 : 1.0) * R * std::cbrt(4 * M_PI / (3 * s.particles));
    s.kernel = steep ? "wendland_c2" : "cubic_spline";
  }
  s.damping = 0.75 / tau;
  s.endTime = 16 * tau;
  s.dt = 0.025 * tau;
  return s;
}

std::string num(Real x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", x);
  return b;
}

// Run the D-dimensional toy-star case as another star with the given
// setting and compute, from the last snapshot, the relative L2 error of the
// particles' density inside 0.9 R against the analytic polytrope about the
// centre of mass (as validation/observables.py's toy_star_errors).
Real starErrorWith(int dimension, Real M, Real R, Real k, Real n, const StarSetting& s, const std::string& tag) {
  const std::string caseName = dimension == 2 ? "toy_star_2d" : "toy_star_3d";
  const auto dir = test::scratchDir(caseName + "_" + tag);
  const std::string box = num(4 * R);
  auto vec = [&](const std::string& sign) {
    std::string v = "[";
    for (int d = 0; d < dimension; ++d) v += (d ? "," : "") + sign + box;
    return v + "]";
  };
  const std::vector<std::string> args{
      "run", test::caseFile(caseName), "--output", dir.string(), "--output_every", "100000", "--threads", "1",
      "--no-progress", "--star_mass", num(M), "--star_radius", num(R), "--k", num(k), "--polytropic_index", num(n),
      "--star_particles", "[" + std::to_string(s.particles) + "]", "--h", num(s.h), "--kernel", s.kernel,
      "--damping", num(s.damping), "--end_time", num(s.endTime), "--dt", num(s.dt), "--domain_min", vec("-"),
      "--domain_max", vec("")};
  const auto res = test::runSph(args);
  BOOST_TEST_REQUIRE(res.exitCode == 0, res.output);
  std::filesystem::path last;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".vtp" && e.path() > last) last = e.path();
  BOOST_TEST_REQUIRE(!last.empty(), "no snapshot in " << dir);
  const VtpParticles p = readVtp(last.string());
  BOOST_TEST_REQUIRE(p.rho.size() == p.x.size());
  BOOST_TEST_REQUIRE(p.m.size() == p.x.size());
  std::array<Real, 3> c{0, 0, 0};
  Real mass = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    for (int d = 0; d < 3; ++d) c[d] += p.m[i] * p.x[i][d];
    mass += p.m[i];
  }
  for (auto& v : c) v /= mass;
  const Real lambda = toyStarLambda(dimension, M, R, k, n);
  Real num2 = 0, den2 = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    Real r2 = 0;
    for (int d = 0; d < dimension; ++d) r2 += (p.x[i][d] - c[d]) * (p.x[i][d] - c[d]);
    const Real r = std::sqrt(r2);
    if (r >= 0.9 * R) continue;
    const Real exact = toyStarDensity(r, lambda, R, k, n);
    num2 += (p.rho[i] - exact) * (p.rho[i] - exact);
    den2 += exact * exact;
  }
  BOOST_TEST_REQUIRE(den2 > 0);
  const Real l2 = std::sqrt(num2 / den2);
  BOOST_TEST_MESSAGE(caseName << " M = " << M << ", R = " << R << ", k = " << k << ", n = " << n << " ("
                              << s.particles << " particles, h = " << s.h << ", " << s.kernel
                              << "): L2 = " << l2);
  return l2;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(toy_star)

BOOST_AUTO_TEST_CASE(lambda_matches_reference_and_closed_form) {
  const Reference ref = readReference();
  // The reference prints 9 significant digits.
  BOOST_TEST(toyStarLambda(2, 2, 0.75, 0.1, 1) == ref.lambda2D, boost::test_tools::tolerance(1e-8));
  BOOST_TEST(toyStarLambda(3, 2, 0.75, 0.1, 1) == ref.lambda3D, boost::test_tools::tolerance(1e-8));
  // 2D, n = 1: lambda = 8 k M / (pi R^4).
  BOOST_TEST(toyStarLambda(2, 2, 0.75, 0.1, 1) == 8 * 0.1 * 2 / (M_PI * std::pow(0.75, 4)),
             boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(analytic_profile_matches_reference) {
  const Reference ref = readReference();
  for (std::size_t i = 0; i < ref.r.size(); ++i) {
    BOOST_TEST(toyStarDensity(ref.r[i], ref.lambda2D, 0.75, 0.1, 1) == ref.rho2D[i], boost::test_tools::tolerance(1e-7));
    BOOST_TEST(toyStarDensity(ref.r[i], ref.lambda3D, 0.75, 0.1, 1) == ref.rho3D[i], boost::test_tools::tolerance(1e-7));
  }
}

// The mass of the particles equals M and the generator stays inside R.
BOOST_AUTO_TEST_CASE(star_generator_places_mass_inside_radius) {
  const auto x = randomPointsInBall<3>(Vec<3>(1, 2, 3), 0.5, 2000, 11);
  BOOST_TEST(x.size() == 2000u);
  Vec<3> mean = Vec<3>::Zero();
  for (const auto& p : x) {
    BOOST_TEST((p - Vec<3>(1, 2, 3)).norm() <= 0.5);
    mean += p / 2000.0;
  }
  // Uniform in the ball: the mean lies within ~3 sigma (0.5/sqrt(5 * 2000))
  BOOST_TEST((mean - Vec<3>(1, 2, 3)).norm() < 0.03);
}

// The gate: the shipped cases within 1% (issue 9: the setting the toy-star
// studies recommend); measured 0.57% in 2D (1600 particles, h = 0.05) and
// 0.80% in 3D (8000, h = 0.06). The error is the SPH density's own
// smoothing bias, O(h^2), plus the noise of a random start, so the gate
// fails if either case's h or N is made coarser (2D at h = 0.1: 1.0%; 3D
// with 4000 particles at h = 0.075: 1.15%).
BOOST_AUTO_TEST_CASE(relaxed_2d_star_matches_analytic_profile) {
  BOOST_TEST(relaxedStarError("toy_star_2d", {}) < 0.01);
}

BOOST_AUTO_TEST_CASE(relaxed_3d_star_matches_analytic_profile) {
  BOOST_TEST(relaxedStarError("toy_star_3d", {}) < 0.01);
}

// Other stars (issue 17): the recommended setting on a slow, wide star
// (M = 1, R = 1.5, k = 0.05: sqrt(lambda) = 0.05-0.3) and a fast, compact
// one (M = 5, R = 0.5, k = 0.5: sqrt(lambda) = 7-40) at n = 0.5 and 2. The
// gate is the goal, 1%; measured 0.46% (n = 0.5) and 0.78-0.79% (n = 2) in
// 2D, 0.5% at n = 0.5 in 3D (docs/methods/toy-stars.md). The star's equilibrium is
// self-similar (lengths in R, times in 1/sqrt(lambda)), so these errors are
// those of the shipped star at the same n, N and h/R; the gate fails when
// the setting is not scaled (next test) or when h/R or N is coarsened
// (2D n = 2 at 1600 particles: 0.90%, at h/R 20% smaller: 1.26%).
BOOST_AUTO_TEST_CASE(recommended_setting_on_other_2d_stars) {
  for (const auto& star : {std::array<Real, 3>{1, 1.5, 0.05}, std::array<Real, 3>{5, 0.5, 0.5}})
    for (Real n : {0.5, 2.0}) {
      const StarSetting s = recommendedStar(2, star[0], star[1], star[2], n);
      BOOST_TEST(starErrorWith(2, star[0], star[1], star[2], n, s, "rule") < 0.01,
                 "2D star M = " << star[0] << ", R = " << star[1] << ", k = " << star[2] << ", n = " << n);
    }
}

// The check can fail: the slow star with the shipped case's damping = 1 and
// end_time = 12 (h scaled with R, as a user would) is still collapsing, its
// damping 20 times its sqrt(lambda) = 0.055 (measured 17%).
BOOST_AUTO_TEST_CASE(unscaled_setting_fails_on_a_slow_star) {
  StarSetting old{1600, 0.05 * 1.5 / 0.75, 1, 12, 0.02, "cubic_spline"};
  BOOST_TEST(starErrorWith(2, 1, 1.5, 0.05, 0.5, old, "old") > 0.05);
}

// 3D at n = 0.5 on both stars (8000 particles, cubic spline: about 10 s of
// one core each). n = 2: the suite toy_star_steep below (label study).
BOOST_AUTO_TEST_CASE(recommended_setting_on_other_3d_stars) {
  for (const auto& star : {std::array<Real, 3>{1, 1.5, 0.05}, std::array<Real, 3>{5, 0.5, 0.5}}) {
    const StarSetting s = recommendedStar(3, star[0], star[1], star[2], 0.5);
    BOOST_TEST(starErrorWith(3, star[0], star[1], star[2], 0.5, s, "rule") < 0.01,
               "3D star M = " << star[0] << ", R = " << star[1] << ", k = " << star[2] << ", n = 0.5");
  }
}

BOOST_AUTO_TEST_SUITE_END()

// 3D at n = 2 (16 000 particles, Wendland C2: about 50 s of one core), so
// in a suite of its own, off by default and out of the core label: the
// ctest toy_star.steep_3d (label study) runs it by name. Measured 0.68% on
// this star (1.50% with the old setting); the shipped star at n = 2 0.71%.
// Gate 1%, the goal.
BOOST_AUTO_TEST_SUITE(toy_star_steep, *boost::unit_test::disabled())

BOOST_AUTO_TEST_CASE(recommended_setting_on_a_steep_3d_star) {
  const StarSetting s = recommendedStar(3, 1, 0.5, 0.05, 2);
  BOOST_TEST(s.kernel == "wendland_c2");
  BOOST_TEST(starErrorWith(3, 1, 0.5, 0.05, 2, s, "rule") < 0.01);
}

BOOST_AUTO_TEST_SUITE_END()
