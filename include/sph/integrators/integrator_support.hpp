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
//
// What an integrator touches is declared, so that the scene refreshes the
// ghosts and MPI halos of those fields only (scene.hpp):
//   advancedState(density)  the state every integrator advances: x and v
//       of the fluid, rho of every particle when it carries a density rate
//       (continuity density). Passes read no other field at a neighbour
//       before they write it, so these are all a neighbour walk after an
//       advance needs refreshed (test periodic/ghosts_hold_their_sources_
//       fields_after_every_step);
//   needs(density)  the integrator's own fields, carried between its
//       stages or from step to step (allocated by the scene);
//   finishes()  what finish() writes after the step's last evaluation.
// (test integrators/integrators_write_only_what_they_declare checks that
// each writes nothing else.)
#pragma once

#include "sph/particles.hpp"

namespace sph {

// Integrators whose acoustic stability limits are alike: each kernel
// declares its measured limit c0 dt / h per class (methods.hpp), each
// integrator its class (kAcousticClass).
enum class AcousticClass { kLeapFrog, kRungeKutta4, kTwoStepLeapFrog };
constexpr int kAcousticClasses = 3;

constexpr FieldSet advancedState(bool density) {
  return fieldBits(kFieldX, kFieldV) | (density ? fieldBit(kFieldRho) : FieldSet(0));
}

// A constraint that does nothing.
struct NoConstraint {
  template <int D>
  void operator()(Particles<D>&, std::size_t) const {}
};

}  // namespace sph
