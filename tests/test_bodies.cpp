// Scenes of several bodies: two blocks and two discs in one case, each with
// its own velocity and its own hydrostatic start (the pressure at the foot of
// a column is rho0 g times that column's height, not the tallest one's);
// overlapping fluid bodies, and a fluid body in a solid one, are refused
// naming both; list sizes are checked.
#include "test_support.hpp"

#include <functional>

using namespace sph;
namespace tt = boost::test_tools;

namespace {

CaseConfig scene() {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = "wendland_c2";
  c.eos = "tait";
  c.c0 = 40;
  c.h = 0.015;
  c.spacing = 0.01;
  c.g = 9.81;
  c.walls = true;
  c.boundary = "dummy";
  c.density = "continuity";
  c.hydrostaticStart = true;
  c.domainMin = {0, 0};
  c.domainMax = {2, 1};
  c.blockMin = {0, 0, 1.6, 0};
  c.blockMax = {0.3, 0.6, 2, 0.3};
  c.blockVelocity = {0, 0, -1, 0};
  c.discCenter = {1.0, 0.5, 1.0, 0.8};
  c.discRadius = {0.1, 0.05};
  c.discVelocity = {0, -1, 0.5, 0};
  return c;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(bodies)

BOOST_AUTO_TEST_CASE(each_body_has_its_particles_velocity_and_hydrostatic_start) {
  Scene<2> s = test::sceneOf<2>(scene());
  const auto& P = s.particles();
  std::size_t left = 0, right = 0, big = 0, small = 0;
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    const Vec<2> x = P.x[i], v = P.v[i];
    if (x[0] < 0.3) {
      ++left;
      BOOST_TEST(v.norm() == 0.0);
    } else if (x[0] > 1.6) {
      ++right;
      BOOST_TEST(v[0] == -1.0);
    } else if (x[1] > 0.7) {
      ++small;
      BOOST_TEST(v[0] == 0.5);
    } else {
      ++big;
      BOOST_TEST(v[1] == -1.0);
    }
  }
  BOOST_TEST(left == 30u * 60u);
  BOOST_TEST(right == 40u * 30u);
  BOOST_TEST(big > 300u);  // pi 10^2 = 314 lattice points
  BOOST_TEST(small > 70u);
  // Hydrostatic start per body: the lowest particle of each column carries
  // p = rho0 g (H_body - y) (from the Tait inverse; within 0.1%).
  auto footPressure = [&](Real xLo, Real xHi) {
    Real yMin = 1e9, p = 0;
    for (std::size_t i = 0; i < P.fluidCount(); ++i)
      if (P.x[i][0] > xLo && P.x[i][0] < xHi && P.x[i][1] < yMin) yMin = P.x[i][1], p = P.p[i];
    return std::pair{yMin, p};
  };
  const auto [yl, pl] = footPressure(0.1, 0.11);
  const auto [yr, pr] = footPressure(1.8, 1.81);
  BOOST_TEST(pl == 1000 * 9.81 * (0.6 - yl), tt::tolerance(1e-3));
  BOOST_TEST(pr == 1000 * 9.81 * (0.3 - yr), tt::tolerance(1e-3));
}

BOOST_AUTO_TEST_CASE(overlaps_and_sizes_are_refused_naming_the_bodies) {
  const std::vector<std::pair<std::function<void(CaseConfig&)>, std::string>> bad{
      {[](CaseConfig& c) { c.discCenter = {0.2, 0.5, 1.0, 0.8}; }, "the fluid bodies block 1 and disc 1 overlap"},
      {[](CaseConfig& c) { c.blockMin = {0, 0, 0.2, 0}; }, "the fluid bodies block 1 and block 2 overlap"},
      {[](CaseConfig& c) { c.discCenter = {1.0, 0.5, 1.0, 0.62}; }, "the fluid bodies disc 1 and disc 2 overlap"},
      {[](CaseConfig& c) { c.obstacleMin = {0.9, 0.3}, c.obstacleMax = {1.1, 0.45}; },
       "the fluid body disc 1 overlaps the solid obstacle 1"},
      {[](CaseConfig& c) { c.discRadius = {0.1}; }, "2 centres and 1 radii given"},
      {[](CaseConfig& c) { c.blockVelocity = {1, 0}; }, "block_velocity has 2 values: it needs 2 per block (4)"},
      {[](CaseConfig& c) { c.blockMax = {0.3, 0.6}; }, "block_min and block_max go together"},
  };
  for (const auto& [change, message] : bad) {
    CaseConfig c = scene();
    change(c);
    BOOST_TEST_CONTEXT(message) {
      try {
        validateCase(c);
        BOOST_TEST(false, "accepted");
      } catch (const CaseError& e) {
        BOOST_TEST(std::string(e.what()).find(message) != std::string::npos, e.what());
      }
    }
  }
  // Two blocks side by side only touch: allowed.
  CaseConfig touching = scene();
  touching.blockMin = {0, 0, 0.3, 0};
  touching.blockMax = {0.3, 0.6, 0.6, 0.3};
  BOOST_CHECK_NO_THROW(validateCase(touching));
}

BOOST_AUTO_TEST_SUITE_END()
