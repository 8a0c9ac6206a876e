// Probes: Shepard-normalised interpolation at points (a constant field
// exactly, a linear one exactly in the interior of a lattice, where the
// kernel weights are symmetric; a dry point is dry), the water height and the
// front of a block, and a real run of the hydrostatic tank whose probe reads
// rho0 g (H - y) and whose files carry units; bad probe keys refused.
#include "cli_support.hpp"

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

// probe_radius: a sensor's points lie on its disc, in the plane of the wall
// face nearest to it, spread about its centre (their mean is the centre
// within 2% of r: the Vogel spiral is not exactly symmetric).
BOOST_AUTO_TEST_CASE(sensor_disc_on_the_nearest_face) {
  using V3 = Vec<3>;
  const std::vector<std::pair<V3, V3>> boxes{{V3(0, 0, 0), V3(3.22, 1, 1)},
                                              {V3(0.6635, 0.295, 0), V3(0.8245, 0.698, 0.161)}};
  BOOST_TEST(nearestFaceAxis<3>(V3(0.8245, 0.4965, 0.021), boxes) == 0);  // the box's face, not the floor
  BOOST_TEST(nearestFaceAxis<3>(V3(0.7635, 0.4965, 0.161), boxes) == 2);  // its top
  BOOST_TEST(nearestFaceAxis<3>(V3(2.0, 0.01, 0.5), boxes) == 1);         // a side wall
  const V3 c(0.8245, 0.4965, 0.061);
  const auto pts = sensorDiscPoints<3>(c, 0, 0.03, 0.03);
  BOOST_TEST(pts.size() == 16u);  // (4 r / h)^2
  V3 mean = V3::Zero();
  for (const V3& x : pts) {
    BOOST_TEST(x[0] == c[0]);
    BOOST_TEST((x - c).norm() <= 0.03 + 1e-12);
    mean += x / static_cast<Real>(pts.size());
  }
  BOOST_TEST((mean - c).norm() < 0.02 * 0.03);
  BOOST_TEST(sensorDiscPoints<3>(c, 0, 0, 0.03).size() == 1u);
  const auto seg = sensorDiscPoints<2>(Vec<2>(0.005, 0.05), 0, 0.02, 0.015);
  BOOST_TEST(seg.size() == 11u);  // ceil(8 r / h)
  for (const auto& x : seg) BOOST_TEST(x[0] == 0.005);
}

// A sensor of radius r averages the pressure over its area: in a linear
// field p = 1000 + 20000 y (deep in the block) it reads the centre's value;
// a sensor centred on the free surface, half in the air, reads about half
// the pressure at its wet half's centre (the air side counts as 0), where
// a point probe there reads the water next to it.
BOOST_AUTO_TEST_CASE(sensor_averages_over_its_area) {
  Particles<2> P = block(1000);
  for (std::size_t k = 0; k < P.size(); ++k) P.p[k] = 1000 + 20000 * P.x[k][1];
  const Vec<2> centre(0.0, 0.25);  // on the left face of the block
  const auto disc = sensorDiscPoints<2>(centre, 0, 0.05, 0.03);
  const auto s = sensorAt(P, wendland(), centre, disc, 0.05, 0.1);
  BOOST_TEST_REQUIRE(s.wet);
  BOOST_TEST(s.pressure == 1000 + 20000 * 0.25, tt::tolerance(0.01));
  for (std::size_t k = 0; k < P.size(); ++k) P.p[k] = 5000;
  const Vec<2> top(0.0, 0.5);
  const auto half = sensorAt(P, wendland(), top, sensorDiscPoints<2>(top, 0, 0.1, 0.03), 0.1, 0.1);
  BOOST_TEST_REQUIRE(half.wet);
  BOOST_TEST(half.pressure > 0.4 * 5000);
  BOOST_TEST(half.pressure < 0.65 * 5000);
}

// probe_window: the filtered column is the mean of the samples in
// (t - T, t]: a pressure that jumps from 0 to 9000 at t = 0.01 (a sample
// every 1 ms, T = 5 ms) reads 9000 k / 5 k ms after the jump, then 9000;
// a one-sample spike of 50 000 reads 10 000 (its impulse over T) while it
// is in the window and nothing after.
BOOST_AUTO_TEST_CASE(moving_average_over_the_window) {
  Particles<2> P = block(1000);
  CaseConfig c;
  c.dimension = 2;
  c.probePoints = {0.5, 0.25};
  c.probeInterval = 0.001;
  c.probeWindow = 0.005;
  c.spacing = 0.02;
  ProbeFiles<2> files(c, wendland());
  auto pressureAt = [&](Real t, Real p) {
    for (std::size_t k = 0; k < P.size(); ++k) P.p[k] = p;
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", t);
    files.sample(P, t, text);
  };
  for (int i = 0; i <= 30; ++i) {
    const Real t = 0.001 * i;
    pressureAt(t, i == 25 ? 50000 : (i >= 10 ? 9000 : 0));
  }
  std::vector<std::vector<double>> rows;
  std::stringstream in(*files.files()[0].text);
  std::string line;
  std::getline(in, line);
  BOOST_TEST(line == "time [s],p1 pressure [N/m],p1 density [kg/m^2],p1 vx [m/s],p1 vy [m/s],p1 pressure filtered [N/m]");
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  BOOST_TEST_REQUIRE(rows.size() == 31u);
  BOOST_TEST(rows[9][5] == 0.0);
  BOOST_TEST(rows[10][5] == 1800.0, tt::tolerance(1e-9));
  BOOST_TEST(rows[12][5] == 5400.0, tt::tolerance(1e-9));
  BOOST_TEST(rows[14][5] == 9000.0, tt::tolerance(1e-9));
  BOOST_TEST(rows[25][1] == 50000.0, tt::tolerance(1e-9));
  BOOST_TEST(rows[25][5] == (4 * 9000.0 + 50000) / 5, tt::tolerance(1e-9));
  BOOST_TEST(rows[29][5] == (4 * 9000.0 + 50000) / 5, tt::tolerance(1e-9));
  BOOST_TEST(rows[30][5] == 9000.0, tt::tolerance(1e-9));
}

// A sensor with a moving average continues on --resume as the run never
// stopped: the window's samples are read back from the rows probes.csv
// kept, which hold 10 significant digits, so the filtered column after the
// resume matches to 1e-9 (the other columns exactly).
BOOST_AUTO_TEST_CASE(sensor_window_resumes_bit_for_bit) {
  const auto dir = test::scratchDir("probes_window_resume");
  const std::vector<std::string> flags{"--probe_points", "0.0", "0.1",  "--probe_radius", "0.02", "--probe_window",
                                       "0.03",           "--probe_interval", "0.002", "--threads", "1"};
  auto run = [&](const std::string& out, const std::string& end) {
    std::vector<std::string> args{"run", test::caseFile("hydrostatic_tank"), "--output", (dir / out).string(),
                                  "--end_time", end};
    args.insert(args.end(), flags.begin(), flags.end());
    return test::runSph(args);
  };
  const auto whole = run("whole", "0.1");
  BOOST_TEST_REQUIRE(whole.exitCode == 0, whole.output);
  const auto first = run("parts", "0.05");
  BOOST_TEST_REQUIRE(first.exitCode == 0, first.output);
  const auto rest = test::runSph({"run", "--resume", (dir / "parts").string(), "--end_time", "0.1"});
  BOOST_TEST_REQUIRE(rest.exitCode == 0, rest.output);
  const auto a = lines(dir / "whole" / "probes.csv"), b = lines(dir / "parts" / "probes.csv");
  BOOST_TEST_REQUIRE(a.size() == 52u);  // header, t = 0, 0.002, ..., 0.1
  BOOST_TEST(a[0].find("p1 pressure filtered [N/m]") != std::string::npos);
  BOOST_TEST_REQUIRE(b.size() == a.size());
  for (std::size_t k = 1; k < a.size(); ++k) {
    std::vector<double> x, y;
    for (auto [line, row] : {std::pair{&a[k], &x}, std::pair{&b[k], &y}}) {
      std::stringstream in(*line);
      for (std::string cell; std::getline(in, cell, ',');) row->push_back(std::stod(cell));
    }
    BOOST_TEST_REQUIRE(x.size() == y.size());
    for (std::size_t c = 0; c + 1 < x.size(); ++c) BOOST_TEST(x[c] == y[c]);
    BOOST_TEST(x.back() == y.back(), tt::tolerance(1e-9));
  }
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
      {{"--probe_points", "0.1", "0.2", "--probe_radius", "-0.01"}, "probe_radius = -0.01 is out of range"},
      {{"--probe_points", "0.1", "0.2", "--probe_interval", "0.01", "--probe_window", "0.005"},
       "probe_window = 0.005000 s is shorter than probe_interval = 0.010000 s"},
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
