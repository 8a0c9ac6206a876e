// Probes: Shepard-normalised interpolation at points (a constant field
// exactly, a linear one exactly in the interior of a lattice, where the
// kernel weights are symmetric; a dry point is dry), the water height and the
// front of a block, and a real run of the hydrostatic tank whose probe reads
// rho0 g (H - y) and whose files carry units; bad probe keys refused.
#include "test_support.hpp"

#include "sph/io/probe_files.hpp"
#include "sph/probes.hpp"

#include <fstream>

using namespace sph;
namespace tt = boost::test_tools;

namespace {

// A 2D lattice block [0, 1] x [0, 0.5], dx 0.02, density rho, mass rho dx^2.
Particles<2> block(Real rho) {
  Particles<2> P;
  const Real dx = 0.02;
  std::vector<Vec<2>> x;
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 25; ++j) x.push_back(Vec<2>((i + 0.5) * dx, (j + 0.5) * dx));
  P.resize(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    P.x[k] = x[k];
    P.rho[k] = rho;
    P.m[k] = rho * dx * dx;
  }
  return P;
}

Kernel<2> wendland() { return WendlandC2<2>(0.03); }

std::vector<std::string> lines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(probes)

// Shepard normalisation reproduces a constant exactly anywhere with fluid in
// the support, also half out of the water (y = 0.49, by the free surface),
// where the plain SPH sum would read about half the value.
BOOST_AUTO_TEST_CASE(constant_field_exactly_also_at_the_surface) {
  Particles<2> P = block(1000);
  for (std::size_t k = 0; k < P.size(); ++k) P.p[k] = 1234.5, P.v[k] = Vec<2>(0.3, -0.2);
  for (const Vec<2>& at : {Vec<2>(0.5, 0.25), Vec<2>(0.5, 0.49), Vec<2>(0.013, 0.017)}) {
    const auto v = interpolateAt(P, wendland(), at, 0.1);
    BOOST_TEST_REQUIRE(v.wet);
    BOOST_TEST(v.pressure == 1234.5, tt::tolerance(1e-12));
    BOOST_TEST(v.density == 1000.0, tt::tolerance(1e-12));
    BOOST_TEST(v.velocity[0] == 0.3, tt::tolerance(1e-12));
  }
}

// probe_interpolation = plain: the bare sum sum_j A_j V_j W. In the interior
// of the lattice it reads the constant to the lattice's kernel sum (within
// 1%, tests/reference/kernel_lattice_sums.csv); at a point dx/2 under the
// free surface, where a quarter of the kernel's weight lies above the water,
// it reads 0.75 of the value (measured 920.8 of 1234.5; gate 0.9), and
// Shepard's normalisation (the default) reads it exactly.
BOOST_AUTO_TEST_CASE(plain_interpolation_is_low_at_the_surface) {
  Particles<2> P = block(1000);
  for (std::size_t k = 0; k < P.size(); ++k) P.p[k] = 1234.5;
  const auto inside = interpolateAt(P, wendland(), Vec<2>(0.5, 0.25), 0.1, {}, false);
  BOOST_TEST_REQUIRE(inside.wet);
  BOOST_TEST(inside.pressure == 1234.5, tt::tolerance(1e-2));
  const auto surface = interpolateAt(P, wendland(), Vec<2>(0.5, 0.49), 0.1, {}, false);
  BOOST_TEST_REQUIRE(surface.wet);
  BOOST_TEST(surface.pressure < 0.9 * 1234.5);
  BOOST_TEST(surface.pressure > 0.5 * 1234.5);
  BOOST_TEST(interpolateAt(P, wendland(), Vec<2>(0.5, 0.49), 0.1).pressure == 1234.5, tt::tolerance(1e-12));
}

// A linear field p = 100 + 2000 y (hydrostatic-like) at interior points: the
// lattice is symmetric about a lattice point or cell centre, so the weighted
// mean is exact to round-off there. At the free surface it is not (the
// weights are one-sided): that shows the test can tell.
BOOST_AUTO_TEST_CASE(linear_field_in_the_interior) {
  Particles<2> P = block(1000);
  for (std::size_t k = 0; k < P.size(); ++k) P.p[k] = 100 + 2000 * P.x[k][1];
  for (const Vec<2>& at : {Vec<2>(0.5, 0.25), Vec<2>(0.51, 0.25), Vec<2>(0.3, 0.11)}) {
    const auto v = interpolateAt(P, wendland(), at, 0.1);
    BOOST_TEST(v.pressure == 100 + 2000 * at[1], tt::tolerance(1e-10));
  }
  const auto top = interpolateAt(P, wendland(), Vec<2>(0.5, 0.495), 0.1);
  BOOST_TEST(std::abs(top.pressure - (100 + 2000 * 0.495)) > 5.0);
}

BOOST_AUTO_TEST_CASE(a_point_out_of_the_water_is_dry) {
  Particles<2> P = block(1000);
  BOOST_TEST(!interpolateAt(P, wendland(), Vec<2>(0.5, 0.6), 0.1).wet);
  BOOST_TEST(!interpolateAt(P, wendland(), Vec<2>(2.0, 0.2), 0.1).wet);
}

BOOST_AUTO_TEST_CASE(height_and_front_of_a_block) {
  Particles<2> P = block(1000);
  const Real at = 0.31;
  BOOST_TEST(waterHeightAt(P, &at, 0.02) == 0.5, tt::tolerance(1e-12));
  const Real beyond = 1.5;
  BOOST_TEST(waterHeightAt(P, &beyond, 0.02) == 0.0);
  BOOST_TEST(frontPosition(P, 0.02) == 1.0, tt::tolerance(1e-12));
}

// The hydrostatic tank run with a probe at mid-depth and at the bottom
// corner: after settling they read the hydrostatic pressure within 1.5% of
// rho0 g H (the tank itself is within 1%: validation/validate.py; a probe
// by a wall averages over a one-sided support); the gauge reads the depth
// within dx/2 + the column's drop; every file has its header with units.
BOOST_AUTO_TEST_CASE(hydrostatic_tank_probes_read_rho_g_depth) {
  const auto dir = test::scratchDir("probes_tank");
  const auto r = test::runSph({"run", test::caseFile("hydrostatic_tank"), "--output", dir.string(), "--end_time", "1.2",
                               "--probe_points", "0.25", "0.25", "0.02", "0.02", "--probe_names", "middle,corner",
                               "--height_probes", "0.25", "--front_probe", "--probe_interval", "0.1", "--threads",
                               "1"});
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  const auto probes = lines(dir / "probes.csv");
  BOOST_TEST_REQUIRE(probes.size() == 14u);  // header, t = 0, 0.1, ..., 1.2
  BOOST_TEST(probes[0].find("middle pressure [N/m]") != std::string::npos);
  BOOST_TEST(probes[0].find("corner density [kg/m^2]") != std::string::npos);
  std::vector<double> row;
  std::stringstream in(probes.back());
  for (std::string cell; std::getline(in, cell, ',');) row.push_back(std::stod(cell));
  BOOST_TEST_REQUIRE(row.size() == 9u);
  BOOST_TEST(row[0] == 1.2, tt::tolerance(1e-12));
  const double rhoGH = 1000 * 9.81 * 0.5;
  BOOST_TEST(std::abs(row[1] - 1000 * 9.81 * 0.25) / rhoGH < 0.015);
  BOOST_TEST(std::abs(row[5] - 1000 * 9.81 * 0.48) / rhoGH < 0.015);
  const auto heights = lines(dir / "heights.csv");
  BOOST_TEST(heights[0] == "time [s],height at x=0.25 [m]");
  BOOST_TEST(std::abs(std::stod(heights.back().substr(heights.back().find(',') + 1)) - 0.5) < 0.006);
  BOOST_TEST(lines(dir / "front.csv")[0] == "time [s],front x [m]");
}

BOOST_AUTO_TEST_CASE(bad_probe_keys_are_refused) {
  const auto dir = test::scratchDir("probes_bad");
  const std::string tank = test::caseFile("hydrostatic_tank");
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad{
      {{"--probe_points", "0.1", "0.2", "0.3"}, "probe_points needs 2 values per probe (3 given)"},
      {{"--probe_points", "0.1", "0.2", "--probe_names", "a,b"}, "probe_names has 2 names for 1 probe_points"},
      {{"--probe_points", "0.1", "0.2", "0.3", "0.4", "--probe_names", "a,a"}, "probe_names: \"a\" is given twice"},
      {{"--probe_points", "0.1", "0.2", "--probe_names", "a b"}, "probe_names: \"a b\" is not allowed"},
      {{"--probe_names", "a"}, "probe_names is given but there are no probe_points"},
      {{"--probe_interval", "-1", "--front_probe"}, "probe_interval = -1 is out of range"},
      {{"--probe_points", "0.1", "0.2", "--probe_interpolation", "cubic"}, "probe_interpolation"},
  };
  for (const auto& [flags, message] : bad) {
    std::vector<std::string> args{"run", tank, "--output", (dir / "out").string()};
    args.insert(args.end(), flags.begin(), flags.end());
    const auto r = test::runSph(args);
    BOOST_TEST_CONTEXT(message) {
      BOOST_TEST(r.exitCode == 2);
      BOOST_TEST(r.output.find(message) != std::string::npos, r.output);
      BOOST_TEST(!std::filesystem::exists(dir / "out"));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
