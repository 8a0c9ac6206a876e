// Laminar flows: the Morris, Fox & Zhu 1997 viscosity (morris_viscosity.hpp)
// on lattices where the answer is known exactly (a linear shear flow feels
// no viscous force; a parabolic one feels nu u''), the body force as a
// vector (gravity), the sliding lid (lid_velocity), and a low-resolution
// Couette flow against the series solution of Morris et al. (their eq. 22,
// tests/reference/couette_morris1997_series.csv, nobody here wrote it).
#include "sph/model_registry.hpp"
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace sph;

namespace {

// A lattice of fluid particles periodic along x, 10 dx long, 30 dx high,
// with the Morris viscosity and nothing else that moves a uniform lattice
// (the pressure of a uniform lattice is uniform in its interior).
CaseConfig shearLattice() {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = "wendland_c2";
  c.spacing = 0.01;
  c.h = 0.015;
  c.viscosity = "morris";
  c.nu = 1e-3;
  // A soft EOS: the lattice's uniform pressure exerts no force either, but
  // with the default k its round-off (p ~ 1e4 Pa) is 1e-10 of the viscous
  // scale, the gate of the linear-shear test.
  c.k = 1e-6;
  c.periodic = "x";
  c.domainMin = {0, 0};
  c.domainMax = {0.1, 0.3};
  c.blockMin = c.domainMin;
  c.blockMax = c.domainMax;
  return c;
}

// a_x of the interior particles (more than two supports from the top and
// bottom rows) for the velocity field u(y) along x.
template <class U>
std::vector<std::pair<Real, Real>> interiorAcceleration(const CaseConfig& c, U u) {
  validateCase(c);
  const ResolvedCase cd = withDefaults(c);
  InitialState<2> init = buildInitialState<2>(cd);
  for (std::size_t i = 0; i < init.particles.x.size(); ++i) init.particles.v[i] = Vec<2>(u(init.particles.x[i][1]), 0);
  const bool scale = !init.massesGiven;
  Scene<2> s = makeScene<2>(cd, std::move(init));
  BOOST_REQUIRE(!s.initialise(scale));
  std::vector<std::pair<Real, Real>> out;
  const auto& P = s.particles();
  for (std::size_t i = 0; i < P.size(); ++i)
    if (P.x[i][1] > 0.065 && P.x[i][1] < 0.235) out.emplace_back(P.x[i][1], P.a[i][0]);
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(laminar)

// A linear shear flow u = gamma y: every pair's v_i - v_j is gamma (y_i -
// y_j), whose lattice sum against the even weights vanishes: no viscous
// force, to round-off (a wrong sign or an odd factor in the term does not
// change that; the parabolic test below catches those).
BOOST_AUTO_TEST_CASE(morris_linear_shear_feels_no_force) {
  const Real gamma = 2.0;
  const CaseConfig c = shearLattice();
  const auto a = interiorAcceleration(c, [&](Real y) { return gamma * y; });
  BOOST_REQUIRE(a.size() > 100u);
  const Real scale = c.nu * gamma / c.spacing;  // one pair's contribution
  for (const auto& [y, ax] : a) BOOST_TEST(std::abs(ax) <= 1e-10 * scale, "y = " << y << ": a_x = " << ax);
}

// u = U (y / Y)^2: nu u'' = 2 nu U / Y^2 everywhere. The lattice sum of the
// Morris term with the Wendland C2 kernel at h = 1.5 dx gives 0.996 of it
// with eta^2 = 1e-4 h^2 (computed independently by summing the kernel's
// second moment over the lattice; with the paper's 0.01 h^2 it is 0.985,
// which this 1% gate rejects). A factor-of-2 slip or the sign is far outside.
BOOST_AUTO_TEST_CASE(morris_parabolic_profile_gives_nu_u_second_derivative) {
  const CaseConfig c = shearLattice();
  const Real U = 0.1, Y = 0.3;
  const auto a = interiorAcceleration(c, [&](Real y) { return U * (y / Y) * (y / Y); });
  BOOST_REQUIRE(a.size() > 100u);
  const Real exact = 2 * c.nu * U / (Y * Y);
  Real worst = 0;
  for (const auto& [y, ax] : a) worst = std::max(worst, std::abs(ax / exact - 1));
  BOOST_TEST_MESSAGE("Morris viscosity, parabolic profile: worst |a/a_exact - 1| = " << worst);
  BOOST_TEST(worst <= 0.01);
}

BOOST_AUTO_TEST_CASE(gravity_vector_and_scalar_shorthand) {
  CaseConfig c = test::bareWcsph(2);
  c.points = {0, 0};
  c.gravity = {1.5, -2};
  c.given = {"gravity"};
  validateCase(c);
  BOOST_TEST((gravityVector<2>(c) == Vec<2>(1.5, -2)));
  c.given = {"gravity", "g"};
  BOOST_CHECK_THROW(validateCase(c), CaseError);  // both at once
  c.given = {"gravity"};
  c.gravity = {1, 2, 3};  // 3 values in 2D
  BOOST_CHECK_THROW(validateCase(c), CaseError);
  CaseConfig d = test::bareWcsph(3);
  d.g = 9.81;
  BOOST_TEST((gravityVector<3>(d) == Vec<3>(0, 0, -9.81)));
  // The scene accelerates a lone particle with that vector.
  c.gravity = {1.5, -2};
  c.dt = 1e-3;
  Scene<2> s = test::sceneOf<2>(c);
  BOOST_TEST((s.particles().a[0] - Vec<2>(1.5, -2)).norm() < 1e-12);
}

BOOST_AUTO_TEST_CASE(lid_velocity_is_checked_and_given_to_the_lid) {
  CaseConfig c;
  c.model = "wcsph";
  c.boundary = "dummy";
  c.spacing = 0.1;
  c.h = 0.13;
  c.domainMin = {0, 0};
  c.domainMax = {1, 1};
  c.blockMin = {0, 0};
  c.blockMax = {1, 0.5};
  c.lidVelocity = {0.3, 0};
  BOOST_CHECK_THROW(validateCase(c), CaseError);  // no lid
  c.lid = true;
  validateCase(c);
  c.lidVelocity = {0.3, 0.1};  // not along the lid
  BOOST_CHECK_THROW(validateCase(c), CaseError);
  c.lidVelocity = {0.3, 0};
  const InitialState<2> init = buildInitialState<2>(withDefaults(c));
  const auto& P = init.particles;
  std::size_t lid = 0;
  for (std::size_t i = P.fluidCount(); i < P.size(); ++i) {
    const bool above = P.x[i][1] > 1;
    lid += above;
    BOOST_TEST((P.v[i] == (above ? Vec<2>(0.3, 0) : Vec<2>(0, 0))));
  }
  BOOST_TEST(lid > 0u);
}

// Couette flow at 10 particles across (cases/couette_2d.case at 1/2.5 of
// its resolution): at t = 0.225 s (a quarter of the viscous time) the mean
// u of every particle row within 3% of V0 of the series solution. 3%: the
// validation run (25 across) is held to 1%; halving the resolution about
// doubles the wall error of the dummy-particle no-slip condition. A lid
// that does not drag (u_w ignored), or a wall seen as at rest, is off by
// tens of percent.
BOOST_AUTO_TEST_CASE(couette_low_resolution_against_series) {
  CaseConfig c;
  c.model = "wcsph";
  c.kernel = "wendland_c2";
  c.spacing = 1e-4;
  c.h = 1.5e-4;
  c.rho0 = 1000;
  c.eos = "linear";
  c.k = 1e-4;
  c.viscosity = "morris";
  c.nu = 1e-6;
  c.gravity = {0, 0};
  c.given = {"gravity"};
  c.boundary = "dummy";
  c.lid = true;
  c.lidVelocity = {1.25e-5, 0};
  c.periodic = "x";
  c.dt = 1e-3;  // viscous limit 0.125 h^2 / nu = 2.8e-3 s
  c.endTime = 0.225;
  c.domainMin = {0, 0};
  c.domainMax = {1e-3, 1e-3};
  c.blockMin = c.domainMin;
  c.blockMax = c.domainMax;
  Scene<2> s = test::sceneOf<2>(c);
  for (int k = 0; k < 225; ++k) BOOST_REQUIRE(!s.step());
  BOOST_TEST(std::abs(s.time() - 0.225) < 1e-12);

  // The series at t = 0.225 s (column 5 of the table).
  std::ifstream in(test::referenceFile("couette_morris1997_series.csv"));
  std::vector<Real> eta, ref;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || !(std::isdigit(static_cast<unsigned char>(line[0])) || line[0] == '-')) continue;
    std::stringstream ss(line);
    std::vector<Real> row;
    for (std::string cell; std::getline(ss, cell, ',');) row.push_back(std::stod(cell));
    eta.push_back(row[0]);
    ref.push_back(row[4]);
  }
  BOOST_REQUIRE(eta.size() > 20u);
  auto series = [&](Real e) {
    std::size_t k = 1;
    while (k + 1 < eta.size() && eta[k] < e) ++k;
    const Real w = (e - eta[k - 1]) / (eta[k] - eta[k - 1]);
    return ref[k - 1] + w * (ref[k] - ref[k - 1]);
  };
  std::map<long, std::pair<Real, int>> rows;
  const auto& P = s.particles();
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    auto& r = rows[std::lround(P.x[i][1] / c.spacing * 2)];
    r.first += P.v[i][0] / 1.25e-5;
    ++r.second;
  }
  BOOST_TEST(rows.size() == 10u);
  Real worst = 0;
  for (const auto& [key, r] : rows) worst = std::max(worst, std::abs(r.first / r.second - series(key * c.spacing / 2 / 1e-3)));
  BOOST_TEST_MESSAGE("Couette, 10 across, t = 0.225 s: worst row |u - u_series| / V0 = " << worst);
  BOOST_TEST(worst <= 0.03);
}

BOOST_AUTO_TEST_SUITE_END()
