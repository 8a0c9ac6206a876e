// A new run from an sph snapshot (--particle_file) continues the run that
// wrote it: its wall particles stay walls (with their masses and, for
// dynamic walls, their integrated densities) and the fluid keeps its
// densities, so the restarted run matches the uninterrupted one.
//
// The reference is the uninterrupted run itself: the default dam break
// (cases/dam_break.case: leap-frog, fixed dt = 5e-5 s, continuity density,
// dummy walls) to t = 0.02 s, against the same case restarted from its
// snapshot at t = 0.01 s (step 200) and run to 0.02 s, compared particle by
// particle (by id) at t = 0.02 s.
//
// What is not bitwise, and why: a new run evaluates the forces at its first
// state from the snapshot's integer-time velocity v^n, while the running
// leap-frog evaluated a^n with its predicted velocity v^{n-1/2} + a^{n-1}
// dt/2 (integrators/leap_frog.hpp); the two differ by (a^n - a^{n-1}) dt/2,
// which only velocity-dependent forces (the artificial viscosity) see. So:
//  - with alpha = 0 the restart is bit for bit the uninterrupted run
//    (measured: 0 difference in x, v, rho, m, kind), dummy and dynamic walls;
//  - with the case's alpha = 0.02, measured max |dx| = 2.1e-10 m,
//    max |dv| = 1.2e-8 m/s, max |drho| = 1.2e-7 kg/m^2 at t = 0.02 s
//    (2468 particles, 200 steps after the restart). The tolerances below,
//    1e-8 m, 1e-6 m/s, 1e-5 kg/m^2, are ~50x those: far above the measured
//    start-up difference, far below a change of physics (dx = 0.01 m; the
//    surge moves ~1e-3 m per 0.01 s).
// The bit-for-bit variants run with neighbour_skin = 0: with a skin the
// uninterrupted run keeps the list of its last rebuild while the new run
// builds one at the snapshot's positions, so the same pairs are summed in
// another order (round-off; `sph run --resume` instead rebuilds the
// recorded list and stays bit for bit: test_run_folder.cpp).
// 3D (cases/dam_break_3d.case, coarse, dynamic walls): the restart runs and
// keeps every wall particle as a wall.
#include "cli_support.hpp"
#include "snapshot_by_id.hpp"

using namespace sph;

namespace {

using test::Particle;
using test::load;
using test::compare;
using test::Difference;

int walls(const std::map<std::int64_t, Particle>& s) {
  int n = 0;
  for (const auto& [id, p] : s) n += p.kind == 1;
  return n;
}

// The dam break to 0.02 s, uninterrupted and restarted from its snapshot at
// 0.01 s, with `extra` flags for both; returns their states at 0.02 s.
std::pair<std::map<std::int64_t, Particle>, std::map<std::int64_t, Particle>> damBreakBothWays(
    const std::string& name, const std::vector<std::string>& extra) {
  const auto dir = test::scratchDir("restart_" + name);
  auto run = [&](const std::string& out, std::vector<std::string> more) {
    std::vector<std::string> args{"run", test::caseFile("dam_break"), "--output", (dir / out).string(), "--end_time",
                                  "0.02", "--output_interval", "0.01", "--threads", "1", "--no-progress"};
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), more.begin(), more.end());
    const auto r = test::runSph(args);
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  };
  run("whole", {});
  const auto snapshot = dir / "whole" / "dam_break_00001.vtp";
  run("restarted", {"--particle_file", snapshot.string()});
  const auto atSnapshot = load(snapshot);
  BOOST_TEST_REQUIRE(walls(atSnapshot) > 0);
  const auto whole = load(dir / "whole" / "dam_break_00002.vtp");
  const auto restarted = load(dir / "restarted" / "dam_break_00001.vtp");
  BOOST_TEST(walls(restarted) == walls(atSnapshot));
  return {whole, restarted};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(restart)

BOOST_AUTO_TEST_CASE(dummy_walls_continue_bit_for_bit_without_viscosity) {
  const auto [whole, restarted] = damBreakBothWays("dummy_inviscid", {"--neighbour_skin", "0", "--alpha", "0"});
  const Difference d = compare(whole, restarted);
  BOOST_TEST(d.x == 0);
  BOOST_TEST(d.v == 0);
  BOOST_TEST(d.rho == 0);
  BOOST_TEST(d.m == 0);
  BOOST_TEST(d.kinds == 0);
}

BOOST_AUTO_TEST_CASE(dynamic_walls_continue_bit_for_bit_without_viscosity) {
  // Dynamic walls integrate their density: the snapshot's must be kept
  // (walls regenerated from the case would restart at rho0).
  const auto [whole, restarted] = damBreakBothWays("dynamic_inviscid", {"--neighbour_skin", "0", "--alpha", "0", "--boundary", "dynamic"});
  int compressedWalls = 0;
  for (const auto& [id, p] : whole) compressedWalls += p.kind == 1 && std::abs(p.rho - 1000) > 1e-3;
  BOOST_TEST(compressedWalls > 0);
  const Difference d = compare(whole, restarted);
  BOOST_TEST(d.x == 0);
  BOOST_TEST(d.v == 0);
  BOOST_TEST(d.rho == 0);
  BOOST_TEST(d.kinds == 0);
}

BOOST_AUTO_TEST_CASE(the_default_dam_break_continues_to_round_off) {
  const auto [whole, restarted] = damBreakBothWays("default", {});
  const Difference d = compare(whole, restarted);
  BOOST_TEST(d.x <= 1e-8);
  BOOST_TEST(d.v <= 1e-6);
  BOOST_TEST(d.rho <= 1e-5);
  BOOST_TEST(d.m == 0);
  BOOST_TEST(d.kinds == 0);
}

BOOST_AUTO_TEST_CASE(a_3d_restart_keeps_its_walls) {
  const auto dir = test::scratchDir("restart_3d");
  const std::vector<std::string> coarse{"--boundary", "dynamic", "--density", "continuity", "--spacing", "0.04", "--h",
                                        "0.04", "--output_every", "10", "--threads", "1", "--no-progress"};
  auto run = [&](const std::string& out, const std::string& endTime, std::vector<std::string> more) {
    std::vector<std::string> args{"run", test::caseFile("dam_break_3d"), "--output", (dir / out).string(),
                                  "--end_time", endTime};
    args.insert(args.end(), coarse.begin(), coarse.end());
    args.insert(args.end(), more.begin(), more.end());
    const auto r = test::runSph(args);
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  };
  run("whole", "0.01", {});
  const auto snapshot = load(dir / "whole" / "dam_break_3d_00001.vtp");
  run("restarted", "0.02", {"--particle_file", (dir / "whole" / "dam_break_3d_00001.vtp").string()});
  const auto restarted = load(dir / "restarted" / "dam_break_3d_00001.vtp");
  BOOST_TEST(walls(snapshot) > 1000);
  BOOST_TEST(walls(restarted) == walls(snapshot));
  BOOST_TEST(restarted.size() == snapshot.size());
  int sameWalls = 0;
  for (const auto& [id, p] : snapshot) sameWalls += p.kind == 1 && restarted.count(id) && restarted.at(id).kind == 1;
  BOOST_TEST(sameWalls == walls(snapshot));
}

BOOST_AUTO_TEST_CASE(walls_that_do_not_fit_the_case_are_refused) {
  const auto dir = test::scratchDir("restart_refused");
  auto run = [&](const std::string& out, std::vector<std::string> more) {
    std::vector<std::string> args{"run", test::caseFile("dam_break"), "--output", (dir / out).string(), "--end_time",
                                  "0.0002", "--output_interval", "0.0001", "--threads", "1", "--no-progress"};
    args.insert(args.end(), more.begin(), more.end());
    return test::runSph(args);
  };
  BOOST_TEST_REQUIRE(run("whole", {}).exitCode == 0);
  const std::string snapshot = (dir / "whole" / "dam_break_00001.vtp").string();
  for (const auto& [flags, expected] :
       std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--boundary", "reflecting"}, "but the case has none"},
           {{"--wall_layers", "5"}, "but the case makes"}}) {
    std::vector<std::string> more = flags;
    more.insert(more.end(), {"--particle_file", snapshot});
    const auto r = run("refused", more);
    BOOST_TEST(r.exitCode == 2, r.output);
    BOOST_TEST(r.output.find("sph: error: particle_file " + snapshot + " holds") != std::string::npos, r.output);
    BOOST_TEST(r.output.find(expected) != std::string::npos, r.output);
    BOOST_TEST(!std::filesystem::exists(dir / "refused"));
  }
}

BOOST_AUTO_TEST_SUITE_END()
