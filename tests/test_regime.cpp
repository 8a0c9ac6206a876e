// The regime check (sph/regime_check.hpp): its references from the model's
// EOS, its measures on a lattice (no particle alone, the neighbour count, a
// pair brought together is seen),
// and runs that leave the regime without a NaN, each stopped with its cause
// named, exit 3, the cause in run.json and the snapshots before it intact:
// explicit Euler past its acoustic limit (Mach), a column whose sound speed
// is too low (compressed past the density window), a block dropped with a time
// step 20x the seed's (the fluid scatters into spray); `regime_check =
// warn` lets the same run finish with a warning.
#include "test_support.hpp"

#include "sph/model_registry.hpp"
#include "sph/regime_check.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>

using namespace sph;
namespace tt = boost::test_tools;

namespace {

nlohmann::json runJson(const std::filesystem::path& dir) {
  std::ifstream in(dir / "run.json");
  return nlohmann::json::parse(in);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(regime)

// The references the regime check judges against come from the model's EOS:
// the sound speed at rho0 (Tait: c0, by its definition c = c0 (rho/rho0)^((gamma-1)/2);
// linear p = k (rho - rho0), the seed's too: sqrt(k)), none for the polytropic
// toy star; the density window's rho0 for Tait only. Exact up to one rounding.
BOOST_AUTO_TEST_CASE(the_references_come_from_the_model) {
  CaseConfig c;
  c.k = 16;
  c.rho0 = 1000;
  c.c0 = 30;
  c.gamma = 7;
  c.model = "seed_wcsph";
  const Model<2> seed = makeModel<2>(withDefaults(c));
  BOOST_TEST(seed.regimeSoundSpeed() == 4.0, tt::tolerance(1e-15));
  BOOST_TEST(seed.regimeDensity() == 0.0);
  c.model = "wcsph";
  const std::pair<const char*, std::pair<double, double>> expected[] = {
      {"tait", {30.0, 1000.0}}, {"linear", {4.0, 0.0}}, {"linear_clamped", {4.0, 0.0}}, {"polytropic", {0.0, 0.0}}};
  for (const auto& [eos, reference] : expected) {
    c.eos = eos;
    const Model<2> m = makeModel<2>(withDefaults(c));
    BOOST_TEST_CONTEXT("eos " << eos) {
      BOOST_TEST(m.regimeSoundSpeed() == reference.first, tt::tolerance(1e-15));
      BOOST_TEST(m.regimeDensity() == reference.second);
    }
  }
}

BOOST_AUTO_TEST_CASE(measures_on_a_lattice) {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = "wendland_c2";
  c.h = 0.013;
  c.spacing = 0.01;
  c.blockMin = {0, 0};
  c.blockMax = {0.3, 0.3};
  Scene<2> scene = test::sceneOf<2>(c);
  // (The list's Verlet skin holds pairs beyond the support: counted only within it.)
  RegimeState s = measureRegime(scene.particles(), scene.neighbours(), 10.0, 0.01, 0, scene.support());
  BOOST_TEST(scene.neighbourSkin() > 0);
  BOOST_TEST(s.isolatedFraction == 0.0);
  BOOST_TEST(s.pairedFraction == 0.0);
  BOOST_TEST(s.meanNeighbours == scene.meanNeighbours(), tt::tolerance(1e-12));  // no walls: every particle is fluid
  BOOST_TEST(s.mach == 0.0);
  // Two particles brought within 0.1 dx of each other: both are paired.
  auto& P = scene.particles();
  P.x[1] = P.x[0] + Vec<2>(0.001, 0);
  P.v[0] = Vec<2>(0, 25);
  s = measureRegime(P, scene.neighbours(), 10.0, 0.01);
  BOOST_TEST(s.pairedFraction * static_cast<Real>(P.fluidCount()) == 2.0, tt::tolerance(1e-9));
  BOOST_TEST(s.mach == 2.5, tt::tolerance(1e-12));
  RegimeCheck check(10.0, 0.01, P.fluidCount());
  check.start(RegimeState{0, 0, 0, 12, 0});
  BOOST_TEST(check.judge(s, 1e-3, 0.013).stop.find("Mach 2.5") == 0u);
  // One particle 20% denser than rho0 (no particle faster than sound): compressed.
  P.v[0] = Vec<2>::Zero();
  P.rho[2] = 1.2 * c.rho0;
  s = measureRegime(P, scene.neighbours(), 10.0, 0.01, c.rho0);
  BOOST_TEST(s.densityMax == 1.2, tt::tolerance(1e-12));
  BOOST_TEST(check.judge(s, 1e-3, 0.013).stop.find("compressed: a fluid particle's density is 1.2 rho0") == 0u);
  P.rho[2] = 1.09 * c.rho0;  // inside the window
  BOOST_TEST(check.judge(measureRegime(P, scene.neighbours(), 10.0, 0.01, c.rho0), 1e-3, 0.013).stop.empty());
  // One particle's density not positive (a splash particle leaving a wall,
  // docs/methods/boundaries.md): rarefied, at zero and below.
  for (const Real rho : {0.0, -15.9}) {
    P.rho[3] = rho;
    s = measureRegime(P, scene.neighbours(), 10.0, 0.01, c.rho0);
    BOOST_TEST(s.densityMin == rho);
    BOOST_TEST(check.judge(s, 1e-3, 0.013).stop.find("rarefied: a fluid particle's density is") == 0u);
  }
  // With a neighbour compressed too (what follows in a run): rarefied, the
  // cause, is named, not compressed, which would blame the time step.
  P.rho[2] = 1.2 * c.rho0;
  BOOST_TEST(check.judge(measureRegime(P, scene.neighbours(), 10.0, 0.01, c.rho0), 1e-3, 0.013)
                 .stop.find("rarefied") == 0u);
  P.rho[2] = c.rho0;
  P.rho[3] = 1e-3;  // positive, however small: not this check's business
  BOOST_TEST(check.judge(measureRegime(P, scene.neighbours(), 10.0, 0.01, c.rho0), 1e-3, 0.013).stop.empty());
}

// A sound speed far too low for the column (Tait, c0 = 5 m/s: B = rho0 c0^2
// / 7 = 3.6 kPa against rho0 g 2a = 4.9 kPa at the floor, so the bottom of
// the column is at (1 + 4.9/3.6)^(1/7) = 1.13 rho0 from the start).
BOOST_AUTO_TEST_CASE(a_column_compressed_past_the_density_window_is_stopped) {
  const auto dir = test::scratchDir("regime_compressed");
  const auto r = test::runSph({"run", test::caseFile("dam_break_mm"), "--output", dir.string(), "--c0", "5",
                               "--spacing", "0.02", "--h", "0.03", "--dt", "1e-3", "--threads", "1"});
  BOOST_TEST(r.exitCode == 3, r.output);
  BOOST_TEST(r.output.find("compressed: a fluid particle's density is 1.1") != std::string::npos, r.output);
  BOOST_TEST(runJson(dir)["message"].get<std::string>().find("compressed") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(explicit_euler_past_its_limit_is_stopped_as_mach) {
  const auto dir = test::scratchDir("regime_euler");
  const auto r = test::runSph({"run", test::caseFile("dam_break_mm"), "--output", dir.string(), "--integrator", "euler",
                               "--dt", "5e-4", "--boundary", "reflecting", "--density", "summation",
                               "--hydrostatic_start=false", "--delta", "0", "--threads", "1"});
  BOOST_TEST(r.exitCode == 3, r.output);
  BOOST_TEST(r.output.find("the run left its regime at step 10") != std::string::npos, r.output);
  BOOST_TEST(r.output.find("Mach") != std::string::npos);
  const auto j = runJson(dir);
  BOOST_TEST(j["status"] == "blew_up");
  BOOST_TEST(j["message"].get<std::string>().find("Mach") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_block_scattered_into_spray_is_stopped_and_warn_lets_it_go) {
  const auto dir = test::scratchDir("regime_spray");
  const auto r = test::runSph({"run", test::caseFile("block_drop"), "--output", (dir / "stop").string(), "--dt", "2e-3",
                               "--output_every", "50", "--threads", "1"});
  BOOST_TEST_REQUIRE(r.exitCode == 3, r.output);
  BOOST_TEST(r.output.find("the fluid is breaking up") != std::string::npos, r.output);
  const auto j = runJson(dir / "stop");
  BOOST_TEST(j["status"] == "blew_up");
  // The last snapshot is from before the stop: every 50 steps up to the
  // stop's step, excluded (a check before a snapshot stops the run before
  // it is written). The spray forms after step 150: at step 200 to 210
  // (double), 200 (mixed precision).
  const long stopStep = j["summary"]["steps"].get<long>();
  BOOST_TEST(stopStep > (std::string(kBuildPrecision) == "double" ? 200 : 150));
  const long lastSnapshot = (stopStep - 1) / 50;
  char name[48], next[48];
  std::snprintf(name, sizeof name, "block_drop_%05ld.vtp", lastSnapshot);
  std::snprintf(next, sizeof next, "block_drop_%05ld.vtp", lastSnapshot + 1);
  BOOST_TEST(std::filesystem::exists(dir / "stop" / name), name);
  BOOST_TEST(!std::filesystem::exists(dir / "stop" / next), next);
  const auto w = test::runSph({"run", test::caseFile("block_drop"), "--output", (dir / "warn").string(), "--dt", "2e-3",
                               "--end_time", "0.5", "--regime_check", "warn", "--threads", "1"});
  BOOST_TEST(w.exitCode == 0, w.output);
  BOOST_TEST(w.output.find("sph: warning: the run left its regime") != std::string::npos, w.output);
}

BOOST_AUTO_TEST_SUITE_END()
