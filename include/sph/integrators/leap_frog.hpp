// Leap-frog, kick-drift-kick (Verlet; symplectic, second order):
//
//   v^{n+1/2} = v^n + a^n dt/2
//   x^{n+1}   = x^n + v^{n+1/2} dt
//   v^{n+1}   = v^{n+1/2} + a^{n+1} dt/2
//
// For a fixed dt this is the seed scheme's leap-frog exactly: its
// half-step start v^{1/2} = v^0 + a^0 dt/2 and v^{n+1/2} = v^{n-1/2} + a^n dt
// are the same numbers, since v^n = v^{n-1/2} + a^n dt/2. Between drift and
// kick the forces at x^{n+1} see the velocity estimate v^{n+1/2} + a^n dt/2
// (the seed's choice for viscosity). With constant acceleration it reproduces
// x0 + v0 t + a t^2/2 to round-off.
#pragma once

#include "sph/particles.hpp"

namespace sph {

template <int D>
struct LeapFrog {
  static constexpr const char* name = "leap_frog";
  static FieldNeeds needs() {
    FieldNeeds f;
    f.halfStepVelocity = true;
    return f;
  }

  // evaluate(): rho, p, a (and XSPH) at the current x, v; constrain(): walls.
  template <class Evaluate, class Constrain>
  void step(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain) const {
    const std::size_t n = P.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      P.vHalf[i] = P.v[i] + (dt / 2) * P.a[i];
      P.x[i] += dt * P.driftVelocity(i, P.vHalf[i]);
      P.v[i] = P.vHalf[i] + (dt / 2) * P.a[i];
    }
    constrain();
    evaluate();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) P.v[i] = P.vHalf[i] + (dt / 2) * P.a[i];
  }
};

}  // namespace sph
