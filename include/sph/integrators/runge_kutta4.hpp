// Classical fourth-order Runge-Kutta for dx/dt = v (+ XSPH), dv/dt = a(x, v)
// (and d rho/dt = drho with continuity density):
//
//   k1 = f(y^n), k2 = f(y^n + dt/2 k1), k3 = f(y^n + dt/2 k2), k4 = f(y^n + dt k3)
//   y^{n+1} = y^n + dt/6 (k1 + 2 k2 + 2 k3 + k4)
//
// Four force evaluations per step (each re-sorts and rebuilds the neighbour
// list, carrying the stage fields along). Not symplectic: the energy of an
// oscillator drifts slowly, at O(dt^4). Walls act once, after the full step.
#pragma once

#include "sph/integrators/integrator_support.hpp"

namespace sph {

template <int D>
struct RungeKutta4 {
  static constexpr const char* name = "rk4";
  static constexpr const char* summary = "classical Runge-Kutta: fourth order, four evaluations per step";
  static constexpr AcousticClass kAcousticClass = AcousticClass::kRungeKutta4;
  static constexpr const char* kUnstable = nullptr;
  static constexpr Real kViscousFraction = 1;
  static constexpr bool kDensityRateApart = false;  // the force evaluation gives d rho/dt
  static constexpr FieldSet finishes() { return 0; }
  static FieldSet needs(bool density) {
    return fieldBit(kFieldX0) | fieldBit(kFieldV0) | fieldBit(kFieldDx) | fieldBit(kFieldDv) |
           (density ? fieldBit(kFieldRho0) | fieldBit(kFieldDrhoSum) : 0);
  }

  template <class Evaluate, class Constrain, class DensityRate>
  void advance(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain, DensityRate&&) const {
    // (Read again after every evaluation: on several MPI ranks a rebuild of
    // the neighbour list migrates particles, and the counts change.)
    std::size_t n = P.size(), nFluid = P.fluidCount();
    const bool density = !P.drho.empty();
    auto drift = [&](std::size_t i) { return P.driftVelocity(i, P.v[i]); };
    // k1 from the current state; then stages at dt/2, dt/2, dt.
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      if (density) {
        P.rho0[i] = P.rho[i];
        P.drhoSum[i] = P.drho[i];
      }
      if (i >= nFluid) continue;
      P.x0[i] = P.x[i];
      P.v0[i] = P.v[i];
      P.dx[i] = drift(i);
      P.dv[i] = P.a[i];
    }
    const Real stage[3] = {dt / 2, dt / 2, dt};
    const Real weight[3] = {2, 2, 1};
    for (int s = 0; s < 3; ++s) {
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
      for (std::size_t i = 0; i < n; ++i) {
        if (density) P.rho[i] = P.rho0[i] + stage[s] * P.drho[i];
        if (i >= nFluid) continue;
        const Vec<D> kx = drift(i), kv = P.a[i];
        P.x[i] = P.x0[i] + stage[s] * kx;
        P.v[i] = P.v0[i] + stage[s] * kv;
      }
      evaluate();
      n = P.size(), nFluid = P.fluidCount();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
      for (std::size_t i = 0; i < n; ++i) {
        if (density) P.drhoSum[i] += weight[s] * P.drho[i];
        if (i >= nFluid) continue;
        P.dx[i] += weight[s] * drift(i);
        P.dv[i] += weight[s] * P.a[i];
      }
    }
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      if (density) P.rho[i] = P.rho0[i] + (dt / 6) * P.drhoSum[i];
      if (i >= nFluid) continue;
      P.x[i] = P.x0[i] + (dt / 6) * P.dx[i];
      P.v[i] = P.v0[i] + (dt / 6) * P.dv[i];
      constrain(P, i);
    }
    evaluate();
  }

  void finish(Particles<D>&, std::size_t, Real) const {}
};

}  // namespace sph
