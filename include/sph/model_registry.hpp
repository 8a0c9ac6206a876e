// Where names become objects: the case's model, kernel, equation of state,
// viscosity, body forces and integrator, all registered here and nowhere
// else. A choice set to "none" (or a coefficient of 0) constructs nothing.
// Call with a validated case whose defaults are filled in (withDefaults).
#pragma once

#include "sph/case_config.hpp"
#include "sph/particle_sources.hpp"
#include "sph/scene.hpp"
#include "sph/toy_star.hpp"

#include <stdexcept>

namespace sph {

template <int D>
Kernel<D> makeKernel(const std::string& name, Real h) {
  if (name == "cubic_spline") return CubicSpline<D>(h);
  if (name == "wendland_c2") return WendlandC2<D>(h);
  if (name == "gaussian") return Gaussian<D>(h);
  if (name == "muller") return Muller<D>(h);
  throw CaseError("kernel = \"" + name + "\" is not known");
}

inline EquationOfState makeEos(const CaseConfig& c) {
  if (c.eos == "linear") return LinearEos{c.k, c.rho0};
  if (c.eos == "linear_clamped") return ClampedLinearEos{c.k, c.rho0};
  if (c.eos == "tait") return TaitEos{c.rho0, c.c0, c.gamma};
  if (c.eos == "polytropic") return PolytropicEos{c.k, c.polytropicIndex};
  throw CaseError("eos = \"" + c.eos + "\" is not known");
}

inline ViscosityChoice makeViscosity(const CaseConfig& c) {
  if (c.viscosity == "laplacian" && c.mu > 0) return LaplacianViscosityChoice{c.mu};
  if (c.viscosity == "monaghan" && (c.alpha > 0 || c.beta > 0)) return MonaghanViscosityChoice{c.alpha, c.beta};
  return NoViscosity{};
}

// lambda of the toy star(s), 0 when the case has none.
inline Real starLambda(const CaseConfig& c) {
  return c.starMass > 0 ? toyStarLambda(c.dimension, c.starMass, c.starRadius, c.k, c.polytropicIndex) : 0;
}

template <int D>
Model<D> makeModel(const CaseConfig& c) {
  if (c.model == "seed_wcsph") return makeSeedWcsph<D>(SeedWcsphParameters{c.h, c.k, c.rho0, c.mu, c.g});
  WcsphSpec<D> spec{makeKernel<D>(c.kernel, c.h), makeEos(c), makeViscosity(c), c.rho0, {}, c.xsph};
  if (c.g != 0) spec.bodies.gravity = UniformGravity<D>{c.g};
  if (c.starMass > 0) spec.bodies.star = StarAttraction<D>{starLambda(c)};
  if (c.damping > 0) spec.bodies.damping = LinearDamping<D>{c.damping};
  return makeWcsph<D>(spec);
}

template <int D>
Integrator<D> makeIntegrator(const std::string& name) {
  if (name == "leap_frog") return LeapFrog<D>{};
  if (name == "symplectic_euler") return SymplecticEuler<D>{};
  if (name == "rk4") return RungeKutta4<D>{};
  if (name == "euler") return ExplicitEuler<D>{};
  throw CaseError("integrator = \"" + name + "\" is not known");
}

// The scene of a validated case (defaults filled in) from its initial state.
template <int D>
Scene<D> makeScene(const CaseConfig& c, InitialState<D> init) {
  const Vec<D> lo = toVec<D>(c.domainMin), hi = toVec<D>(c.domainMax);
  std::optional<DampedReflectingWalls<D>> walls;
  if (c.walls)
    walls = DampedReflectingWalls<D>{lo, hi, c.h, c.restitution,
                                     c.model == "seed_wcsph" ? ReflectionRule::kSeed : ReflectionRule::kApproaching};
  return Scene<D>(std::move(init.particles), makeModel<D>(c), walls, StateCheck<D>{lo, hi},
                  TimeStepControl{c.dt, c.cfl, init.startTime + c.endTime}, init.startTime,
                  makeIntegrator<D>(c.integrator));
}

}  // namespace sph
