// Symplectic (semi-implicit) Euler: v^{n+1} = v^n + a^n dt,
// x^{n+1} = x^n + v^{n+1} dt (rho^{n+1} = rho^n + drho^n dt with continuity
// density). First order, symplectic: energy errors stay bounded.
// Free fall: y_n = y0 - g t_n^2/2 - g t_n dt/2.
#pragma once

#include "sph/integrators/integrator_support.hpp"

namespace sph {

template <int D>
struct SymplecticEuler {
  static constexpr const char* name = "symplectic_euler";
  static constexpr const char* summary = "semi-implicit Euler: symplectic, first order";
  static FieldSet needs(bool) { return 0; }

  template <class Evaluate, class Constrain>
  void advance(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain) const {
    const std::size_t n = P.size(), nFluid = P.fluidCount();
    const bool density = !P.drho.empty();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      if (density) P.rho[i] += dt * P.drho[i];
      if (i >= nFluid) continue;
      P.v[i] += dt * P.a[i];
      P.x[i] += dt * P.driftVelocity(i, P.v[i]);
      constrain(P, i);
    }
    evaluate();
  }

  void finish(Particles<D>&, std::size_t, Real) const {}
};

}  // namespace sph
