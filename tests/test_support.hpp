// Helpers shared by the test suites: small scenes built in code, and (from
// cli_support.hpp) running the real `sph` executable and scratch folders.
#pragma once

#include "cli_support.hpp"
#include "sph/models/seed_wcsph.hpp"
#include "sph/scene.hpp"

#include <boost/test/unit_test.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace sph::test {

// A scene from explicit positions (and velocities), with the seed model.
// Masses are scaled to rho0 unless `mass` > 0 is given. Walls on the unit
// box unless `walls` is false (then the domain is [-10, 10]^D).
template <int D>
Scene<D> makeScene(const std::vector<Vec<D>>& x, const std::vector<Vec<D>>& v,
                   SeedWcsphParameters prm, bool walls, Real dt, Real mass = 0,
                   Real restitution = 0.5) {
  Particles<D> P;
  P.x = x;
  P.v = v.empty() ? std::vector<Vec<D>>(x.size(), Vec<D>::Zero()) : v;
  P.m.assign(x.size(), mass);
  for (std::size_t i = 0; i < x.size(); ++i) P.id.push_back(static_cast<std::int64_t>(i));
  P.resize(x.size());
  const Vec<D> lo = Vec<D>::Constant(walls ? 0 : -10), hi = Vec<D>::Constant(walls ? 1 : 10);
  std::optional<DampedReflectingWalls<D>> w;
  if (walls) w = DampedReflectingWalls<D>{lo, hi, prm.h, restitution, ReflectionRule::kSeed};
  Scene<D> scene(std::move(P), makeSeedWcsph<D>(prm), w, StateCheck<D>{lo, hi}, TimeStepControl{dt});
  BOOST_REQUIRE(!scene.initialise(mass <= 0));
  return scene;
}

// Index (in the scene's current, sorted order) of the particle with this id.
template <int D>
std::size_t indexOf(const Scene<D>& s, std::int64_t id) {
  const auto& ids = s.particles().id;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] == id) return i;
  BOOST_FAIL("no particle with id " << id);
  return 0;
}

// Total momentum sum m v of the particles, and sum m |v| (the scale its
// round-off is measured against).
template <int D>
std::pair<Vec<D>, Real> momentum(const Particles<D>& P) {
  Vec<D> p = Vec<D>::Zero();
  Real scale = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    p += P.m[i] * P.v[i];
    scale += P.m[i] * P.v[i].norm();
  }
  return {p, scale};
}

}  // namespace sph::test

#include "sph/model_registry.hpp"

namespace sph::test {

// A wcsph case with nothing switched on: no viscosity, no gravity, no walls,
// in a large domain. Tests switch on what they need.
inline CaseConfig bareWcsph(int dimension) {
  CaseConfig c;
  c.model = "wcsph";
  c.dimension = dimension;
  c.viscosity = "none";
  c.g = 0;
  c.walls = false;
  c.domainMin.assign(static_cast<std::size_t>(dimension), -100);
  c.domainMax.assign(static_cast<std::size_t>(dimension), 100);
  return c;
}

// A water column 0.1 x 0.2 m in a tank 0.4 x 0.3 m (2D, dx 0.01, Wendland
// C2 with h = 1.5 dx, Tait c0 = 20, continuity with delta-SPH 0.1,
// Monaghan 0.02, gravity, leap-frog, dt 1e-4) with wall particles of
// `boundary` and a neighbour-list skin `skin`: the water physics of the
// dam break on a few hundred particles. In 3D the same column and tank
// 0.04 m deep (y; gravity along -z).
inline CaseConfig waterColumn(const std::string& boundary, Real skin, int dimension = 2) {
  CaseConfig c = bareWcsph(dimension);
  c.kernel = "wendland_c2", c.spacing = 0.01, c.h = 0.015;
  c.eos = "tait", c.c0 = 20, c.rho0 = 1000, c.g = 9.81;
  c.density = "continuity", c.delta = 0.1;
  c.viscosity = "monaghan", c.alpha = 0.02, c.beta = 0;
  c.walls = true, c.boundary = boundary;
  if (dimension == 2)
    c.domainMin = {0, 0}, c.domainMax = {0.4, 0.3}, c.blockMin = {0, 0}, c.blockMax = {0.1, 0.2};
  else
    c.domainMin = {0, 0, 0}, c.domainMax = {0.4, 0.04, 0.3}, c.blockMin = {0, 0, 0}, c.blockMax = {0.1, 0.04, 0.2};
  c.dt = 1e-4, c.neighbourSkin = skin;
  return c;
}

// The scene of a case, built and initialised as `sph run` does.
template <int D>
Scene<D> sceneOf(const CaseConfig& given) {
  validateCase(given);
  const ResolvedCase c = withDefaults(given);
  InitialState<D> init = buildInitialState<D>(c);
  const bool scale = !init.massesGiven;
  Scene<D> s = makeScene<D>(c, std::move(init));
  BOOST_REQUIRE(!s.initialise(scale));
  return s;
}

// The scene of a case after `steps` steps (none may fail).
template <int D>
Scene<D> settled(const CaseConfig& c, int steps) {
  Scene<D> s = sceneOf<D>(c);
  for (int n = 0; n < steps; ++n) BOOST_REQUIRE(!s.step());
  return s;
}

}  // namespace sph::test
