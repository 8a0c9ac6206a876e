// The neighbour list's Verlet skin (neighbour_skin, scene.hpp): a list
// built with radius R (1 + s) and kept until a particle has moved more than
// s R / 2 since its build.
//
// - A run with a skin is the run without one to round-off: the same pairs
//   contribute (those in the skin contribute exactly 0), summed in another
//   order (the grid's cells are wider, the particles are sorted less often).
//   Measured at 200 steps of the water dam break (cases/dam_break.case,
//   skin 0.05, several rebuilds): max |dx| 2e-16 m, |dv| 1e-14 m/s, |drho|
//   6e-13 kg/m^2; at 400 steps of the periodic Poiseuille flow driven 100x
//   harder than the case (particles cross the periodic face between
//   rebuilds): |dx| 3e-19 m, |dv| 3e-18 m/s, |drho| 1e-12. Tolerances
//   (below) are 1e4-1e6 x those, and far below what one missed pair does
//   in one step (a pressure force ~ g: dv ~ g dt = 5e-4 m/s in the dam
//   break; a viscous force ~ nu u / dx^2 dt ~ 1e-7 m/s in the Poiseuille flow).
// - The list is rebuilt when one particle moves more than half the skin
//   (and not before), and then holds a pair that came closer than R.
// - Resume bit for bit with a skin: tests/test_run_folder.cpp
//   (resume_is_bit_identical, the *_skin variants).
#include "snapshot_by_id.hpp"
#include "test_support.hpp"

using namespace sph;
namespace tt = boost::test_tools;

namespace {

using Snapshot = std::map<std::int64_t, test::Particle>;
struct Runs {
  Snapshot start, without, with;  // the first snapshot; the last ones with skin 0 and with the skin
};

// `case` run to `end` with skin 0 and with `skin`, snapshots by particle id.
Runs withAndWithoutSkin(const std::string& name, const std::string& skin, const std::string& end,
                        const std::vector<std::string>& extra) {
  const auto dir = test::scratchDir("skin_" + name);
  auto run = [&](const std::string& s) {
    std::vector<std::string> args{"run",      test::caseFile(name), "--output", (dir / s).string(), "--end_time",
                                  end,        "--output_interval",  end,        "--threads",        "1",
                                  "--no-progress", "--neighbour_skin", s};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = test::runSph(args);
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
    return test::load(dir / s / (name + "_00001.vtp"));
  };
  Runs r;
  r.without = run("0");
  r.with = run(skin);
  r.start = test::load(dir / "0" / (name + "_00000.vtp"));
  return r;
}

// Every pair of owned particles closer than the support is in the list.
template <int D>
std::size_t missingPairs(const Scene<D>& s) {
  const auto& P = s.particles();
  const Real R2 = s.support() * s.support();
  std::size_t missing = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    std::vector<std::uint32_t> listed;
    s.neighbours().forEach(i, [&](std::uint32_t j) { listed.push_back(j); });
    for (std::size_t j = 0; j < P.size(); ++j)
      if (j != i && (P.x[i] - P.x[j]).squaredNorm() < R2 &&
          std::find(listed.begin(), listed.end(), j) == listed.end())
        ++missing;
  }
  return missing;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(neighbour_skin)

BOOST_AUTO_TEST_CASE(dam_break_with_a_skin_is_the_run_without_to_round_off) {
  const Runs r = withAndWithoutSkin("dam_break", "0.05", "0.01", {});
  const test::Difference d = test::compare(r.without, r.with);
  BOOST_TEST(d.x <= 1e-12);
  BOOST_TEST(d.v <= 1e-10);
  BOOST_TEST(d.rho <= 1e-8);
  BOOST_TEST(d.kinds == 0);
}

BOOST_AUTO_TEST_CASE(periodic_poiseuille_with_a_skin_is_the_run_without_to_round_off) {
  // F = 1e-2 m/s^2: u_max = F H^2 / (8 nu) = 1.25e-3 m/s, so in 0.1 s the
  // midline moves 1.2e-4 m, 0.3 box lengths, against a half skin of 6e-6 m.
  const Runs r = withAndWithoutSkin("poiseuille_2d", "0.1", "0.1", {"--gravity", "1e-2", "0"});
  const Real L = 4e-4;  // the periodic box along x (poiseuille_2d.case)
  std::size_t crossed = 0;
  double dx = 0, dv = 0, drho = 0;
  for (const auto& [id, p] : r.without) {
    const auto& q = r.with.at(id);
    // Positions are wrapped into the box only at a rebuild: compare the
    // nearest images along x.
    const double along = std::abs(p.x[0] - q.x[0]);
    dx = std::max({dx, std::min(along, std::abs(along - L)), std::abs(p.x[1] - q.x[1])});
    for (int k = 0; k < 3; ++k) dv = std::max(dv, std::abs(p.v[k] - q.v[k]));
    drho = std::max(drho, std::abs(p.rho - q.rho));
    crossed += p.x[0] < r.start.at(id).x[0] - 1e-5;  // moving along +x, now behind where it started: it wrapped
  }
  BOOST_TEST_MESSAGE("max |dx| " << dx << " m, |dv| " << dv << " m/s, |drho| " << drho);
  BOOST_TEST(crossed > 0u, "no particle crossed the periodic face");
  BOOST_TEST(dx <= 1e-13);
  BOOST_TEST(dv <= 1e-12);
  BOOST_TEST(drho <= 1e-8);
}

// Two particles A and B, 0.034 apart (outside the list radius R (1 + s) =
// 0.0312, R = 0.026, s = 0.2; half the skin 0.0026): A moving 0.002 keeps
// the list; A and B each moving 0.0045 towards each other (more than half
// the skin, less than all of it) come 0.025 apart, closer than R, and the
// list must be rebuilt to hold them.
BOOST_AUTO_TEST_CASE(a_particle_moving_half_the_skin_rebuilds_the_list) {
  CaseConfig c = test::bareWcsph(2);
  c.h = 0.013;
  c.spacing = 0.01;
  c.k = 200;
  c.blockMin = {0, 0};
  c.blockMax = {0.1, 0.1};
  c.neighbourSkin = 0.2;
  c.given.insert("neighbour_skin");
  Scene<2> s = test::sceneOf<2>(c);
  BOOST_TEST(s.support() == 0.026, tt::tolerance(1e-12));
  auto& P = s.particles();
  const std::int64_t a = P.id[0], b = P.id[1];
  P.x[test::indexOf(s, b)] = Vec<2>(0.5, 0.5);  // away from the block
  P.x[test::indexOf(s, a)] = Vec<2>(0.534, 0.5);
  long builds = s.listBuilds();
  s.prepareList();
  BOOST_TEST(s.listBuilds() == builds + 1);  // they moved far
  builds = s.listBuilds();
  P.x[test::indexOf(s, a)] -= Vec<2>(0.002, 0);
  s.prepareList();
  BOOST_TEST(s.listBuilds() == builds, "a move under half the skin rebuilt the list");
  BOOST_TEST(missingPairs(s) == 0u);
  P.x[test::indexOf(s, a)] -= Vec<2>(0.0025, 0);
  P.x[test::indexOf(s, b)] += Vec<2>(0.0045, 0);
  BOOST_TEST((P.x[test::indexOf(s, a)] - P.x[test::indexOf(s, b)]).norm() < s.support());
  s.prepareList();
  BOOST_TEST(s.listBuilds() == builds + 1, "a move over half the skin kept the list");
  BOOST_TEST(missingPairs(s) == 0u);
}

// The seed scheme's factors are not cut off at the support: it keeps 0.
BOOST_AUTO_TEST_CASE(the_seed_scheme_refuses_a_skin) {
  const auto r = test::runSph({"run", test::caseFile("dam_break_seed"), "--neighbour_skin", "0.1", "--output",
                               (test::scratchDir("skin_seed") / "out").string()});
  BOOST_TEST(r.exitCode == 2);
  BOOST_TEST(r.output.find("neighbour_skin = 0.1: model seed_wcsph takes 0 only") != std::string::npos, r.output);
}

BOOST_AUTO_TEST_SUITE_END()
