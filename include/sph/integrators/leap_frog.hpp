// Leap-frog time integration as the seed scheme defines it:
//
//   first step:  v^{1/2}   = v^0 + a^0 dt/2
//   then:        v^{n+1/2} = v^{n-1/2} + a^n dt
//   always:      x^{n+1}   = x^n + v^{n+1/2} dt
//
// split in two calls around the force evaluation: kickDrift() advances the
// half-step velocity and the position; closingKick() then sets the
// integer-time velocity v^{n+1} = v^{n+1/2} + a^{n+1} dt/2, which is what the
// viscosity term of the next step, the output and the energy see. With a
// constant acceleration this reproduces x0 + v0 t + a t^2/2 to round-off.
// Before the first force evaluation v^0 is the initial velocity.
#pragma once

#include "sph/particles.hpp"

namespace sph {

template <int D>
struct LeapFrog {
  bool started = false;

  void kickDrift(Particles<D>& P, Real dt) {
    const std::size_t n = P.size();
    const Real kick = started ? dt : dt / 2;
    const bool fromV = !started;
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      P.vHalf[i] = (fromV ? P.v[i] : P.vHalf[i]) + kick * P.a[i];
      P.x[i] += dt * P.vHalf[i];
      // Until the forces at x^{n+1} are known, viscosity sees this estimate.
      P.v[i] = P.vHalf[i] + (dt / 2) * P.a[i];
    }
    started = true;
  }

  void closingKick(Particles<D>& P, Real dt) const {
    const std::size_t n = P.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) P.v[i] = P.vHalf[i] + (dt / 2) * P.a[i];
  }
};

}  // namespace sph
