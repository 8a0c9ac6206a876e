// Symplectic (semi-implicit) Euler: v^{n+1} = v^n + a^n dt,
// x^{n+1} = x^n + v^{n+1} dt. First order, symplectic: energy errors stay
// bounded. Free fall: y_n = y0 - g t_n^2/2 - g t_n dt/2.
#pragma once

#include "sph/particles.hpp"

namespace sph {

template <int D>
struct SymplecticEuler {
  static constexpr const char* name = "symplectic_euler";
  static FieldNeeds needs() { return {}; }

  template <class Evaluate, class Constrain>
  void step(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain) const {
    const std::size_t n = P.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      P.v[i] += dt * P.a[i];
      P.x[i] += dt * P.driftVelocity(i, P.v[i]);
    }
    constrain();
    evaluate();
  }
};

}  // namespace sph
