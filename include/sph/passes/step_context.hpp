// What every pass of a model is told about the step it works in.
#pragma once

#include "sph/types.hpp"

namespace sph {

// What the kernel corrections did, summed over a scene's evaluations (the
// run summary prints them): particle-evaluations of the CSPM correction and
// how many fell back to the uncorrected gradient; density re-initialisations
// (steps), the particles re-initialised and how many of those MLS left to
// Shepard.
struct CorrectionCounts {
  long cspmParticles = 0, cspmFallbacks = 0;
  long reinitSteps = 0, reinitParticles = 0, mlsFallbacks = 0;
};

struct StepContext {
  long step = 0;   // index of the step being computed (0: the initial state)
  Real time = 0;   // simulated time of the state being evaluated [s]
  Real dt = 0;     // the step's dt [s] (0 before the first step)
  Real start = 0;  // simulated time at the step's start [s] (time - dt, without its round-off)
  // The integrator advances rho with a density rate of its own
  // (Model::densityRate, the density-rate pass of density_rate.hpp;
  // leap-frog and symplectic Euler with continuity density): the force
  // pass leaves d rho/dt alone.
  bool densityRateApart = false;
  // The last evaluation left particle shifting's sums at the current state
  // in the particles (shiftSum, shiftGrad; terms/shifting_sums.hpp).
  bool shiftSumsGiven = false;
  CorrectionCounts* counts = nullptr;  // where passes add their counts (the model's; none: not counted)
};

}  // namespace sph
