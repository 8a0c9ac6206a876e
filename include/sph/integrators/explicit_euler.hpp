// Explicit (forward) Euler: x^{n+1} = x^n + v^n dt, v^{n+1} = v^n + a^n dt
// (rho^{n+1} = rho^n + drho^n dt with continuity density).
// First order and not symplectic: the energy of an oscillator grows every
// step, and linear stability analysis shows undamped SPH sound waves are
// unstable for any dt. Kept as the known-bad baseline.
// Free fall: y_n = y0 - g t_n^2/2 + g t_n dt/2.
#pragma once

#include "sph/integrators/integrator_support.hpp"

namespace sph {

template <int D>
struct ExplicitEuler {
  static constexpr const char* name = "euler";
  static constexpr const char* summary = "explicit Euler: first order, unstable for undamped waves (the known-bad baseline)";
  // (sph check: unstable at every dt; its acoustic warning uses the leap-frog class's limit)
  static constexpr AcousticClass kAcousticClass = AcousticClass::kLeapFrog;
  static constexpr const char* kUnstable = "(explicit Euler) gains energy every step whatever dt";
  static constexpr Real kViscousFraction = 1;
  static constexpr bool kDensityRateApart = false;  // the force evaluation gives d rho/dt
  static constexpr FieldSet finishes() { return 0; }
  static FieldSet needs(bool) { return 0; }

  template <class Evaluate, class Constrain, class DensityRate>
  void advance(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain, DensityRate&&) const {
    const std::size_t n = P.size(), nFluid = P.fluidCount();
    const bool density = !P.drho.empty();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      if (density) P.rho[i] += dt * P.drho[i];
      if (i >= nFluid) continue;
      P.x[i] += dt * P.driftVelocity(i, P.v[i]);
      P.v[i] += dt * P.a[i];
      constrain(P, i);
    }
    evaluate();
  }

  void finish(Particles<D>&, std::size_t, Real) const {}
};

}  // namespace sph
