// A run that blows up is detected, explained, and leaves its outputs valid.
// The seed scheme at h/dx = 2 (dam break with spacing 0.005, h = 0.01) lets
// two particles coincide within ~650 steps: the pressure kernel's r_ij/q is
// then 0/0 and the acceleration NaN.
#include "pvd_reader.hpp"
#include "test_support.hpp"

#include <nlohmann/json.hpp>

#include <vtkPointData.h>

#include <algorithm>
#include <cmath>

using namespace sph;

BOOST_AUTO_TEST_SUITE(blow_up)

BOOST_AUTO_TEST_CASE(nan_stops_the_run_and_leaves_a_readable_series) {
  const auto dir = test::scratchDir("blowup");
  const auto r = test::runSph({"run", test::caseFile("dam_break_seed"), "--output", dir.string(),
                               "--spacing", "0.005", "--output_every", "100", "--end_time", "0.5"});
  BOOST_TEST(r.exitCode == 3, r.output);
  BOOST_TEST(r.output.find("the run blew up at step ") != std::string::npos, r.output);
  BOOST_TEST(r.output.find("is not finite") != std::string::npos, r.output);
  BOOST_TEST(r.output.find("are intact in") != std::string::npos, r.output);
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    BOOST_TEST(entry.path().extension() != ".tmp", "left behind " << entry.path());

  const auto series = test::readPvd(dir / "dam_break_seed.pvd");
  BOOST_TEST(series.size() >= 2u);
  for (const auto& e : series) BOOST_TEST(e.data->GetNumberOfPoints() == 5000);
}

// The Scene API reports the same failure with the particle and quantity.
BOOST_AUTO_TEST_CASE(state_check_names_particle_and_quantity) {
  auto s = test::makeScene<2>({Vec<2>(0.5, 0.5), Vec<2>(0.504, 0.5)}, {}, SeedWcsphParameters{}, true, 1e-4);
  s.particles().v[1][0] = std::numeric_limits<Real>::quiet_NaN();
  s.particles().vHalf[1][0] = std::numeric_limits<Real>::quiet_NaN();
  const auto failure = s.step();
  BOOST_TEST_REQUIRE(failure.has_value());
  BOOST_TEST(!failure->detail.empty());
  BOOST_TEST((failure->quantity == "position" || failure->quantity == "acceleration" ||
              failure->quantity == "velocity"));
}

// Nonsense in a short run (issue 21): the default dam break with reflecting
// walls at dt = 1 s (acoustic number c0 dt / h = 2900, 15000x the shipped
// dt) reaches ~6e4 m/s, Mach 1.4e3, in its first step, still finite and
// inside the box, so the state check passes it. Before the regime check ran
// before every snapshot, the run took its 2 steps, ended with exit 0 and
// wrote snapshots at 1e14 m/s. Now the check runs before each snapshot
// (output_interval 0.01 s: one is due at step 1) and at the end (an
// output_interval longer than the run: only the end), so the run stops
// with exit 3 naming the Mach number in its message and run.json, and the
// series holds only the start.
BOOST_AUTO_TEST_CASE(a_two_step_run_is_checked_before_its_snapshots) {
  for (const char* interval : {"0.01", "5"}) {
    const auto dir = test::scratchDir(std::string("two_steps_") + interval);
    const auto r = test::runSph({"run", test::caseFile("dam_break"), "--output", dir.string(), "--boundary",
                                 "reflecting", "--dt", "1", "--end_time", "2", "--output_interval", interval,
                                 "--no-progress"});
    BOOST_TEST(r.exitCode == 3, r.output);
    BOOST_TEST(r.output.find("the run left its regime at step") != std::string::npos, r.output);
    BOOST_TEST(r.output.find(": Mach ") != std::string::npos, r.output);
    const auto series = test::readPvd(dir / "dam_break.pvd");
    BOOST_TEST_REQUIRE(series.size() == 1u, "interval " << interval);
    BOOST_TEST(series[0].time == 0.0);
    // run.json names the stop and its cause.
    std::ifstream in(dir / "run.json");
    const auto record = nlohmann::json::parse(in);
    BOOST_TEST(record.at("status").get<std::string>() == "blew_up");
    BOOST_TEST(record.at("message").get<std::string>().find(": Mach ") != std::string::npos);
    BOOST_TEST(!std::filesystem::exists(dir / "dam_break_00001.vtp"));
  }
}

// A sound short run still passes: the shipped dam break for two steps of
// its own dt ends with exit 0 and its two snapshots (the start, the end).
BOOST_AUTO_TEST_CASE(a_sound_short_run_passes) {
  const auto dir = test::scratchDir("two_sound_steps");
  const auto r = test::runSph({"run", test::caseFile("dam_break"), "--output", dir.string(), "--end_time", "1e-4",
                               "--no-progress"});
  BOOST_TEST(r.exitCode == 0, r.output);
  BOOST_TEST(r.output.find("steps            2") != std::string::npos, r.output);
  BOOST_TEST(test::readPvd(dir / "dam_break.pvd").size() == 2u);
}

BOOST_AUTO_TEST_SUITE_END()
