// A moving paddle (wall_motion.hpp; keys paddle, paddle_amplitude,
// paddle_period): its particles follow d(t) = A sin(2 pi t / T) exactly and
// carry its velocity, the other walls stay put, the water in front of it
// moves with it, and bad paddle keys are refused naming the key.
#include "sph/model_registry.hpp"
#include "refused_naming.hpp"
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <map>
#include <string>

using namespace sph;

namespace {

// A tank 1 m x 0.4 m with water 0.1 m deep and a paddle 4 cm thick at the
// left end.
CaseConfig paddleTank() {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = "wendland_c2";
  c.spacing = 0.01;
  c.h = 0.015;
  c.eos = "tait";
  c.c0 = 10;
  c.density = "continuity";
  c.delta = 0.1;
  c.viscosity = "monaghan";
  c.alpha = 0.02;
  c.beta = 0;
  c.g = 9.81;
  c.walls = true;
  c.boundary = "dummy";
  c.negativePressure = "clamp";
  c.hydrostaticStart = true;
  c.domainMin = {0, 0};
  c.domainMax = {1, 0.4};
  c.obstacleMin = {0.05, 0};
  c.obstacleMax = {0.09, 0.3};
  c.paddle = 1;
  c.paddleAmplitude = {0.02, 0};
  c.paddlePeriod = 4;
  c.blockMin = {0.09, 0};
  c.blockMax = {1, 0.1};
  c.dt = 1e-4;
  return c;
}

const Real kPi = std::acos(Real(-1));

}  // namespace

BOOST_AUTO_TEST_SUITE(wall_motion)

BOOST_AUTO_TEST_CASE(paddle_particles_follow_the_sine_and_the_other_walls_stay) {
  const CaseConfig c = paddleTank();
  Scene<2> s = test::sceneOf<2>(c);
  std::map<std::int64_t, Vec<2>> start;
  const auto& P0 = s.particles();
  for (std::size_t i = P0.fluidCount(); i < P0.size(); ++i) start[P0.id[i]] = P0.x[i];
  const int steps = 500;
  for (int k = 0; k < steps; ++k) BOOST_REQUIRE(!s.step());
  const Real t = s.time(), w = 2 * kPi / c.paddlePeriod;
  BOOST_TEST(std::abs(t - steps * c.dt) < 1e-12);
  const Real d = c.paddleAmplitude[0] * std::sin(w * t), u = c.paddleAmplitude[0] * w * std::cos(w * t);
  const auto& P = s.particles();
  std::size_t moved = 0, fixed = 0;
  for (std::size_t i = P.fluidCount(); i < P.size(); ++i) {
    const Vec<2> x0 = start.at(P.id[i]);
    const bool paddle = x0[0] > 0.05 && x0[0] < 0.09 && x0[1] > 0 && x0[1] < 0.3;
    if (paddle) {
      ++moved;
      BOOST_TEST((P.x[i] - x0 - Vec<2>(d, 0)).norm() < 1e-12);
      BOOST_TEST((P.v[i] - Vec<2>(u, 0)).norm() < 1e-12);
    } else {
      ++fixed;
      BOOST_TEST((P.x[i] - x0).norm() == 0);
      BOOST_TEST(P.v[i].norm() == 0);
    }
  }
  BOOST_TEST(moved == 4u * 30u);  // 4 x 30 particles: the box's lattice, all of it within 3 layers
  BOOST_TEST(fixed > 100u);
}

// Pushing into still water, the water against the paddle moves with it
// (mass conservation at the face: to first order its speed is the
// paddle's). At t = 0.1 s the paddle moves at A w cos(w t) = 0.031 m/s; the
// fluid within 2 dx of its face, averaged, within 25% of that (the SPH
// layer next to a wall lags it by the part of a kernel support the wall
// fills; without the motion it would be 0).
BOOST_AUTO_TEST_CASE(the_water_in_front_of_the_paddle_moves_with_it) {
  const CaseConfig c = paddleTank();
  Scene<2> s = test::sceneOf<2>(c);
  for (int k = 0; k < 1000; ++k) BOOST_REQUIRE(!s.step());
  const Real t = s.time(), w = 2 * kPi / c.paddlePeriod;
  const Real face = 0.09 + c.paddleAmplitude[0] * std::sin(w * t);
  const Real u = c.paddleAmplitude[0] * w * std::cos(w * t);
  const auto& P = s.particles();
  Real sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < P.fluidCount(); ++i)
    if (P.x[i][0] < face + 2 * c.spacing) sum += P.v[i][0], ++n;
  BOOST_REQUIRE(n > 10);
  const Real mean = sum / n;
  BOOST_TEST_MESSAGE("paddle speed " << u << " m/s, water at its face " << mean << " m/s (" << n << " particles)");
  BOOST_TEST(std::abs(mean / u - 1) < 0.25);
}

// Dynamic wall particles enter the viscous term with their own velocity
// (Crespo et al. 2007): with the laplacian viscosity, which reads the
// velocity a wall shows the fluid (vWall), a moving paddle's particles show
// the paddle's, the fixed walls 0. (Nothing wrote it for dynamic walls
// before: the paddle looked still to the viscous term.)
BOOST_AUTO_TEST_CASE(a_dynamic_paddle_shows_the_viscous_term_its_own_velocity) {
  CaseConfig c = paddleTank();
  c.boundary = "dynamic";
  c.viscosity = "laplacian";
  c.mu = 1e-3;
  Scene<2> s = test::sceneOf<2>(c);
  for (int k = 0; k < 200; ++k) BOOST_REQUIRE(!s.step());
  const Real t = s.time(), w = 2 * kPi / c.paddlePeriod;
  const Real u = c.paddleAmplitude[0] * w * std::cos(w * t);
  const auto& P = s.particles();
  BOOST_REQUIRE(P.vWall.size() == P.size());
  std::size_t moving = 0;
  for (std::size_t i = P.fluidCount(); i < P.size(); ++i) {
    BOOST_TEST((P.vWall[i] - P.v[i]).norm() == 0);
    if (P.v[i].norm() > 0) {
      ++moving;
      BOOST_TEST(std::abs(P.vWall[i][0] - u) < 1e-12);
    }
  }
  BOOST_TEST(moving == 4u * 30u);  // the paddle's particles (as in the first test)
}

BOOST_AUTO_TEST_CASE(bad_paddle_keys_are_refused_naming_them) {
  CaseConfig c = paddleTank();
  c.paddle = 2;
  BOOST_TEST(test::refusedNaming(c, "paddle = 2"));
  c = paddleTank();
  c.paddleAmplitude = {0.02};
  BOOST_TEST(test::refusedNaming(c, "paddle_amplitude"));
  c = paddleTank();
  c.paddleAmplitude = {0.06, 0};  // would reach x < 0
  BOOST_TEST(test::refusedNaming(c, "leave the domain"));
}

BOOST_AUTO_TEST_SUITE_END()
