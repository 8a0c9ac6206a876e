// Where names become objects: the case's model, kernel, equation of state,
// viscosity, body forces and integrator, built from the method tables of
// methods.hpp (the one place a method is registered). A choice set to "none"
// (or a coefficient of 0) constructs nothing. Call with a validated case
// whose defaults are filled in (a ResolvedCase, from withDefaults). The
// model and the scene are built in src/model_registry.cpp, the one place
// that includes both presets (models/*.hpp) for them.
#pragma once

#include "sph/case_config.hpp"
#include "sph/methods.hpp"
#include "sph/particle_sources.hpp"
#include "sph/scene.hpp"
#include "sph/toy_star.hpp"
#include "sph/wall_particles.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sph {

template <int D>
Kernel<D> makeKernel(const ResolvedCase& c) {
  return methodRow(kernelMethods<D>(), "kernel", c.kernel).make(c);
}

// The kernel probes interpolate with: the case's; the seed model's kernels
// are its own, so there a Wendland C2 with the seed's support h stands in.
template <int D>
Kernel<D> makeProbeKernel(const ResolvedCase& c) {
  if (!c.kernel.empty()) return makeKernel<D>(c);
  return WendlandC2<D>(c.h / 2);
}

// The case's equation of state (src/model_registry.cpp).
EquationOfState makeEos(const ResolvedCase& c);

inline ViscosityChoice makeViscosity(const ResolvedCase& c) {
  return methodRow(viscosityMethods(), "viscosity", c.viscosity).make(c);
}

// lambda of the toy star(s), 0 when the case has none.
inline Real starLambda(const CaseConfig& c) {
  return c.starMass > 0 ? toyStarLambda(c.dimension, c.starMass, c.starRadius, c.k, c.polytropicIndex) : 0;
}

// The paddle's motion (case keys paddle, paddle_amplitude, paddle_period),
// none when the case has none; nFluid: the fluid particles before the walls.
template <int D>
std::optional<SinusoidalWallMotion<D>> makeWallMotion(const ResolvedCase& c, std::size_t nFluid) {
  if (c.paddle <= 0 || !wallParticles(c)) return std::nullopt;
  const auto range = obstacleParticleRange<D>(c, wallLayersUsed(c), static_cast<std::size_t>(c.paddle - 1));
  SinusoidalWallMotion<D> m;
  m.firstId = static_cast<std::int64_t>(nFluid + range.first);
  m.endId = static_cast<std::int64_t>(nFluid + range.second);
  m.amplitude = toVec<D>(c.paddleAmplitude);
  m.period = c.paddlePeriod;
  return m;
}

// The case's model (seed_wcsph, or wcsph composed from its methods);
// wallMotion: the paddle's, which dummy walls read (src/model_registry.cpp).
template <int D>
Model<D> makeModel(const ResolvedCase& c, std::optional<SinusoidalWallMotion<D>> wallMotion = std::nullopt);

// The damped reflecting walls of the case's boundary constraint, if it
// has them (boundaries/reflecting_boundary.hpp), else none.
template <int D>
std::optional<DampedReflectingWalls<D>> makeReflectingWalls(const ResolvedCase& c) {
  const WallConstraint<D> constraint = activeBoundary(c).hooks<D>().constraint(c);
  if (const auto* walls = constraint.reflecting()) return *walls;
  return std::nullopt;
}

// The wall guard (wall_guard key) acts at wall-particle boundaries only.
inline bool wallGuardOn(const ResolvedCase& c) { return wallParticles(c) && c.wallGuard; }

template <int D>
Integrator<D> makeIntegrator(const std::string& name) {
  return methodRow(integratorMethods<D>(), "integrator", name).make(ResolvedCase{});
}

// The scene of a validated case (defaults filled in) from its initial state.
// `startTime`: where the run's clock started (a fixed-dt run is at
// startTime + n dt after step n); by default the time of the particles
// (src/model_registry.cpp).
template <int D>
Scene<D> makeScene(const ResolvedCase& c, InitialState<D> init,
                   Real startTime = std::numeric_limits<Real>::quiet_NaN());

}  // namespace sph
