// Leap-frog, kick-drift-kick (Verlet; symplectic, second order):
//
//   v^{n+1/2} = v^n + a^n dt/2
//   x^{n+1}   = x^n + v^{n+1/2} dt
//   rho^{n+1} = rho^n + D(x^{n+1/2}, v^{n+1/2}) dt     (continuity density)
//   v^{n+1}   = v^{n+1/2} + a^{n+1} dt/2,  a^{n+1} = a(x^{n+1}, rho^{n+1})
//
// (positions and velocities for the fluid; density for every particle that
// has one.) With continuity density rho is advanced like a position: its
// rate D (continuity and its diffusion) is a pair loop of its own
// (Model::densityRate), at the half-step velocity and the half-step
// positions, on the neighbour list of x^n. The pair (rho, v) of a sound
// wave is then a staggered Stormer-Verlet pair, stable for omega dt <= 2 as
// tests/reference/acoustic_cfl_limits.csv assumes. (Kicking rho like v with
// the rate of the predicted state, in the one force evaluation, is Heun's
// method for that pair: unstable for every dt, and measured stable only to
// c dt/h = 0.29 on the lattice of validation/stability_atlas.py.)
//
// For a fixed dt this is the seed scheme's leap-frog exactly: its half-step
// start v^{1/2} = v^0 + a^0 dt/2 and v^{n+1/2} = v^{n-1/2} + a^n dt are the
// same numbers, since v^n = v^{n-1/2} + a^n dt/2. Between drift and kick the
// forces at x^{n+1} see the estimate v^{n+1/2} + a^n dt/2 of v^{n+1}, or,
// with forcesSeeHalfStepVelocity (the seed model: its document's leap-frog
// holds only v^{n+1/2}), v^{n+1/2} itself. With constant acceleration it
// reproduces x0 + v0 t + a t^2/2 to round-off. The state between steps is x, v (and rho): a run
// resumed from a snapshot continues bit for bit.
#pragma once

#include "sph/integrators/integrator_support.hpp"

namespace sph {

template <int D>
struct LeapFrog {
  static constexpr const char* name = "leap_frog";
  static constexpr const char* summary = "kick-drift-kick leap-frog: symplectic, second order, one evaluation per step";
  static constexpr AcousticClass kAcousticClass = AcousticClass::kLeapFrog;
  static constexpr const char* kUnstable = nullptr;
  static constexpr Real kViscousFraction = 1;
  static constexpr bool kDensityRateApart = true;
  static constexpr FieldSet finishes() { return fieldBit(kFieldV); }
  static FieldSet needs(bool) { return fieldBit(kFieldVHalf); }

  // The velocity the forces see between drift and kick (set by the Scene
  // from its model): v^{n+1/2} + a^n dt/2, or v^{n+1/2} when true.
  bool forcesSeeHalfStepVelocity = false;

  // Up to the step's last evaluation; finish() completes each particle.
  template <class Evaluate, class Constrain, class DensityRate>
  void advance(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain,
               DensityRate&& densityRate) const {
    // (Read again after every evaluation: on several MPI ranks a rebuild of
    // the neighbour list migrates particles, and the counts change.)
    std::size_t n = P.size(), nFluid = P.fluidCount();
    if (P.drho.empty()) {
#pragma omp parallel for schedule(static) if (nFluid >= kMinParallelSize)
      for (std::size_t i = 0; i < nFluid; ++i) {
        P.vHalf[i] = P.v[i] + (dt / 2) * P.a[i];
        P.x[i] += dt * P.driftVelocity(i, P.vHalf[i]);
        P.v[i] = forcesSeeHalfStepVelocity ? P.vHalf[i] : P.vHalf[i] + (dt / 2) * P.a[i];
        constrain(P, i);
      }
    } else {
      // Kick and half drift; the density rate at (x^{n+1/2}, v^{n+1/2}).
#pragma omp parallel for schedule(static) if (nFluid >= kMinParallelSize)
      for (std::size_t i = 0; i < nFluid; ++i) {
        P.vHalf[i] = P.v[i] + (dt / 2) * P.a[i];
        P.v[i] = P.vHalf[i];
        P.x[i] += (dt / 2) * P.driftVelocity(i, P.vHalf[i]);
      }
      densityRate();
      n = P.size(), nFluid = P.fluidCount();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
      for (std::size_t i = 0; i < n; ++i) {
        P.rho[i] += dt * P.drho[i];
        if (i >= nFluid) continue;
        P.x[i] += (dt / 2) * P.driftVelocity(i, P.vHalf[i]);
        P.v[i] = forcesSeeHalfStepVelocity ? P.vHalf[i] : P.vHalf[i] + (dt / 2) * P.a[i];
        constrain(P, i);
      }
    }
    evaluate();
  }

  void finish(Particles<D>& P, std::size_t i, Real dt) const {
    if (i < P.fluidCount()) P.v[i] = P.vHalf[i] + (dt / 2) * P.a[i];
  }
};

}  // namespace sph
