// Laplacian viscosity with velocity differences (Mueller, Charypar & Gross
// 2003, "Particle-based fluid simulation for interactive applications", eq. 14):
//
//   a_i = (mu / rho_i) sum_j m_j (v_j - v_i) / rho_j  lap W(r_ij, h)
//
// mu: dynamic viscosity. "lap W" must be positive for the term to damp
// relative motion. With the Mueller kernel set it is the Laplacian of the
// viscosity kernel, designed for that. A bell-shaped kernel's true Laplacian
// is negative in its core and would amplify relative motion, so the other
// kernels use the Brookshaw (1985) / Morris, Fox & Zhu (1997) estimate
//   lap W ~ -2 (dW/dr) / r,
// positive and finite at r = 0, the standard SPH Laplacian operator.
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/kernels/muller.hpp"
#include "sph/pair_loop.hpp"

namespace sph {

// The positive Laplacian the viscosity uses, per kernel: -2 (dW/dr)/r of the
// pair (its r -> 0 limit for coincident particles), or Mueller's viscosity
// kernel.
template <class Kernel, int D>
Real viscosityLaplacian(const Kernel&, const Pair<D>& c) {
  return -2 * c.dWdr_r;
}

template <int D>
Real viscosityLaplacian(const Muller<D>& k, const Pair<D>& c) {
  return k.laplacianW(c.r);
}

// kWall: j is a wall particle, seen with the velocity it shows the fluid
// (vWall: no-slip or free-slip, boundaries/).
template <class Kernel, bool kWall = false>
struct LaplacianViscosity {
  static constexpr unsigned bit = term_bits::kLaplacianViscosity;
  static constexpr unsigned writes = rates::kAcceleration;
  Kernel kernel;
  Real mu;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    const Vec<D>& vj = kWall ? P.vWall[c.j] : P.v[c.j];
    r.a += (mu * P.m[c.j] / (P.rho[c.i] * P.rho[c.j]) * viscosityLaplacian(kernel, c)) * (vj - P.v[c.i]);
  }
};

}  // namespace sph
