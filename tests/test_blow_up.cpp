// A run that blows up is detected, explained, and leaves its outputs valid.
// The seed scheme at h/dx = 2 (dam break with spacing 0.005, h = 0.01) lets
// two particles coincide within ~650 steps: the pressure kernel's r_ij/q is
// then 0/0 and the acceleration NaN.
#include "pvd_reader.hpp"
#include "test_support.hpp"


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

BOOST_AUTO_TEST_SUITE_END()
