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

}  // namespace sph::test
