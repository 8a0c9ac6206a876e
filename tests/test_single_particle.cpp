// One particle (the one_particle case: x = (0.5, 0.5), h = 0.01, g = 9.81,
// e = 0.5, dt = 1e-4): free fall y = y0 - g t^2/2 to round-off until it
// reaches the floor clamp at y = h, then a rebound at e times the impact
// speed. Reference: tests/reference/single_particle_bounce.csv (impact
// times and speeds of the continuous problem).
#include "test_support.hpp"
#include "stored_precision.hpp"

#include <fstream>

using namespace sph;

namespace {

struct Impact {
  Real t, vImpact, vRebound;
};

std::vector<Impact> referenceImpacts() {
  std::ifstream in(test::referenceFile("single_particle_bounce.csv"));
  BOOST_TEST_REQUIRE(in.good(), "cannot read single_particle_bounce.csv");
  std::vector<Impact> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'i') continue;
    Impact imp{};
    int k = 0;
    char comma = 0;
    std::istringstream s(line);
    s >> k >> comma >> imp.t >> comma >> imp.vImpact >> comma >> imp.vRebound;
    out.push_back(imp);
  }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(single_particle)

BOOST_AUTO_TEST_CASE(free_fall_is_exact_and_rebound_is_e_times_impact) {
  const auto ref = referenceImpacts();
  BOOST_TEST_REQUIRE(ref.size() >= 2u);
  const Real dt = 1e-4, g = 9.81, y0 = 0.5, h = 0.01, e = 0.5;
  SeedWcsphParameters prm;  // defaults: h = 0.01, k = 2000, rho0 = 1000, mu = 1, g = 9.81
  auto scene = test::makeScene<2>({Vec<2>(0.5, y0)}, {}, prm, true, dt, 0, e);
  const auto& P = scene.particles();
  // Mass scaled: rho = rho0, so p = k (rho - rho0) = 0, to the round-off of
  // the stored mass (narrow: float in a mixed build, test::storedTolerance).
  BOOST_TEST(P.rho[0] == 1000.0, boost::test_tools::tolerance(test::storedTolerance(1e-14)));
  BOOST_TEST(std::abs(P.p[0]) <= std::max(1e-9, prm.k * 1000.0 * test::storedTolerance(0)));

  // Free flight: leap-frog integrates a constant acceleration exactly.
  long contactStep = -1;
  Real vBefore = 0;
  for (long n = 1; n < 10000; ++n) {
    vBefore = P.vHalf[0][1];
    BOOST_REQUIRE(!scene.step());
    const Real t = static_cast<Real>(n) * dt;
    const Real yFree = y0 - 0.5 * g * t * t;
    if (yFree < h) {
      contactStep = n;
      break;
    }
    // Round-off: at most an ulp of 0.5 (5.6e-17) per step over 3161 steps,
    // 1.8e-13; the test allows 1e-12 m and 1e-12 m/s absolute.
    BOOST_TEST(std::abs(P.x[0][1] - yFree) < 1e-12);
    BOOST_TEST(P.x[0][0] == 0.5);
    BOOST_TEST(std::abs(P.v[0][1] + g * t) < 1e-12);
  }
  // First contact: the first step whose end lies past the continuous impact
  // time t = 0.3160665 s.
  const Real tContact = static_cast<Real>(contactStep) * dt;
  BOOST_TEST(tContact >= ref[0].t);
  BOOST_TEST(tContact < ref[0].t + dt);
  // The step that reaches the floor: clamp at y = h and reflect the half-step
  // velocity with restitution e.
  BOOST_TEST(P.x[0][1] == h);
  const Real vIn = vBefore - g * dt;  // v^{n+1/2} before the wall acted
  BOOST_TEST(P.vHalf[0][1] == -e * vIn, boost::test_tools::tolerance(1e-14));
  // The impact speed agrees with the continuous one to within g dt.
  BOOST_TEST(std::abs(-vIn - ref[0].vImpact) < g * dt);
  BOOST_TEST(std::abs(P.vHalf[0][1] - ref[0].vRebound) < e * g * dt + 1e-12);
}

// The second impact of the discrete run lands near the continuous one: the
// clamp loses at most one step of flight per bounce (tolerance 3 dt).
BOOST_AUTO_TEST_CASE(second_impact_time_matches_reference) {
  const auto ref = referenceImpacts();
  const Real dt = 1e-4;
  auto scene = test::makeScene<2>({Vec<2>(0.5, 0.5)}, {}, SeedWcsphParameters{}, true, dt);
  int impacts = 0;
  Real previousV = 0;
  for (long n = 1; n < 8000 && impacts < 2; ++n) {
    BOOST_REQUIRE(!scene.step());
    const Real v = scene.particles().vHalf[0][1];
    if (previousV < 0 && v > 0) {
      ++impacts;
      BOOST_TEST(std::abs(scene.time() - ref[static_cast<std::size_t>(impacts - 1)].t) < 3 * dt);
    }
    previousV = v;
  }
  BOOST_TEST(impacts == 2);
}

BOOST_AUTO_TEST_SUITE_END()
