// Laplacian viscosity with velocity differences (Mueller, Charypar & Gross
// 2003, "Particle-based fluid simulation for interactive applications", eq. 14):
//
//   a_i = (mu / rho_i) sum_j m_j (v_j - v_i) / rho_j  lap W(r_ij, h)
//
// mu: dynamic viscosity. With the Mueller kernel set, lap W is the Laplacian
// of the viscosity kernel (positive inside the support, so the term always
// damps relative motion); other kernels use their own Laplacian.
#pragma once

#include "sph/terms/pair_accelerations.hpp"

namespace sph {

template <class Kernel>
struct LaplacianViscosity {
  Kernel kernel;
  Real mu;
  static constexpr bool isForceDensity = false;

  template <int D>
  Vec<D> pair(const PairContext<D>& c, const Particles<D>& P) const {
    return (mu * P.m[c.j] / (P.rho[c.i] * P.rho[c.j]) * kernel.laplacianW(c.r)) *
           (P.v[c.j] - P.v[c.i]);
  }
};

}  // namespace sph
