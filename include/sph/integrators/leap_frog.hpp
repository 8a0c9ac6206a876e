// Leap-frog, kick-drift-kick (Verlet; symplectic, second order):
//
//   v^{n+1/2} = v^n + a^n dt/2                rho^{n+1/2} = rho^n + drho^n dt/2
//   x^{n+1}   = x^n + v^{n+1/2} dt
//   v^{n+1}   = v^{n+1/2} + a^{n+1} dt/2      rho^{n+1} = rho^{n+1/2} + drho^{n+1} dt/2
//
// (density only when it is a state variable, for every particle that has
// one; positions and velocities for the fluid.) For a fixed dt this is the
// seed scheme's leap-frog exactly: its half-step start v^{1/2} = v^0 + a^0
// dt/2 and v^{n+1/2} = v^{n-1/2} + a^n dt are the same numbers, since v^n =
// v^{n-1/2} + a^n dt/2. Between drift and kick the forces at x^{n+1} see the
// estimates v^{n+1/2} + a^n dt/2 and rho^{n+1/2} + drho^n dt/2 (the seed's
// choice for viscosity). With constant acceleration it reproduces
// x0 + v0 t + a t^2/2 to round-off. The state between steps is x, v (and
// rho): a run resumed from a snapshot continues bit for bit.
#pragma once

#include "sph/integrators/integrator_support.hpp"

namespace sph {

template <int D>
struct LeapFrog {
  static constexpr const char* name = "leap_frog";
  static constexpr const char* summary = "kick-drift-kick leap-frog: symplectic, second order, one evaluation per step";
  static FieldSet needs(bool density) {
    return fieldBit(kFieldVHalf) | (density ? fieldBit(kFieldRhoHalf) : 0);
  }

  // Up to the step's last evaluation; finish() completes each particle.
  template <class Evaluate, class Constrain>
  void advance(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain) const {
    const std::size_t n = P.size(), nFluid = P.fluidCount();
    const bool density = !P.drho.empty();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      if (density) {
        P.rhoHalf[i] = P.rho[i] + (dt / 2) * P.drho[i];
        P.rho[i] = P.rhoHalf[i] + (dt / 2) * P.drho[i];
      }
      if (i >= nFluid) continue;
      P.vHalf[i] = P.v[i] + (dt / 2) * P.a[i];
      P.x[i] += dt * P.driftVelocity(i, P.vHalf[i]);
      P.v[i] = P.vHalf[i] + (dt / 2) * P.a[i];
      constrain(P, i);
    }
    evaluate();
  }

  void finish(Particles<D>& P, std::size_t i, Real dt) const {
    if (!P.drho.empty()) P.rho[i] = P.rhoHalf[i] + (dt / 2) * P.drho[i];
    if (i < P.fluidCount()) P.v[i] = P.vHalf[i] + (dt / 2) * P.a[i];
  }
};

}  // namespace sph
