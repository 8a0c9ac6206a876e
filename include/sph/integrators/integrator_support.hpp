// What the integrators share. An integrator advances the state variables
// x <- v (plus the XSPH correction), v <- a for the fluid particles, and
// rho <- drho for every particle that carries a density rate (continuity
// density; walls too with dynamic boundary particles). Walls never move.
//
//   advance(P, dt, evaluate, constrain, densityRate)  everything up to the
//       step's last evaluation; constrain(P, i) applies the walls to
//       particle i right after its position update; densityRate() fills
//       drho at the current x and v (for kDensityRateApart integrators,
//       whose force evaluations then leave drho alone);
//   finish(P, i, dt)  completes particle i after that evaluation. The scene
//       fuses it with the state check and the time-step reductions, so a
//       step has few parallel regions.
#pragma once

#include "sph/particles.hpp"

namespace sph {

// Integrators whose acoustic stability limits are alike: each kernel
// declares its measured limit c0 dt / h per class (methods.hpp), each
// integrator its class (kAcousticClass).
enum class AcousticClass { kLeapFrog, kRungeKutta4, kTwoStepLeapFrog };
constexpr int kAcousticClasses = 3;

// A constraint that does nothing.
struct NoConstraint {
  template <int D>
  void operator()(Particles<D>&, std::size_t) const {}
};

}  // namespace sph
