// Two-step leap-frog with a Robert-Asselin filter: ONE neighbour walk per
// step (forces and d rho/dt from the same pair loop), at half the acoustic
// limit of leap-frog.
//
//   v^{n+1}   = vbar^{n-1} + 2 dt a^n              a^n, D^n: one walk at
//   rho^{n+1} = rhobar^{n-1} + 2 dt D^n            (x^n, v^n, rho^n)
//   x^{n+1}   = x^n + dt v^n + dt^2/2 a^n          (+ XSPH: dt vXsph^n)
//   vbar^n    = v^n + nu (vbar^{n-1} - 2 v^n + v^{n+1}),  likewise rhobar^n
//
// with nu = kFilter = 0.05. This is DualSPHysics' "Verlet" scheme (Crespo
// et al. 2015, Comput. Phys. Commun. 187, eqs. 17-19: v^{n+1} = v^{n-1} +
// 2 dt F^n, the same for rho, the same position update, also with 2 dt_n
// when dt varies), with the Robert (1966) / Asselin (1972) time filter in
// place of its explicit Euler step every 40 steps. The first step (and a
// run resumed from its t = 0 snapshot) is that Euler step: v^1 = v^0 +
// dt a^0, rho^1 = rho^0 + dt D^0. vbar and rhobar are state (snapshot
// arrays velocity_previous, density_previous): a resumed run continues bit
// for bit.
//
// Linear stability of the acoustic mode. On a lattice at rest (p0 = 0)
// positions enter the continuity and pressure sums only at second order,
// so a plane wave of the density and velocity perturbations is the
// oscillator q' = -omega u (continuity), u' = omega q (pressure), with
// omega = c |G(k)| (tests/reference/acoustic_cfl_limits.csv), z = omega dt.
// Leap-frog's staggered pair is Stormer-Verlet: D at v^{n+1/2}, then a at
// rho^{n+1}; each rate depends on the other's latest value, so the two
// pair loops are sequential (two walks) and the step map is of degree 2 in
// z: stable for z <= 2 (c dt/h = 1.81 Wendland C2, 1.87 cubic spline at
// h/dx 1.3). A scheme with one walk per step evaluates both rates from
// values known before the walk, so its N-step map is a polynomial of
// degree N in z, equal to I + N z J + O(z^2) by consistency (J = [[0,-1],
// [1,0]]); if it stays bounded by K on |z| <= Z, Bernstein's inequality
// gives N <= N K / Z, so Z <= K: about 1, half of leap-frog's 2, for every
// one-walk formulation (DualSPHysics' symplectic scheme, which reaches 2,
// walks twice per step). Checked numerically: the predictor-corrector with
// the last walk's rates (position Verlet with lagged rates) is unstable
// from z = 0.007; leap-frog with rho kicked by the force walk's rate at the
// previous or extrapolated velocity from z = 0 to 0.47; a random search
// over 10-parameter two-level one-walk schemes found at most 0.78; the
// two-step leap-frog above reaches z = 1 exactly (roots e^{i theta},
// -e^{-i theta}, on the unit circle for z <= 1). Its parasitic root
// -e^{-i theta} is what DualSPHysics' Euler step every 40 steps resets:
// that step amplifies by sqrt(1 + z^2), a growth of 3e-3 per step at
// z = 0.5 and 6e-3 at 0.8 without viscosity. The filter instead damps the
// parasitic root by about 2 nu per step and the physical one by
// nu z^2 / (2 (1 - nu)) per step to leading order, and stays stable to z = 0.952 for nu = 0.05
// (1.0 - nu to first order): c dt/h <= 0.86 (Wendland C2), 0.89 (cubic
// spline) at h/dx 1.3, measured with validation/stability_atlas.py in
// docs/methods/integrators.md. Second order in phase; the filter adds an
// amplitude error O(nu dt) at the lattice frequencies. It amplifies
// diffusion: on the negative real axis (a viscous term) the filtered roots
// leave the unit circle at z = -2 nu / (1 + nu) = -0.095, against -2 for
// explicit Euler, so viscosity is stable only to about 1/20 of the viscous
// time-step limit (Poiseuille and Couette at 0.55 of it blow up in 50
// steps, Taylor-Green at 0.045 at t = 1.37 s; `sph check` warns past 1/50;
// Monaghan's viscosity counts as nu = alpha h c0 / 8). The default stays
// leap_frog: use this scheme where c dt/h stays below about 0.8 (the
// shipped water cases run at 0.15) and the viscosity is weak.
#pragma once

#include "sph/integrators/integrator_support.hpp"

namespace sph {

template <int D>
struct TwoStepLeapFrog {
  static constexpr const char* name = "two_step_leap_frog";
  static constexpr const char* summary =
      "two-step leap-frog with a Robert-Asselin filter: one neighbour walk per step, acoustic limit c dt/h ~ 0.86";
  // sph check warns past this fraction of the viscous limit (above).
  static constexpr AcousticClass kAcousticClass = AcousticClass::kTwoStepLeapFrog;
  static constexpr const char* kUnstable = nullptr;
  static constexpr Real kViscousFraction = 0.02;
  static constexpr bool kDensityRateApart = false;
  static constexpr Real kFilter = 0.05;  // Robert-Asselin nu
  static constexpr FieldSet finishes() { return 0; }
  static FieldSet needs(bool density) {
    return fieldBit(kFieldVPrev) | (density ? fieldBit(kFieldRhoPrev) : FieldSet(0));
  }

  // Index of the last finished step (set by the Scene before each step): 0,
  // the first step, which has no vbar^{n-1} yet.
  long step = 0;

  template <class Evaluate, class Constrain, class DensityRate>
  void advance(Particles<D>& P, Real dt, Evaluate&& evaluate, Constrain&& constrain, DensityRate&&) const {
    const std::size_t n = P.size(), nFluid = P.fluidCount();
    const bool density = !P.drho.empty(), start = step == 0;
    const Real span = start ? dt : 2 * dt, nu = start ? 0 : kFilter;
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      if (density) {
        const Real now = P.rho[i], next = (start ? now : P.rhoPrev[i]) + span * P.drho[i];
        P.rhoPrev[i] = now + nu * (P.rhoPrev[i] - 2 * now + next);
        P.rho[i] = next;
      }
      if (i >= nFluid) continue;
      const Vec<D> now = P.v[i], next = (start ? now : P.vPrev[i]) + span * P.a[i];
      P.x[i] += dt * P.driftVelocity(i, now) + (dt * dt / 2) * P.a[i];
      P.vPrev[i] = now + nu * (P.vPrev[i] - 2 * now + next);
      P.v[i] = next;
      constrain(P, i);
    }
    evaluate();
  }

  void finish(Particles<D>&, std::size_t, Real) const {}
};

}  // namespace sph
