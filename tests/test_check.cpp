// `sph check CASE [--KEY VALUE ...]` (case_check.hpp): it states what the
// case implies, warns where the case lies outside a method's measured
// stable range, writes nothing, exits 0 with warnings and 2 on bad input.
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <sstream>
#include <utility>
#include <string>
#include <vector>

using namespace sph;

namespace {

std::string shipped(const std::string& name) { return std::string(SPH_SOURCE_DIR) + "/cases/" + name; }

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(check)

// The shipped dam break is within every range: its figures, no warning.
// The figures are the case's own, worked by hand: a 25 x 50 lattice (1250
// fluid particles), h / dx = 0.015 / 0.01, Mach sqrt(2 g 0.5) / 44 =
// 0.0712, c0 dt / h = 44 x 5e-5 / 0.015 = 0.147.
BOOST_AUTO_TEST_CASE(a_sound_case_gets_its_figures_and_no_warning) {
  const auto dir = test::scratchDir("check_sound");
  const test::Result r = test::runSph({"check", shipped("dam_break_mm.case"), "--output", (dir / "out").string()});
  BOOST_TEST_MESSAGE(r.output);
  BOOST_TEST(r.exitCode == 0);
  for (const char* line : {"particles        2468 (1250 fluid, 1218 wall)", "h / dx           1.5",
                           "Mach 0.0712", "c0 dt / h = 0.147", "wall layers      3 (the support needs 3)",
                           "time estimate", "0 warnings"})
    BOOST_TEST(r.output.find(line) != std::string::npos, "missing: " << line);
  BOOST_TEST(!std::filesystem::exists(dir / "out"));  // nothing written
}

// Where the memory goes, per particle. The parts add up to the total. Two
// of them are counted here by hand from what the water physics of
// cases/dam_break.case keeps per particle:
//   fields:  x, v, a, vHalf (leap-frog), xList (the list's build), 16 B
//            each in 2D, plus rho and id, 8 B each, drho, p, m and c
//            (Monaghan's sound speed), 8 B each (4 in a mixed-precision
//            build: sph::Narrow), plus kind, 1 B: 129 B (113);
//   scratch: one 2D vector per particle for the re-sort, the ghosts'
//            bookkeeping (none: no periodic axis), and in the same bytes
//            the pair loops' p/rho^2 and m/rho and the grid sort's bucket
//            numbers: 16 B.
// A regression gate on the layout: a field allocated that the physics does
// not use (vWall for Monaghan's viscosity, say), or pair-loop arrays of
// their own (16 B more), fail it.
BOOST_AUTO_TEST_CASE(memory_is_told_by_part) {
  const test::Result r = test::runSph({"check", shipped("dam_break.case")});
  BOOST_TEST_REQUIRE(r.exitCode == 0);
  const std::size_t at = r.output.find("  memory ");
  BOOST_TEST_REQUIRE(at != std::string::npos);
  const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
  BOOST_TEST_MESSAGE(line);
  std::istringstream in(line);
  std::string word;
  double mib = 0, total = 0;
  in >> word >> mib >> word >> total >> word >> word >> word;  // memory X MiB, Y B per particle:
  BOOST_TEST_REQUIRE(word == "particle:");
  std::map<std::string, double> part;
  std::string name;
  for (std::string token; in >> token;) {
    if (!token.empty() && (std::isdigit(static_cast<unsigned char>(token[0])) != 0)) {
      part[name] = std::stod(token);
      name.clear();
    } else {
      name += (name.empty() ? "" : " ") + token;
    }
  }
  BOOST_TEST(part.size() == 4u);
  double sum = 0;
  for (const auto& [key, value] : part) sum += value;
  BOOST_TEST(sum == total, boost::test_tools::tolerance(0.01));  // each printed to 3 figures
  BOOST_TEST(part["fields"] == 97.0 + 4 * sizeof(Narrow));
  BOOST_TEST(part["scratch"] == 16.0);
  BOOST_TEST(part["grid"] > 0.0);
  BOOST_TEST(part["neighbour list"] > 0.0);
}

// Each concern the check knows, provoked by a flag: a low c0 (Mach 0.16),
// dt past half the acoustic limit, explicit Euler, the cubic spline at
// h/dx 1.5 and one wall layer too few.
BOOST_AUTO_TEST_CASE(each_concern_is_warned_about) {
  const test::Result r = test::runSph({"check", shipped("dam_break_mm.case"), "--c0", "20", "--dt", "8e-4",
                                       "--integrator", "euler", "--kernel", "cubic_spline", "--wall_layers", "2",
                                       "--wall_layers_override"});
  BOOST_TEST_MESSAGE(r.output);
  BOOST_TEST(r.exitCode == 0);
  BOOST_TEST(count(r.output, "warning: ") == 5);
  for (const char* what : {"Mach 0.157 > 0.1", "past half the measured acoustic limit", "explicit Euler",
                           "cubic spline at h/dx 1.5", "fewer wall layers"})
    BOOST_TEST(r.output.find(what) != std::string::npos, "missing: " << what);
  BOOST_TEST(r.output.find("5 warnings") != std::string::npos);
}

// The acoustic limits sph check states are declared by the kernel rows
// (methods.hpp, measured with sph at h/dx 1.3) for an integrator class:
// they agree within 2% with the linear stability analysis of
// tests/reference/acoustic_cfl_limits.csv (2D, h/dx 1.3; leap-frog and
// symplectic Euler stable while omega dt <= 2, RK4 while <= 2 sqrt 2). 2%:
// the measured limits are where a run blew up, on a 0.01-0.05 grid of c0 dt/h.
BOOST_AUTO_TEST_CASE(declared_acoustic_limits_match_the_stability_analysis) {
  std::ifstream in(std::string(SPH_SOURCE_DIR) + "/tests/reference/acoustic_cfl_limits.csv");
  BOOST_REQUIRE(in.good());
  std::string line;
  int checked = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("kernel,", 0) == 0) continue;
    std::vector<std::string> cell;
    std::stringstream row(line);
    for (std::string x; std::getline(row, x, ',');) cell.push_back(x);
    std::string kernel = cell[0];
    for (char& ch : kernel) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (cell[1] != "2" || cell[2] != "1.3" || !findMethod(kernelMethods<2>(), kernel)) continue;
    CaseConfig c = test::bareWcsph(2);
    c.kernel = kernel;
    for (const auto& [integrator, column] : {std::pair<const char*, int>{"leap_frog", 4}, {"symplectic_euler", 4},
                                             {"rk4", 5}}) {
      c.integrator = integrator;
      const Real reference = std::stod(cell[static_cast<std::size_t>(column)]);
      BOOST_TEST(acousticLimit<2>(c) == reference, boost::test_tools::tolerance(0.02));
      ++checked;
    }
  }
  BOOST_TEST(checked == 6);  // cubic_spline and wendland_c2
}

BOOST_AUTO_TEST_CASE(bad_input_exits_2_naming_it) {
  const test::Result r = test::runSph({"check", shipped("dam_break_mm.case"), "--h", "-1"});
  BOOST_TEST(r.exitCode == 2);
  BOOST_TEST(r.output.find("h = -1 is out of range") != std::string::npos, r.output);
  const test::Result m = test::runSph({"check", "no_such.case"});
  BOOST_TEST(m.exitCode == 2);
  BOOST_TEST(m.output.find("no_such.case") != std::string::npos, m.output);
}

// The wall guard is stated; without it, sph check warns before the run
// that a splash particle may pass the wall particles.
BOOST_AUTO_TEST_CASE(the_wall_guard_is_stated_and_its_absence_warned_about) {
  const test::Result on = test::runSph({"check", shipped("dam_break_mm.case")});
  BOOST_TEST(on.output.find("wall guard       on") != std::string::npos, on.output);
  const test::Result off = test::runSph({"check", shipped("dam_break_mm.case"), "--no-wall_guard"});
  BOOST_TEST(off.exitCode == 0);
  BOOST_TEST(off.output.find("warning: wall_guard = false") != std::string::npos, off.output);
  BOOST_TEST(off.output.find("1 warning") != std::string::npos);
}

// The Mach estimate counts the walls that drive the flow (issue 21). A
// sliding lid: the Couette case with its lid at U = 0.5 m/s and a Tait
// sound speed c0 = 10 U = 5 m/s is Mach 0.1 exactly (no gravity, no initial
// flow: the lid alone sets the speed); at c0 = 2.5 m/s it is Mach 0.2 and
// warned about, naming the c0 that Mach 0.1 needs. A paddle: the wave maker
// at period T = 0.05 s moves at 2 pi A / T = 2 pi 0.03 / 0.05 = 3.77 m/s,
// above the fall speed sqrt(2 g 0.3) = 2.43 m/s; c0 = 37.7 m/s gives 0.09999.
BOOST_AUTO_TEST_CASE(mach_counts_the_lid_and_the_paddle) {
  const std::vector<std::string> lid{"check", shipped("couette_2d.case"), "--lid_velocity", "0.5", "0"};
  auto with = [](std::vector<std::string> a, std::initializer_list<std::string> more) {
    a.insert(a.end(), more);
    return a;
  };
  const test::Result r = test::runSph(with(lid, {"--eos", "tait", "--gamma", "7", "--c0", "5"}));
  BOOST_TEST_MESSAGE(r.output);
  BOOST_TEST(r.exitCode == 0);
  BOOST_TEST(r.output.find("expected speed 0.5 m/s (lid 0.5): Mach 0.1\n") != std::string::npos, r.output);
  BOOST_TEST(r.output.find("warning: Mach") == std::string::npos, r.output);
  const test::Result fast = test::runSph(with(lid, {"--eos", "tait", "--gamma", "7", "--c0", "2.5"}));
  BOOST_TEST(fast.output.find("Mach 0.2") != std::string::npos, fast.output);
  BOOST_TEST(fast.output.find("warning: Mach 0.2 > 0.1") != std::string::npos, fast.output);
  BOOST_TEST(fast.output.find("at least 5 m/s keeps Mach <= 0.1: c0 >= 5 m/s") != std::string::npos, fast.output);
  // The linear EOS's sound speed is sqrt(k): the advice is k in m^2/s^2.
  const test::Result linear = test::runSph(with(lid, {"--eos", "linear", "--k", "1"}));
  BOOST_TEST(linear.output.find("Mach 0.5") != std::string::npos, linear.output);
  BOOST_TEST(linear.output.find("k >= 25 m^2/s^2 (c = sqrt(k))") != std::string::npos, linear.output);

  const test::Result paddle =
      test::runSph({"check", shipped("wave_paddle.case"), "--paddle_period", "0.05", "--c0", "37.7"});
  BOOST_TEST_MESSAGE(paddle.output);
  BOOST_TEST(paddle.exitCode == 0);
  BOOST_TEST(paddle.output.find("paddle 2 pi A / T 3.77") != std::string::npos, paddle.output);
  BOOST_TEST(paddle.output.find("): Mach 0.1\n") != std::string::npos, paddle.output);
}

BOOST_AUTO_TEST_SUITE_END()
