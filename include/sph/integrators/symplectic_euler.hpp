// Symplectic (semi-implicit) Euler: v^{n+1} = v^n + a^n dt,
// x^{n+1} = x^n + v^{n+1} dt, and with continuity density
// rho^{n+1} = rho^n + D(x^n, v^{n+1}) dt: rho is advanced like a position,
// with a density rate of its own at the new velocity (Model::densityRate,
// one more pair loop), so that the pair (rho, v) of a sound wave is
// symplectic too, stable for omega dt <= 2 (with the rate of the old
// velocity it is explicit Euler for that pair, unstable for every dt;
// measured stable only to c dt/h = 0.07). First order, symplectic: energy
// errors stay bounded. Free fall: y_n = y0 - g t_n^2/2 - g t_n dt/2.
#pragma once

#include "sph/integrators/integrator_support.hpp"

namespace sph {

template <int D>
struct SymplecticEuler {
  static constexpr const char* name = "symplectic_euler";
  static constexpr const char* summary = "semi-implicit Euler: symplectic, first order";
  static constexpr AcousticClass kAcousticClass = AcousticClass::kLeapFrog;
  static constexpr const char* kUnstable = nullptr;
  static constexpr Real kViscousFraction = 1;
  static constexpr bool kDensityRateApart = true;
  static constexpr FieldSet finishes() { return 0; }
  static FieldSet needs(bool) { return 0; }

  template <class Evaluate, class Constrain, class DensityRate>
  void advance(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain,
               DensityRate&& densityRate) const {
    // (Read again after every evaluation: on several MPI ranks a rebuild of
    // the neighbour list migrates particles, and the counts change.)
    std::size_t n = P.size(), nFluid = P.fluidCount();
    const bool density = !P.drho.empty();
    if (density) {
#pragma omp parallel for schedule(static) if (nFluid >= kMinParallelSize)
      for (std::size_t i = 0; i < nFluid; ++i) P.v[i] += dt * P.a[i];
      densityRate();
      n = P.size(), nFluid = P.fluidCount();
    }
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      if (density) P.rho[i] += dt * P.drho[i];
      if (i >= nFluid) continue;
      if (!density) P.v[i] += dt * P.a[i];
      P.x[i] += dt * P.driftVelocity(i, P.v[i]);
      constrain(P, i);
    }
    evaluate();
  }

  void finish(Particles<D>&, std::size_t, Real) const {}
};

}  // namespace sph
