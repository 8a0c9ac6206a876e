// The toy star against tests/reference/toystar_profiles.csv (analytic
// equilibrium for M = 2, R = 0.75, k = 0.1, n = 1), and the gate: a relaxed
// star of 800 particles is within 3% relative L2 of the analytic density
// inside 0.9 R, in 2D and 3D.
#include "test_support.hpp"

#include "sph/toy_star.hpp"

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

BOOST_AUTO_TEST_SUITE_END()
